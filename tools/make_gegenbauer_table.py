#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write the Chebyshev table of the Gamma-function ratio in src/hcimpact/numerics/modified_cc.f90.

The whole-contact rule of the closed forms (hcimpact_modified_cc's sym_m0) needs the
complete moment of the symmetric weight (1 - x^2)^(-alpha) on [-1, 1],

    M_0 = B(1/2, a) = sqrt(pi) Gamma(a) / Gamma(a + 1/2) = sqrt(pi) f(a) / a,
    f(a) = Gamma(a + 1) / Gamma(a + 1/2),     a = 1 - alpha = 1/(n + 1) in (0, 1],

to about 1e-18 relative. f is analytic on a disc around [0, 1] (its nearest singularity
is the pole a = -1), so its Chebyshev series in t = 2a - 1 converges like 5.8**-k:
NTERMS = 26 coefficients leave a truncation below 1e-20. The coefficients c_0 and c_1 are
stored as hi + lo (they carry the value); the others as doubles (their sum is 0.023, so
their rounding and that of a Clenshaw sum in double stay below 1e-17 of f).

The block between "! BEGIN GENERATED (tools/make_gegenbauer_table.py)" and
"! END GENERATED (tools/make_gegenbauer_table.py)" is replaced; every value comes from
mpmath at 50 digits, rounded once. The script checks the truncated series against
mpmath at 2001 points of [0, 1] and fails if it is off by more than 1e-18 (the rounding of the stored
coefficients: 5e-19).

Usage: python3 tools/make_gegenbauer_table.py [path/to/modified_cc.f90]
"""
import os
import sys

import mpmath as mp

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "test",
                                "reference"))
from doubles import nearest_double as nearest, split_double as split  # noqa: E402

mp.mp.dps = 50
NTERMS = 26
BEGIN = "! BEGIN GENERATED (tools/make_gegenbauer_table.py)"
END = "! END GENERATED (tools/make_gegenbauer_table.py)"


def f(a):
    return mp.gamma(a + 1) / mp.gamma(a + mp.mpf(1) / 2)


def chebyshev(n_nodes=80):
    """Chebyshev coefficients of f(a(t)), a = (t + 1)/2, from the Chebyshev-Gauss nodes."""
    nodes = [mp.cos(mp.pi * (j + mp.mpf(1) / 2) / n_nodes) for j in range(n_nodes)]
    vals = [f((x + 1) / 2) for x in nodes]
    coef = []
    for k in range(NTERMS):
        s = mp.fsum(vals[j] * mp.cos(mp.pi * k * (j + mp.mpf(1) / 2) / n_nodes)
                    for j in range(n_nodes))
        coef.append(2 * s / n_nodes)
    coef[0] /= 2
    return coef


def fortran(d):
    text = repr(d)
    if "e" not in text and "." not in text:
        text += ".0"
    return text + "_wp"


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "src", "hcimpact", "numerics", "modified_cc.f90")
    coef = chebyshev()
    # check the truncated series with the stored doubles
    stored = [mp.mpf(nearest(c)) for c in coef]
    hi0, lo0 = split(coef[0])
    hi1, lo1 = split(coef[1])
    stored[0] = mp.mpf(hi0) + mp.mpf(lo0)
    stored[1] = mp.mpf(hi1) + mp.mpf(lo1)
    worst = 0
    for i in range(2001):
        a = mp.mpf(i) / 2000
        t = 2 * a - 1
        s = mp.fsum(stored[k] * mp.chebyt(k, t) for k in range(NTERMS))
        worst = max(worst, abs(s / f(a) - 1))
    if worst > mp.mpf("1e-18"):
        sys.exit(f"make_gegenbauer_table.py: series off by {mp.nstr(worst, 3)}")
    lines = [BEGIN,
             "   !> Chebyshev coefficients of Gamma(a + 1)/Gamma(a + 1/2) in t = 2a - 1 on",
             f"   !> a in [0, 1] (largest relative error of the series {mp.nstr(worst, 2)})",
             f"   integer, parameter :: gamma_ratio_terms = {NTERMS}",
             f"   real(wp), parameter :: gamma_ratio_c0(2) = [{fortran(hi0)}, {fortran(lo0)}]",
             f"   real(wp), parameter :: gamma_ratio_c1(2) = [{fortran(hi1)}, {fortran(lo1)}]",
             f"   real(wp), parameter :: gamma_ratio_c(2:{NTERMS - 1}) = [ &"]
    items = [fortran(nearest(c)) for c in coef[2:]]
    for i in range(0, len(items), 3):
        last = i + 3 >= len(items)
        lines.append("      & " + ", ".join(items[i:i + 3]) + (" ]" if last else ", &"))
    lines.append(END)
    with open(path) as fh:
        text = fh.read()
    if BEGIN not in text:
        sys.exit(f"make_gegenbauer_table.py: no generated block in {path}")
    head = text[:text.index(BEGIN)]
    tail = text[text.index(END) + len(END):]
    with open(path, "w") as fh:
        fh.write(head + "\n".join(lines) + tail)
    print(f"make_gegenbauer_table.py: {path} ({NTERMS} terms, max error {mp.nstr(worst, 3)})")


if __name__ == "__main__":
    main()
