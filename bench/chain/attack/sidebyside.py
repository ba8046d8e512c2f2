# SPDX-License-Identifier: Apache-2.0
"""Contacts of one random case side by side: python3 sidebyside.py SEED [rtol_ref] [method] [lib rtol]"""
import sys, math
import numpy as np
import hcimpact, ref
from run_random import draw
seed = int(sys.argv[1])
rr = float(sys.argv[2]) if len(sys.argv) > 2 else 1e-12
meth = sys.argv[3] if len(sys.argv) > 3 else "auto"
lr = float(sys.argv[4]) if len(sys.argv) > 4 else 1e-10
case = draw(seed)
r = hcimpact.chain(**case, rtol=lr, method=meth)
s = ref.System(case["masses"], case["velocities"], case["gaps"], case["stiffness"], case["exponent"],
               case["damping"], case["wall_left"], case["wall_right"], case["gravity"])
q = ref.simulate(s, case["t_end"], rtol=rr)
print("lib", r.n_contacts, r.method_used, "ref", len(q["contacts"]))
L = sorted(r.contacts, key=lambda c: (c["t_start"], c["pair"]))
for i in range(max(len(L), len(q["contacts"]))):
    a = L[i] if i < len(L) else None
    b = q["contacts"][i] if i < len(q["contacts"]) else None
    sa = ("%2d %.12e %.12e %+.6e %+.6e %.3e %d" % (a["pair"], a["t_start"], a["t_end"], a["approach_speed"], a["separation_speed"], a["max_deformation"], a["method"])) if a is not None else "-"
    sb = ("%2d %.12e %.12e %+.6e %+.6e %.3e" % (b["pair"], b["t_start"], b["t_end"], b["approach_speed"], b.get("separation_speed", math.nan), b["max_def"])) if b is not None else "-"
    print("L", sa); print("R", sb)
print("vel lib", r.velocities); print("vel ref", q["vel"])
print("pos lib", r.positions); print("pos ref", q["pos"])
