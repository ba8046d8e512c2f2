# SPDX-License-Identifier: Apache-2.0
"""Which side is right: the reference at two tolerances (and Radau), the library at several rtol.
python3 converge.py SEED [SEED...]"""
import sys
import numpy as np
import hcimpact, ref
from run_random import draw
for seed in map(int, sys.argv[1:]):
    case = draw(seed)
    s = ref.System(case["masses"], case["velocities"], case["gaps"], case["stiffness"], case["exponent"],
                   case["damping"], case["wall_left"], case["wall_right"], case["gravity"])
    qs = {}
    for rr, meth in ((1e-12, "DOP853"), (1e-13, "DOP853")):
        qs[(rr, meth)] = ref.simulate(s, case["t_end"], rtol=rr, method=meth)
    base = qs[(1e-13, "DOP853")]
    vscale = max(np.max(np.abs(s.v0)), 1e-300)
    def at(vel, pos, t0, tc):
        dt = tc - t0
        return vel + s.g * dt
    print(f"seed {seed}: ref end {base['t']}, contacts {len(base['contacts'])}")
    tc = base["t"] if case["t_end"] is None else case["t_end"]
    for k, q in qs.items():
        print("  ref", k, "t", q["t"], "dv %.2e" % (np.max(np.abs(at(q["vel"], 0, q["t"], max(tc, q['t'])) - at(base["vel"], 0, base["t"], max(tc, q['t'])))) / vscale))
    for meth in ("auto", "integrated"):
        for integ in ("bdf", "adams"):
            for lr in (1e-8, 1e-10, 1e-12):
                try:
                    r = hcimpact.chain(**case, rtol=lr, method=meth, integrator=integ)
                except Exception as e:
                    print("  lib", meth, integ, lr, "EXC", e); continue
                T = max(r.time, base["t"])
                dv = np.max(np.abs(at(r.velocities, 0, r.time, T) - at(base["vel"], 0, base["t"], T))) / vscale
                print(f"  lib {meth:10s} {integ} rtol {lr:.0e} t {r.time:.9g} contacts {r.n_contacts} dv {dv:.2e} ({dv/lr:.0f} rtol) E {r.energy_error:.1e} {r.method_used}")
