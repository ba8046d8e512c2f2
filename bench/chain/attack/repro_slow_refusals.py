# SPDX-License-Identifier: Apache-2.0
"""Defect: inputs that can never finish with t_end=None (or t_end far beyond the rest)
are reported only after the default limits (1e8 contacts or 1e8 steps): about 100 s
for contacts, a quarter of an hour or more for steps. Each is shown here with a small
limit (instant), and the time for 1e6 (events) / 1e5 (steps) to extrapolate."""
import time
import hcimpact

C = 1e9
cases = {
    "one ball between two walls, elastic, no gravity": (
        dict(masses=[1.0], velocities=[1.0], wall_left={"stiffness": C, "gap": 0.01},
             wall_right={"stiffness": C, "gap": 0.01}), "max_events", 10**6),
    "elastic ball bouncing on a floor (b = 0)": (
        dict(masses=[1.0], velocities=[0.0], wall_left={"stiffness": C, "gap": 0.01},
             gravity=-9.81), "max_steps", 10**5),
    "two touching elastic balls between touching walls, gravity": (
        dict(masses=[1.0, 1.0], velocities=[0.0, 0.0], gaps=[0.0], stiffness=C,
             wall_left={"stiffness": C}, wall_right={"stiffness": C}, gravity=-9.81),
        "max_steps", 10**5),
    "three touching balls, exponent 1e-3 (accepted: >= 1e-6)": (
        dict(masses=[1.0] * 3, velocities=[1.0, 0, 0], gaps=[0, 0], stiffness=C, exponent=1e-3),
        "max_steps", 10**5),
    "damped ball on a floor, at rest at 2.25 s, t_end = 1e300": (
        dict(masses=[1.0], velocities=[0.0], wall_left={"stiffness": C, "gap": 0.01, "damping": 0.5},
             gravity=-9.81, t_end=1e300), "max_steps", 10**6),
}
for name, (kw, limit, value) in cases.items():
    t0 = time.time()
    try:
        r = hcimpact.chain(**kw, **{limit: value})
        print(f"{name}: {r} rested {r.rested}", end="")
    except hcimpact.HcimpactError as e:
        print(f"{name}: {type(e).__name__}: {str(e)[:100]}", end="")
    dt = time.time() - t0
    print(f"\n    {limit}={value}: {dt:.2f} s -> default 1e8: about {dt * 1e8 / value:.0f} s")
