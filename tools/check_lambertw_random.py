#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""An independent spot check of hcimpact's Lambert W on fresh random inputs.

The accuracy tests read test/reference/lambertw.csv (make_lambertw.py). This script
draws other points with another seed and another sampler, evaluates the four
functions through the Python binding (so through the C API), and compares them with
mpmath's lambertw at the exact double inputs, with enough digits for each (the 1 + W
forms from t need about -log10(t) + 70 digits next to the branch point). It prints
the largest and median error in ulps per family; nothing is asserted.

    HCIMPACT_LIBRARY=build/<dir>/libhcimpact.so python3 tools/check_lambertw_random.py [N]

N points per family (default 1500; about a minute). Needs a shared library build
(-DBUILD_SHARED_LIBS=ON) and mpmath.
"""

import math
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import hcimpact as hc  # noqa: E402
from mpmath import e, exp, lambertw, mp, mpf  # noqa: E402


def ulp(x):
    """Spacing of the doubles at |x| (2**-1074 at zero and below the normal range)."""
    m, ex = math.frexp(abs(x))
    return max(math.ldexp(1.0, ex - 53), math.ldexp(1.0, -1074)) if x != 0 else math.ldexp(1.0, -1074)


def ulp_error(got, ref):
    ref = ref.real
    return float(abs(mpf(got) - ref) / ulp(float(ref)))


def main():
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 1500
    rng = random.Random(20261121)
    errors = {}

    def record(name, got, ref):
        errors.setdefault(name, []).append(ulp_error(got, ref))

    def log_uniform(a, b):
        return math.exp(rng.uniform(math.log(a), math.log(b)))

    mp.dps = 60
    for _ in range(count):
        # next to the branch point: z = -1/e + d rounded, kept if it lies in the domain
        with mp.workdps(80):
            z = float(-1 / e + log_uniform(1e-17, 0.2))
            if mpf(z) + 1 / e > 0:
                record("W0 near -1/e", hc.lambert_w0(z), lambertw(mpf(z), 0))
                record("W-1 near -1/e", hc.lambert_wm1(z), lambertw(mpf(z), -1))
        z = rng.uniform(-0.36787944117144, 0.0)
        record("W0 z in (-1/e, 0)", hc.lambert_w0(z), lambertw(mpf(z), 0))
        record("W-1 z in (-1/e, 0)", hc.lambert_wm1(z), lambertw(mpf(z), -1))
        z = log_uniform(1e-300, 1e300)
        record("W0 z > 0", hc.lambert_w0(z), lambertw(mpf(z), 0))
        z = -log_uniform(1e-300, 0.3)
        record("W-1 -z in [1e-300, 0.3]", hc.lambert_wm1(z), lambertw(mpf(z), -1))
        z = -log_uniform(1e-300, 1e-3)
        record("W0 -z in [1e-300, 1e-3]", hc.lambert_w0(z), lambertw(mpf(z), 0))
    for _ in range(count):
        t = log_uniform(1e-300, 1e300)
        with mp.workdps(70 + int(max(0.0, -math.log10(t)))):
            if t < 1e250:
                z = -exp(-1 - mpf(t))
                record("1+W0(t)", hc.lambert_w0p1(t), 1 + lambertw(z, 0))
                record("1+W-1(t)", hc.lambert_wm1p1(t), 1 + lambertw(z, -1))
            else:
                # 1 + W0 = 1 - |z| (1 + ...) with |z| < 1e-300: the double 1
                record("1+W0(t)", hc.lambert_w0p1(t), mpf(1))
    for name, values in errors.items():
        values.sort()
        print(f"{name:26s} n = {len(values):5d}  max {values[-1]:.3f}  median "
              f"{values[len(values) // 2]:.3f} ulp")


if __name__ == "__main__":
    main()
