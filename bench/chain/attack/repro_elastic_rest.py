# SPDX-License-Identifier: Apache-2.0
"""Defect: an ELASTIC ball (damping 0) released touching a floor under gravity is
reported at rest (rested=True, velocity 0, at the static equilibrium) with energy
'dissipated' although b = 0 dissipates nothing. The true motion is an undamped
oscillation about the equilibrium between x = 0 and about twice its deformation, for
ever (energy conserved). The reference (ref.py, SciPy DOP853 rtol 1e-12) shows the
oscillation at the same times."""
import numpy as np
import hcimpact
import ref

m, c, n, g = 1.0, 1e9, 1.5, -9.81
wall = {"stiffness": c, "exponent": n, "damping": 0.0, "gap": 0.0}
xstar = (m * -g / c) ** (1 / n)          # static deformation
print("static deformation x* = %.6e m" % xstar)
for t_end in (None, 1e-4, 3.3e-4, 1e-2):
    r = hcimpact.chain([m], [0.0], wall_left=wall, gravity=g, t_end=t_end)
    print(f"t_end={t_end}: time {r.time:.4g} rested {r.rested} rest_time {r.rest_time:.3g} "
          f"x {r.positions[0]:.6e} v {r.velocities[0]:.3e} dissipated {r.dissipated:.3e} J "
          f"energy_error {r.energy_error:.1e} steps {r.counters['steps']}")
    if t_end is not None:
        s = ref.System([m], [0.0], wall_left=wall, gravity=g)
        q = ref.simulate(s, t_end, rtol=1e-12)
        print(f"   reference: x {q['pos'][0]:.6e} v {q['vel'][0]:.3e} "
              f"dissipated {q['dissipated']:.1e}")
# the same ball 1 nm above the floor: not 'at rest' (runs to the step limit)
try:
    r = hcimpact.chain([m], [0.0], wall_left=dict(wall, gap=1e-9), gravity=g, max_steps=200000)
    print("gap 1 nm:", r, r.rested)
except hcimpact.HcimpactError as e:
    print("gap 1 nm:", e)
