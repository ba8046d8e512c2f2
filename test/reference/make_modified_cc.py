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

* ``sym n y k Q``: the moments of the symmetric weight of the whole-contact rule,
  Q_k(y) = int_y^1 (1 - x^2)^(-alpha) T_k(x) dx, alpha = n/(n+1) (n the double),
  k = 0 .. 48, for y = -1 (the complete moments M_k) and y in SYM_POINTS: from
  M_0 = sqrt(pi) Gamma(1 - alpha)/Gamma(3/2 - alpha), Q_0(y) = M_0/2 - y 2F1(1/2,
  alpha; 3/2; y^2) and the three-term recurrence of hcimpact_modified_cc at 90 digits
  (its errors damp), each (n, y) checked at k = 0, 1, 2, 7, 24, 48 to 1e-30 against
  an independent route: the closed form of M_k (Gamma functions) for y = -1, else
  mpmath.quad of sin(theta)^(1 - 2 alpha) cos(k theta) over [0, acos y] (theta =
  v^(1/(2 - 2 alpha)) removes the end singularity).

    python3 test/reference/make_modified_cc.py > test/reference/modified_cc.csv

Requires mpmath only. The values are printed to 25 significant digits.
"""

import sys

from mpmath import mp, mpf, hyp2f1, digamma, exp, quad, factorial, gamma, sqrt, pi, acos, \
    sin, cos, chebyt, rgamma

mp.dps = 90

EXPONENTS = ["0.1", "0.5", "1", "1.5", "2", "3", "7", "12"]
SHARES = ["1", "0.75", "0.3", "0.01", "0.0005"]
INTEGRAL_SHARES = ["1", "0.6", "0.05"]
MAX_DEGREE = 48
SYM_POINTS = ["-1", "-0.4", "0", "0.3", "0.5", "0.6", "0.8", "0.95"]


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


def symmetric_moments(n, y):
    """Q_k(y), k = 0 .. MAX_DEGREE, of (1 - x^2)^(-alpha), alpha = n/(n+1)."""
    alpha = n / (n + 1)
    nu = 1 - 2 * alpha
    m0 = sqrt(pi) * gamma(1 - alpha) / gamma(mpf(3) / 2 - alpha)
    if y == -1:
        q = [m0, mpf(0)]
        s = mpf(0)
    else:
        q = [m0 / 2 - y * hyp2f1(mpf(1) / 2, alpha, mpf(3) / 2, y * y)]
        s = (1 - y * y) ** (1 - alpha)
        q.append(s / (nu + 1))
    for k in range(1, MAX_DEGREE):
        q.append((2 * s * chebyt(k, y) + (k - 1 - nu) * q[k - 1]) / (k + 1 + nu))
    # an independent route for some k: the closed form of M_k (y = -1), else the theta
    # integral with its singularity taken out
    mp.dps = 50
    p = 1 / (nu + 1)
    top = acos(y) ** (nu + 1)
    for k in (0, 1, 2, 7, 24, 48):
        if y == -1:
            check = (pi * cos(k * pi / 2) * gamma(nu + 1) / 2 ** nu * rgamma(1 + (nu + k) / 2)
                     * rgamma(1 + (nu - k) / 2))
        else:
            check = quad(lambda v: sin(v ** p) ** nu * cos(k * v ** p) * p * v ** (p - 1)
                         if v > 0 else (mpf(0) if nu != 0 else p), [0, top / 2, top])
        if abs(check - q[k]) > mpf(10) ** -30 * abs(q[0]):
            sys.exit(f"sym n={n} y={y} k={k}: recurrence {q[k]} and quadrature {check}")
    mp.dps = 90
    return q


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
    print("# sym n y k Q_k(y): moments of (1 - x^2)^(-alpha) on [y, 1], alpha = n/(n+1)")
    for n in EXPONENTS:
        for y_text in SYM_POINTS:
            for k, value in enumerate(symmetric_moments(mpf(float(n)), mpf(float(y_text)))):
                print(f"sym {n} {y_text} {k} {text(value)}")


if __name__ == "__main__":
    main()
