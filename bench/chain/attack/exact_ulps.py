# SPDX-License-Identifier: Apache-2.0
"""The exact path against the closed forms of one impact, in ulps: random pairs
(masses, laws, gaps, g), a ball on a wall (g = 0), and a dilute row of three where
1 hits 2, then 2 hits 3 (each contact isolated)."""
import math
import numpy as np
import hcimpact


def ulps(a, b, scale=None):
    s = abs(b) if scale is None else scale
    return abs(a - b) / (math.ulp(s) if s > 0 else 5e-324)


rng = np.random.default_rng(2026)
worst = {}
count = {"pairs": 0, "walls": 0, "rows": 0}
not_exact = []


def note(key, value, info):
    if value > worst.get(key, (-1,))[0]:
        worst[key] = (value, info)


for trial in range(400):
    m1, m2 = 10 ** rng.uniform(-3, 0, 2)
    c = 10 ** rng.uniform(4, 10)
    n = [1.0, 1.5, 2.0, rng.uniform(1, 3)][trial % 4]
    b = 0.0 if trial % 3 == 0 else 10 ** rng.uniform(-2, 0)
    v1, v2 = rng.uniform(0.05, 1), rng.uniform(-1, 0.04)
    gap = [0.0, 10 ** rng.uniform(-7, -5), 10 ** rng.uniform(-3, -2)][trial % 3]
    g = 0.0 if trial % 2 else rng.uniform(-20, 20)
    r = hcimpact.chain([m1, m2], [v1, v2], gaps=[gap], stiffness=c, exponent=n, damping=b,
                       gravity=g)
    if r.method_used != "exact":
        not_exact.append(("pair", trial, r.method_used))
        continue
    count["pairs"] += 1
    V = v1 - v2
    mu = hcimpact.effective_mass(m1, m2)
    q = hcimpact.impact(mass=mu, stiffness=c, exponent=n, damping=b, velocity=V)
    w1, w2 = hcimpact.two_body_velocities(m1, m2, v1, v2, q.restitution)
    k = r.contacts[0]
    info = (trial, m1, m2, c, n, b, v1, v2, gap, g)
    t0 = gap / V
    note("t_start", ulps(k["t_start"], t0), info)
    note("duration", ulps(k["t_end"] - k["t_start"], q.contact_time, k["t_end"]), info)
    note("sep", ulps(k["separation_speed"], q.restitution * V), info)
    note("xmax", ulps(k["max_deformation"], q.max_compression), info)
    note("peak", ulps(k["peak_force"], q.peak_force), info)
    sc = max(abs(w1), abs(w2))
    # final velocities: the library's plus g t against the closed forms' plus g t
    note("v_final", max(ulps(r.velocities[0] - g * r.time, w1, sc),
                        ulps(r.velocities[1] - g * r.time, w2, sc)), info)

for trial in range(200):
    m = 10 ** rng.uniform(-3, 0)
    c = 10 ** rng.uniform(4, 10)
    n = [1.0, 1.5, 2.0, rng.uniform(1, 3)][trial % 4]
    b = 0.0 if trial % 3 == 0 else 10 ** rng.uniform(-2, 0)
    v = -rng.uniform(0.05, 1)
    gap = [0.0, 10 ** rng.uniform(-7, -5), 10 ** rng.uniform(-3, -2)][trial % 3]
    r = hcimpact.chain([m], [v], wall_left={"stiffness": c, "exponent": n, "damping": b, "gap": gap})
    if r.method_used != "exact":
        not_exact.append(("wall", trial, r.method_used))
        continue
    count["walls"] += 1
    q = hcimpact.impact(mass=m, stiffness=c, exponent=n, damping=b, velocity=-v)
    k = r.contacts[0]
    info = (trial, m, c, n, b, v, gap)
    note("wall_v", ulps(r.velocities[0], -q.restitution * v), info)
    note("wall_duration", ulps(k["t_end"] - k["t_start"], q.contact_time, k["t_end"]), info)
    note("wall_xmax", ulps(k["max_deformation"], q.max_compression), info)

for trial in range(200):
    m = 10 ** rng.uniform(-3, 0, 3)
    c = 10 ** rng.uniform(4, 10, 2)
    b = np.where(rng.random(2) < 0.5, 0.0, 10 ** rng.uniform(-2, 0, 2))
    gaps = [10 ** rng.uniform(-3, -2), 0.5]
    v = [rng.uniform(0.1, 1), 0.0, 0.0]
    r = hcimpact.chain(m, v, gaps=gaps, stiffness=c, exponent=1.5, damping=b)
    if r.method_used != "exact":
        not_exact.append(("row", trial, r.method_used))
        continue
    count["rows"] += 1
    q = hcimpact.impact(mass=hcimpact.effective_mass(m[0], m[1]), stiffness=c[0], damping=b[0], velocity=v[0])
    a1, a2 = hcimpact.two_body_velocities(m[0], m[1], v[0], 0.0, q.restitution)
    expect = [a1]
    if a2 > 0:
        q2 = hcimpact.impact(mass=hcimpact.effective_mass(m[1], m[2]), stiffness=c[1], damping=b[1], velocity=a2)
        b2, b3 = hcimpact.two_body_velocities(m[1], m[2], a2, 0.0, q2.restitution)
        expect += [b2, b3]
    if len(expect) < 3 or expect[0] > expect[1]:
        continue   # 1 meets 2 again: not the simple row
    sc = max(map(abs, expect))
    note("row_v", max(ulps(x, y, sc) for x, y in zip(r.velocities, expect)), (trial, m, c, b, gaps, v))

for k, (val, info) in worst.items():
    print(f"{k:14s} worst {val:8.1f} ulp  at {info}")
print("counts", count, "not exact:", len(not_exact), not_exact[:10])
