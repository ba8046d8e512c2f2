# SPDX-License-Identifier: Apache-2.0
"""Smaller defects, each a few lines (see the report):
1. rtol >= 0.5 (accepted: (0, 1)): contacts happen (the velocities change, CVODE took
   steps) but none is recorded, n_contacts 0, and method_used says 'exact' even with
   method='integrated'.
2. method_used 'exact' for runs whose cluster CVODE integrated when its contacts are
   still in progress at t_end (contacts in progress are neither listed nor counted).
3. t_end = 5e-324 (positive, accepted) with a cluster at t = 0: CVODE's CV_ILL_INPUT.
4. gaps whose sum exceeds the double range: success with an infinite position.
5. gravity -5e-324 toward a floor 1 cm below: 'no contact can happen again' at t = 0,
   though the ball lands at t = sqrt(2 * 0.01 / 5e-324) = 6.4e160 s (representable).
"""
import hcimpact
from run_random import draw

C = 1e9
r = hcimpact.chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness=C, rtol=0.9, method="integrated")
print("1.", r, "contacts", r.n_contacts, "steps", r.counters["steps"], "v", r.velocities)
case = draw(43)
r = hcimpact.chain(**case)
print("2.", r, r.counters)
try:
    r = hcimpact.chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness=C, t_end=5e-324)
    print("3.", r)
except hcimpact.HcimpactError as e:
    print("3.", type(e).__name__, e)
r = hcimpact.chain([1, 1, 1], [1, 0, -1], gaps=[1.7e308, 1.7e308], stiffness=C)
print("4.", r, "positions", r.positions)
r = hcimpact.chain([1], [0], wall_left={"stiffness": C, "gap": 0.01, "damping": 0.5}, gravity=-5e-324)
print("5.", r, "contacts", r.n_contacts)
