#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Reference integrals of the tanh-sinh quadrature tests (issue #3).

Prints every integral that test/unit/test_quadrature.f90 hard-codes, at 36
significant digits, from its closed form; each is checked against
``mpmath.quad`` at 50 digits (the script stops if they differ by more than
1e-20 relative: mpmath's own quadrature is slow to converge on the strongest
endpoint singularities, and 1e-20 is far below the tests' tolerances).  Parameters
that the Fortran integrands hold as doubles (0.001, 0.3, 1e-300, ...) are taken
here as the same doubles, so the references are the exact integrals of the
integrands as the tests write them.

    python3 test/reference/make_quadrature.py

Requires mpmath only.  Prints, per line: name, value, and the value as the
Fortran literal used in the test (the nearest double is what matters; the
extra digits make the literal round correctly).
"""

import sys

from mpmath import mp, mpf

mp.dps = 50


def double(x):
    """A Python float as the exact binary value it holds."""
    return mpf(float(x))


def cases():
    """(name, closed form, integrand or None when only the closed form is used, a, b)."""
    eps_pole = double(1e-3)
    centre = double(0.3)
    width = double(1e-2)
    k_gauss = double(50)
    offset = double(1e-6)
    bump_at = double(0.35)
    bump_width = double(0.02)
    tiny_b = double(1e-300)
    small_b = double(1e-30)
    huge_b = double(1e300)
    tiny_c = double(1e-300)
    return [
        ("poly7", mpf(2757) / 40,
         lambda x: 3 * x**7 - 2 * x**4 + x - 5, -1, 2),
        ("exp", mp.e - 1, mp.exp, 0, 1),
        ("inv_sqrt", mpf(2), lambda x: 1 / mp.sqrt(1 - x), 0, 1),
        ("sqrt_log", mpf(-4) / 9, lambda x: mp.sqrt(x) * mp.log(x), 0, 1),
        ("log_log", 2 - mp.pi**2 / 6, lambda x: mp.log(x) * mp.log(1 - x), 0, 1),
        ("chebyshev", +mp.pi, lambda x: 1 / mp.sqrt(1 - x * x), -1, 1),
        # x**(-p) with p the double nearest 0.9 (0.99): 1/(1 - p) is not 10
        # (100) in double precision, and mpmath.quad is too slow on it to check
        ("pow_m0p9", 1 / (1 - double(0.9)), None, 0, 1),
        ("pow_m0p99", 1 / (1 - double(0.99)), None, 0, 1),
        ("near_pole", mp.log((1 + eps_pole) / eps_pole),
         lambda x: 1 / (x + eps_pole), 0, 1),
        ("interior_peak",
         (mp.atan((1 - centre) / width) + mp.atan(centre / width)) / width,
         lambda x: 1 / ((x - centre) ** 2 + width**2), 0, 1),
        ("gauss50", mp.sqrt(mp.pi / k_gauss) / 2 * mp.erf(mp.sqrt(k_gauss)),
         lambda x: mp.exp(-k_gauss * x * x), 0, 1),
        ("small_interval", 2 * mp.sqrt(small_b), None, 0, small_b),
        ("late_singularity",
         2 * ((1 + offset) ** mpf(1.5) - offset ** mpf(1.5)) / 3,
         lambda x: mp.sqrt(1 - x + offset), 0, 1),
        ("hidden_bump",
         2 + 100 * bump_width * mp.sqrt(mp.pi) / 2
         * (mp.erf((1 - bump_at) / bump_width) + mp.erf((1 + bump_at) / bump_width)),
         lambda x: 1 + 100 * mp.exp(-(((x - bump_at) / bump_width) ** 2)), -1, 1),
        ("tiny_interval", 2 * mp.sqrt(tiny_b), None, 0, tiny_b),
        ("huge_interval", 2 * huge_b * tiny_c, None, -huge_b, huge_b),
    ]


def main():
    for name, closed, integrand, a, b in cases():
        if integrand is not None:
            # split at the interior peak so that mpmath.quad resolves it
            points = {"interior_peak": [a, double(0.3), b],
                      "hidden_bump": [a, double(0.35), b]}.get(name, [a, b])
            check = mp.quad(integrand, points, maxdegree=10)
            if abs(check - closed) > mpf(10) ** -20 * abs(closed):
                sys.exit(f"{name}: closed form {closed} and quadrature {check} disagree")
        text = mp.nstr(closed, 36, min_fixed=-1, max_fixed=0)
        literal = mp.nstr(closed, 22, min_fixed=-1, max_fixed=0) + "_wp"
        print(f"{name:14s} {text:>44s}   {literal}")


if __name__ == "__main__":
    main()
