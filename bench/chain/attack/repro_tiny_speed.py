# SPDX-License-Identifier: Apache-2.0
"""Defect: two equal bodies touching, approach speed below ~1e-270 m/s: the run leaves
the exact path (method auto) and CVODE either stops ('did not advance the time') or
runs to max_steps (default 1e8: about a quarter of an hour, a hang to the user). The
answer is the closed forms' (equal masses, elastic: the velocities exchange, [0, v]),
which the same call gives for v = 1e-250. Subnormal speeds (5e-324) behave the same,
also with a gap of 1e-300 m."""
import time
import hcimpact

for v, gap in ((1e-250, 0.0), (1e-270, 0.0), (1e-280, 0.0), (1e-300, 0.0), (1e-300, 1e-300),
               (5e-324, 0.0), (5e-324, 1e-300)):
    t0 = time.time()
    try:
        r = hcimpact.chain([1.0, 1.0], [v, 0.0], gaps=[gap], stiffness=1e9, max_steps=100000)
        print(f"v {v:.0e} gap {gap:.0e}: {r.method_used}, velocities/v {r.velocities / v}", end="")
    except hcimpact.HcimpactError as e:
        print(f"v {v:.0e} gap {gap:.0e}: {type(e).__name__}: {str(e)[:110]}", end="")
    print(f"  ({time.time() - t0:.2f} s)")
