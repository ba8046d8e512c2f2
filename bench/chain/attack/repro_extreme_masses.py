# SPDX-License-Identifier: Apache-2.0
"""Two bodies with a gap: always one isolated contact, so method auto should use the
closed forms (doc/chains.md, issue 15: two bodies on the exact path to a few ulps). With
both masses very large or very small the run goes to CVODE instead (method_used
'integrated'), and with subnormal masses CVODE fails though the closed forms
(hcimpact.impact with the effective mass) answer at once: [0, 1] for equal masses."""
import time
import hcimpact

for m in (1e-150, 1e-160, 1e-200, 1e-300, 5e-324, 1e150, 1e160, 1e200, 1e308):
    t0 = time.time()
    try:
        r = hcimpact.chain([m, m], [1.0, 0.0], gaps=[0.01], stiffness=1e9, max_steps=10**6)
        print(f"m {m:.0e}: {r.method_used:10s} v {r.velocities} steps {r.counters['steps']}", end="")
    except hcimpact.HcimpactError as e:
        print(f"m {m:.0e}: {type(e).__name__}: {str(e)[:100]}", end="")
    try:
        q = hcimpact.impact(mass=hcimpact.effective_mass(m, m), stiffness=1e9, velocity=1.0)
        print(f"   closed forms: k = {q.restitution}", end="")
    except hcimpact.HcimpactError as e:
        print(f"   closed forms: {type(e).__name__}", end="")
    print(f" ({time.time() - t0:.2f} s)")
