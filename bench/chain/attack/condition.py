# SPDX-License-Identifier: Apache-2.0
"""Sensitivity of a random case: the reference with the initial velocities perturbed by
1e-10 relative (random signs); the ratio of the output change to 1e-10 is the
amplification a solver at that tolerance can expect. python3 condition.py SEED..."""
import sys
import numpy as np
import ref
from run_random import draw
for seed in map(int, sys.argv[1:]):
    case = draw(seed)
    rng = np.random.default_rng(1)
    outs = []
    for k in range(3):
        v = np.array(case["velocities"])
        if k:
            v = v * (1 + 1e-10 * rng.choice([-1, 1], v.size)) + 1e-10 * np.max(np.abs(v)) * rng.choice([-1, 1], v.size) * (v == 0)
        s = ref.System(case["masses"], v, case["gaps"], case["stiffness"], case["exponent"],
                       case["damping"], case["wall_left"], case["wall_right"], case["gravity"])
        q = ref.simulate(s, case["t_end"], rtol=1e-13)
        T = case["t_end"] if case["t_end"] is not None else 1e3
        outs.append(q["vel"] + s.g * (T - q["t"]))
    vs = np.max(np.abs(case["velocities"]))
    amp = max(np.max(np.abs(outs[k] - outs[0])) for k in (1, 2)) / vs / 1e-10
    print(f"seed {seed}: amplification of 1e-10 in v0: {amp:.3g}")
