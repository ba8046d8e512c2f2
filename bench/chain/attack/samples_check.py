# SPDX-License-Identifier: Apache-2.0
"""Samples (positions, velocities, forces) of random finite-t_end systems against the
reference integrated to each sample time."""
import numpy as np
import hcimpact, ref
from run_random import draw

worst = 0.0
count = 0
for seed in range(0, 60):
    case = draw(seed)
    if case["t_end"] is None:
        continue
    times = np.sort(np.random.default_rng(seed).uniform(0, case["t_end"], 5))
    r = hcimpact.chain(**case, sample_times=times)
    s = ref.System(case["masses"], case["velocities"], case["gaps"], case["stiffness"], case["exponent"],
                   case["damping"], case["wall_left"], case["wall_right"], case["gravity"])
    vs = max(np.max(np.abs(s.v0)), abs(s.g) * case["t_end"])
    for j, t in enumerate(times):
        q = ref.simulate(s, t, rtol=1e-12)
        ev = np.max(np.abs(r.sample_velocities[j] - q["vel"])) / vs
        y = np.concatenate([q["pos"], q["vel"], np.zeros(s.n + 1)])
        f = np.array([s.force(p, *s.x_xd(p, y)) if s.present[p] else 0.0 for p in range(s.n + 1)])
        fs = max(np.max(np.abs(f)), 1e-300)
        ef = np.max(np.abs(r.sample_forces[j] - f)) / fs if np.max(np.abs(f)) > 0 else np.max(np.abs(r.sample_forces[j]))
        count += 1
        if max(ev, ef) > 1e-6:
            print(f"seed {seed} t {t:.6g}: velocity error {ev:.2e}, force error {ef:.2e} (largest force {fs:.3g} N)")
        worst = max(worst, ev)
print(f"samples {count}, worst velocity error {worst:.2e}")
