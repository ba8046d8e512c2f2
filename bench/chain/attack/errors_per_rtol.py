# SPDX-License-Identifier: Apache-2.0
"""Velocity errors per rtol (error / max|v0| / rtol) of BDF and Adams at rtol 1e-8, 1e-10,
1e-12 for seeds of run_random.py, against ref.py (DOP853, rtol 1e-13); amp: the
amplification of a 1e-10 perturbation of v0 (as condition.py); steps: CVODE's steps over
the three rtols. Usage: python3 errors_per_rtol.py 34,42,0,5 (METHOD=integrated for the
whole system integrated; BDFONLY=1; references cached in REFCACHE)."""
import os
import pickle
import sys
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hcimpact, ref
from run_random import draw
seeds = [int(s) for s in sys.argv[1].split(",")]
method = os.environ.get("METHOD", "auto")
cache = os.environ.get("REFCACHE", "/tmp/hcimpact_errors_per_rtol.pkl")
refs = pickle.load(open(cache, "rb")) if os.path.exists(cache) else {}
def sim(case, v):
    s = ref.System(case["masses"], v, case["gaps"], case["stiffness"], case["exponent"],
                   case["damping"], case["wall_left"], case["wall_right"], case["gravity"])
    return s, ref.simulate(s, case["t_end"], rtol=1e-13)
for seed in seeds:
    case = draw(seed)
    if seed not in refs:
        s, q = sim(case, case["velocities"])
        rng = np.random.default_rng(1)
        v = np.array(case["velocities"])
        v = v * (1 + 1e-10 * rng.choice([-1, 1], v.size)) + 1e-10 * np.max(np.abs(v)) * rng.choice([-1, 1], v.size) * (v == 0)
        s2, q2 = sim(case, v)
        T = case["t_end"] if case["t_end"] is not None else 1e3
        o1 = q["vel"] + s.g * (T - q["t"]); o2 = q2["vel"] + s.g * (T - q2["t"])
        amp = np.max(np.abs(o2 - o1)) / np.max(np.abs(case["velocities"])) / 1e-10
        refs[seed] = (s, q, amp)
        pickle.dump(refs, open(cache, "wb"))
    s, q, amp = refs[seed]
    line = f"seed {seed:4d} n={len(case['masses'])} nc {len(q['contacts']):3d} amp {amp:7.2g} |"
    steps = {}
    steps["adams"] = 0
    for integ in (("bdf",) if os.environ.get("BDFONLY") else ("bdf", "adams")):
        steps[integ] = 0
        for rt in (1e-8, 1e-10, 1e-12):
            try:
                r = hcimpact.chain(**case, rtol=rt, integrator=integ, method=method)
            except Exception as e:
                line += f" {integ[0]}{-int(np.log10(rt))}: {'FAIL':>6s}"; continue
            if case["t_end"] is None:
                tc = max(r.time, q["t"]); dt = tc - r.time
                lv = r.velocities + s.g * dt
                qp, qv = ref.advance_free(s, q, tc)
            else:
                tc = case["t_end"]; lv = r.velocities; qv = q["vel"]
            vscale = max(np.max(np.abs(s.v0)), abs(s.g) * tc, 1e-300)
            err = np.max(np.abs(lv - qv)) / vscale
            steps[integ] += r.counters["steps"]
            line += f" {integ[0]}{-int(np.log10(rt))}: {err/rt:6.0f}"
        line += " |"
    line += f" steps b {steps['bdf']} a {steps['adams']}"
    print(line, flush=True)
