#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""References of the modified Clenshaw-Curtis tests (test/unit/test_modified_cc.f90).

Writes test/reference/modified_cc.csv: for the weight w(t) = t^(c-1) on [0, 1],
c = 1/(n+1) taken as the double the Fortran code forms (1/(n+1) rounded once),

* ``moment n s k J``: the modified moments
  J_k(y) = int_-1^y ((1+x)/2)^(c-1) T_k(x) dx, y = 2s - 1, k = 0 .. 48,
  from the exact expansion of T_k(2t-1) in powers of t (integer coefficients)
  integrated term by term, 2 sum_j b_j s^(c+j)/(c+j), at 90 digits (the
  coefficients reach 4^48, so 90 digits leave over 50 after the cancellation);
* ``exp n s 0 I`` and ``recip n s 0 I``: I = int_0^s t^(c-1) F(t) dt with
  F = e^t (series sum_j s^(c+j)/(j! (c+j))) and F = 1/(1+t) (for s = 1 the
  closed form (psi((c+1)/2) - psi(c/2))/2, else the hypergeometric form
  s^c/c 2F1(1, c; c+1; -s)); each is checked to 1e-40 against mpmath.quad after the substitution
  t = v^(1/c), which removes the endpoint singularity.

    python3 test/reference/make_modified_cc.py > test/reference/modified_cc.csv

Requires mpmath only. The values are printed to 25 significant digits.
"""

import sys

from mpmath import mp, mpf, hyp2f1, digamma, exp, quad, factorial

mp.dps = 90

EXPONENTS = ["0.1", "0.5", "1", "1.5", "2", "3", "7", "12"]
SHARES = ["1", "0.75", "0.3", "0.01", "0.0005"]
INTEGRAL_SHARES = ["1", "0.6", "0.05"]
MAX_DEGREE = 48


def exponent_c(n_text):
    """c = 1/(n+1) as the double the Fortran code forms from the double n."""
    return mpf(1.0 / (float(n_text) + 1.0))


def shifted_chebyshev(kmax):
    """Integer coefficients (in powers of t) of T_k(2t - 1), k = 0 .. kmax."""
    polys = [[1], [-1, 2]]
    for k in range(1, kmax):
        # T_(k+1) = 2 (2t - 1) T_k - T_(k-1)
        p, q = polys[k], polys[k - 1]
        new = [0] * (len(p) + 1)
        for j, b in enumerate(p):
            new[j] -= 2 * b
            new[j + 1] += 4 * b
        for j, b in enumerate(q):
            new[j] -= b
        polys.append(new)
    return polys


def moments(c, s, polys):
    """J_k(2s - 1), k = 0 .. len(polys) - 1."""
    return [2 * sum(b * s ** (c + j) / (c + j) for j, b in enumerate(p)) for p in polys]


def integral_exp(c, s):
    total, j = mpf(0), 0
    while True:
        term = s ** (c + j) / (factorial(j) * (c + j))
        total += term
        if abs(term) < mpf(10) ** -80 * abs(total):
            return total
        j += 1


def integral_recip(c, s):
    if s == 1:
        return (digamma((c + 1) / 2) - digamma(c / 2)) / 2
    return s**c / c * hyp2f1(1, c, c + 1, -s)


def checked(name, value, integrand, c, s):
    mp.dps = 50
    # t = v^(1/c) takes the singularity out: int_0^(s^c) F(v^(1/c)) dv / c
    check = quad(lambda v: integrand(v ** (1 / c)), [0, s**c]) / c
    mp.dps = 90
    if abs(check - value) > mpf(10) ** -40 * abs(value):
        sys.exit(f"{name}: {value} and quadrature {check} disagree")
    return value


def text(x):
    return mp.nstr(x, 25, min_fixed=-1, max_fixed=0)


def main():
    polys = shifted_chebyshev(MAX_DEGREE)
    print("# kind n s k value: modified moments J_k(2s-1) of ((1+x)/2)^(c-1), c = 1/(n+1),")
    print("# and int_0^s t^(c-1) F(t) dt for F = exp, 1/(1+t) (make_modified_cc.py)")
    for n in EXPONENTS:
        c = exponent_c(n)
        for s_text in SHARES:
            for k, value in enumerate(moments(c, mpf(float(s_text)), polys)):
                print(f"moment {n} {s_text} {k} {text(value)}")
        for s_text in INTEGRAL_SHARES:
            s = mpf(float(s_text))
            value = checked("exp", integral_exp(c, s), exp, c, s)
            print(f"exp {n} {s_text} 0 {text(value)}")
            value = checked("recip", integral_recip(c, s), lambda t: 1 / (1 + t), c, s)
            print(f"recip {n} {s_text} 0 {text(value)}")


if __name__ == "__main__":
    main()
