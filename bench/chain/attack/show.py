# SPDX-License-Identifier: Apache-2.0
"""Print one random case of run_random.py and run the library alone: python3 show.py SEED"""
import sys, time, json
import hcimpact
from run_random import draw
case = draw(int(sys.argv[1]))
print(json.dumps(case, indent=None))
kw = dict(a.split("=") for a in sys.argv[2:])
t0 = time.time()
r = hcimpact.chain(**case, **{k: (v if k in ("method", "integrator") else float(v)) for k, v in kw.items()})
print(r, time.time() - t0, "s")
print(r.velocities, r.counters, r.message)
