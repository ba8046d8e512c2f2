#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write src/hcimpact/lambertw_tables.f90: Taylor tables for Lambert W near the branch point.

Two analytic functions are tabulated as local Taylor polynomials on a uniform grid of
centres (spacing h, each polynomial used on [xc - h/2, xc + h/2]):

* V(s) = 1 + W(-exp(-1 - s^2/2)), the "1 + W" form as a function of s = +-sqrt(2t)
  (s >= 0: principal branch W0, s < 0: branch W-1). It solves -V - ln(1 - V) = s^2/2,
  so V V' = s (1 - V).
* Y(p) = 1 + W(z) with p = +-sqrt(2 (1 + e z)) (DLMF 4.13): p >= 0 gives W0, p < 0 W-1.
  It solves 1 + (Y - 1) exp(Y) = p^2/2, so Y Y' (p^2/2 - 1) = (Y - 1) p.

At the centre 0 both are series reversions of sigma^2/2 = F(x) with F(x) = sum_k c_k x^k,
done in exact rational arithmetic. Elsewhere the ODE gives the Taylor coefficients by a
recurrence at 60 digits, started from a value of W computed with mpmath.

Each coefficient c0 and c1 is stored as a pair of doubles (hi + lo), the others as one
double. The script also checks every polynomial against mpmath on its interval.

Usage: python3 tools/make_lambertw_tables.py  (writes the module; takes ~1 minute)
"""
from fractions import Fraction
from math import factorial
import os
import sys

import mpmath as mp

mp.mp.dps = 60
W0_SERIES_TERMS = 18   # enough for |z| <= 0.05 (first omitted term below 2**-61 relative)

TABLES = {
    # name: (spacing, first centre index, last centre index, number of coefficients)
    "s": (Fraction(1, 8), -16, 16, 14),     # s in [-2.0625, 2.0625]
    "p": (Fraction(1, 16), -10, 69, 14),    # p in [-0.65625, 4.34375]: z up to 3.1
    "q": (Fraction(1, 2), 9, 128, 14),      # p in [4.25, 64.25]: W0 for z up to 759
    "k": (Fraction(1, 16), 0, 58, 14),      # beta in [0, 3.65625]: restitution k(beta)
    "m": (Fraction(1, 4), 14, 160, 14),     # beta in [3.375, 40.125]: k(beta), coarser
}


def revert(coef, n):
    """Series x(sigma) with sigma = x sqrt(2 F(x)/x^2), F = sum coef[k] x^k (coef[2] = 1/2)."""
    # g(x) = 2 F(x) / x^2 = 1 + ..., sqrt via the recurrence for r^2 = g
    g = [2 * coef[k + 2] for k in range(n)]
    r = [Fraction(1)] + [Fraction(0)] * (n - 1)
    for k in range(1, n):
        acc = g[k] - sum(r[j] * r[k - j] for j in range(1, k))
        r[k] = acc / 2
    # sigma(x) = x r(x): coefficients sig[1..n]
    sig = [Fraction(0)] + r[:n]
    # Reversion by fixed point x = sigma - (sig(x) - x), order by order
    x = [Fraction(0), Fraction(1)] + [Fraction(0)] * (n - 1)
    for order in range(2, n + 1):
        # compose sig(x(sigma)) up to `order`
        comp = [Fraction(0)] * (n + 1)
        power = [Fraction(1)] + [Fraction(0)] * n     # x^0
        for k in range(1, n + 1):
            power = mul(power, x, n)
            if sig[k] != 0:
                comp = [c + sig[k] * p for c, p in zip(comp, power)]
        x[order] -= comp[order]
    return x[: n + 1]


def mul(a, b, n):
    out = [Fraction(0)] * (n + 1)
    for i, ai in enumerate(a[: n + 1]):
        if ai == 0:
            continue
        for j in range(0, n + 1 - i):
            out[i + j] += ai * b[j]
    return out


def restitution_series(n):
    """Taylor series of k(beta) at 0 from h(-k beta) = h(beta), h(u) = u - ln(1 + u):
    sum_{m>=2} k^m beta^(m-2)/m = sum_{m>=2} (-1)^m beta^(m-2)/m, solved order by order."""
    a = [Fraction(1)] + [Fraction(0)] * n

    def residual(coef, order):
        total = Fraction(0)
        power = [Fraction(1)] + [Fraction(0)] * n
        for m in range(1, order + 3):
            power = mul(power, coef, n)
            if m >= 2 and order + 2 - m >= 0:
                total += power[order + 2 - m] / m
        return total - Fraction((-1) ** (order + 2), order + 2)

    for order in range(1, n + 1):
        r0 = residual(a, order)
        trial = list(a)
        trial[order] = Fraction(1)
        r1 = residual(trial, order)
        a[order] = -r0 / (r1 - r0)
    return a


def origin_series(kind, n):
    if kind == "k":
        return [mp.mpf(c.numerator) / c.denominator for c in restitution_series(n)[:n]]
    if kind == "s":      # F(V) = -V - ln(1 - V) = sum_{k>=2} V^k / k
        coef = [Fraction(0), Fraction(0)] + [Fraction(1, k) for k in range(2, n + 3)]
    else:                # F(Y) = 1 + (Y - 1) e^Y = sum_{k>=2} (k - 1) Y^k / k!
        coef = [Fraction(0), Fraction(0)] + [Fraction(k - 1, factorial(k)) for k in range(2, n + 3)]
    return [mp.mpf(c.numerator) / c.denominator for c in revert(coef, n)]


def restitution_value(beta):
    """k(beta) = (1 + W0(-(1 + beta) exp(-(1 + beta))))/beta (seed eq. 21)."""
    z = -(1 + beta) * mp.exp(-(1 + beta))
    return (1 + mp.lambertw(z, 0).real) / beta


def value_at(kind, xc):
    """V(s) (kind s), Y(p) (kinds p, q) or k (kind k) at a non-zero centre, 60 digits."""
    if kind == "k":
        return restitution_value(xc)
    if kind == "s":
        z = -mp.exp(-1 - xc * xc / 2)
    else:
        z = (xc * xc / 2 - 1) / mp.e
    branch = 0 if xc > 0 else -1
    return 1 + mp.lambertw(z, branch).real


def series_mul(a, b, n):
    return [sum(a[i] * b[k - i] for i in range(k + 1)) for k in range(n)]


def restitution_taylor(bc, n):
    """Taylor coefficients of k(beta) at bc > 0 by composing power series in d = beta - bc:
    h(beta) = beta - ln(1 + beta), s = sqrt(2 h), V(s) from the s-table recurrence, k = V/beta."""
    q = 1 + bc
    h = [bc - mp.log(q), 1 - 1 / q] + [mp.mpf(-1) ** k / (k * q**k) for k in range(2, n)]
    # s = sqrt(2h): r^2 = 2h, r0 = sqrt(2 h0), r_k = (2h_k - sum_{j=1..k-1} r_j r_{k-j}) / (2 r0)
    r = [mp.sqrt(2 * h[0])]
    for k in range(1, n):
        r.append((2 * h[k] - sum(r[j] * r[k - j] for j in range(1, k))) / (2 * r[0]))
    v = taylor("s", r[0], n)          # V(r0 + sigma) = sum v_j sigma^j
    sigma = [mp.mpf(0)] + r[1:]       # s(beta) - r0
    comp = [mp.mpf(0)] * n
    power = [mp.mpf(1)] + [mp.mpf(0)] * (n - 1)
    for j in range(n):
        comp = [c + v[j] * p for c, p in zip(comp, power)]
        power = series_mul(power, sigma, n)
    # k = comp / (bc + d)
    k = []
    for m in range(n):
        k.append((comp[m] - (k[m - 1] if m else 0)) / bc)
    return k


def taylor(kind, xc, n):
    if xc == 0:
        return origin_series(kind, n)[:n]
    if kind in ("k", "m"):
        return restitution_taylor(xc, n)
    a = [value_at(kind, xc)]
    # y y' * P(delta) = (y - 1 [p only]) * Q(delta), with
    #   s-table: P = 1, right side s (1 - V)      -> R_k = (s(1-V))_k
    #   p-table: P = xc^2/2 - 1 + xc d + d^2/2, right side (Y - 1) (xc + d)
    A = []      # coefficients of y y'
    for k in range(0, n - 1):
        if kind == "s":
            one_minus = (1 - a[0]) if k == 0 else -a[k]
            prev = 0 if k == 0 else ((1 - a[0]) if k == 1 else -a[k - 1])
            rhs = xc * one_minus + prev
            Ak = rhs
        else:
            ym1 = (a[0] - 1) if k == 0 else a[k]
            prev = 0 if k == 0 else ((a[0] - 1) if k == 1 else a[k - 1])
            rhs = xc * ym1 + prev
            P0, P1, P2 = xc * xc / 2 - 1, xc, mp.mpf(1) / 2
            Ak = rhs
            if k >= 1:
                Ak -= P1 * A[k - 1]
            if k >= 2:
                Ak -= P2 * A[k - 2]
            Ak /= P0
        A.append(Ak)
        # A_k = a0 (k+1) a_{k+1} + sum_{j=1..k} a_j (k-j+1) a_{k-j+1}
        acc = Ak - sum(a[j] * (k - j + 1) * a[k - j + 1] for j in range(1, k + 1))
        a.append(acc / ((k + 1) * a[0]))
    return a


def exact_value(kind, x):
    if kind in ("k", "m"):
        return mp.mpf(1) if x == 0 else restitution_value(x)
    if kind == "s":
        if x == 0:
            return mp.mpf(0)
        return value_at(kind, x)
    if x == 0:
        return mp.mpf(0)
    return value_at(kind, x)


def split(v):
    hi = float(v)
    lo = float(v - mp.mpf(hi))
    return hi, lo


def fortran_real(x):
    r = repr(float(x))
    if "e" in r:
        mant, ex = r.split("e")
        if "." not in mant:
            mant += ".0"
        return f"{mant}e{int(ex)}_wp"
    if "." not in r:
        r += ".0"
    return r + "_wp"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = os.path.join(here, "..", "src", "hcimpact", "lambertw_tables.f90")
    lines = []
    w = lines.append
    w("! SPDX-License-Identifier: Apache-2.0")
    w("! GENERATED by tools/make_lambertw_tables.py: do not edit by hand.")
    w("!> Local Taylor tables of Lambert W near its branch point.")
    w("!>")
    w("!> Row i of a table holds the Taylor coefficients c0, c1, ... at centre xc = i*h, used for")
    w("!> |x - xc| <= h/2; c0 and c1 carry a low part (columns 0 and 1 of the `_lo` table).")
    w("!> `s` tables: V(s) = 1 + W(-exp(-1 - s**2/2)), s = +-sqrt(2t) (+: W0, -: W-1).")
    w("!> `p` tables: W(z) with p = +-sqrt(2(1 + e z)) (+: W0, -: W-1; DLMF 4.13.6).")
    w("!> `q` tables: W0(z) in the same variable p, coarser, for 3 < z < 759.")
    w("!> `k` tables: the restitution k(beta) of the Hunt-Crossley impact, 0 <= beta < 3.66;")
    w("!> `m` tables: the same, coarser, for 3.66 <= beta < 40.125.")
    w("module hcimpact_lambertw_tables")
    w("   use hcimpact_kinds, only : wp")
    w("   implicit none")
    w("   private")
    w("")
    w("   public :: s_ncoef, s_step_inv, s_first, s_last, s_coef, s_lo")
    w("   public :: p_ncoef, p_step_inv, p_first, p_last, p_coef, p_lo")
    w("   public :: q_ncoef, q_step_inv, q_first, q_last, q_coef, q_lo")
    w("   public :: k_ncoef, k_step_inv, k_first, k_last, k_coef, k_lo")
    w("   public :: m_ncoef, m_step_inv, m_first, m_last, m_coef, m_lo")
    w("   public :: w0_series")
    worst_all = {}
    for kind, (h, i0, i1, nterms) in TABLES.items():
        rows, lows = [], []
        worst = 0
        for i in range(i0, i1 + 1):
            xc = mp.mpf(i * h.numerator) / h.denominator
            c = taylor(kind, xc, nterms)
            # check on the interval against the implicit definition
            for frac in (-0.5, -0.37, -0.21, 0.13, 0.29, 0.5):
                x = xc + frac * mp.mpf(h.numerator) / h.denominator
                if x == 0 or (kind == "k" and x < 0):
                    continue      # the k table is used for beta >= 0 only
                ref = exact_value(kind, x)
                d = x - xc
                approx = sum(ck * d**k for k, ck in enumerate(c))
                err = abs(approx - ref) / abs(ref)
                worst = max(worst, err)
            if kind in ("p", "q"):
                c = [c[0] - 1] + list(c[1:])      # tabulate W itself: no rounding of 1 + W
            hi0, lo0 = split(c[0])
            hi1, lo1 = split(c[1])
            rows.append([hi0, hi1] + [float(ck) for ck in c[2:]])
            lows.append([lo0, lo1])
        worst_all[kind] = worst
        print(f"table {kind}: {i1 - i0 + 1} intervals, worst relative truncation {mp.nstr(worst, 3)}",
              file=sys.stderr)
        if worst > 2.0**-62:
            raise SystemExit(f"table {kind}: truncation {worst} too large; use more terms")
        n = i1 - i0 + 1
        w("")
        w(f"   !> Number of Taylor coefficients per interval of the {kind} table")
        w(f"   integer, parameter :: {kind}_ncoef = {nterms}")
        w(f"   !> 1/h for the {kind} table")
        w(f"   real(wp), parameter :: {kind}_step_inv = {float(1 / h)}_wp")
        w(f"   !> Index of the first and last centre of the {kind} table")
        w(f"   integer, parameter :: {kind}_first = {i0}, {kind}_last = {i1}")
        w(f"   !> High parts of the coefficients, one row per centre")
        w(f"   real(wp), parameter :: {kind}_coef(0:{kind}_ncoef-1, {i0}:{i1}) = reshape([ &")
        flat = [v for row in rows for v in row]
        for j, row in enumerate(rows):
            vals = [fortran_real(v) for v in row]
            for g in range(0, len(vals), 3):
                last = j == n - 1 and g + 3 >= len(vals)
                w("      & " + ", ".join(vals[g:g + 3]) + ("], &" if last else ", &"))
        w(f"      & [{kind}_ncoef, {n}])")
        w(f"   !> Low parts of c0 and c1, one row per centre")
        w(f"   real(wp), parameter :: {kind}_lo(0:1, {i0}:{i1}) = reshape([ &")
        for j, row in enumerate(lows):
            sep = ", &" if j < n - 1 else "], &"
            w("      & " + ", ".join(fortran_real(v) for v in row) + sep)
        w(f"      & [2, {n}])")
        del flat
    # Taylor series of W0 at z = 0: W0 = sum_{k>=1} (-k)^(k-1)/k! z^k (Abramowitz-Stegun 4.13.5 style)
    zc = [Fraction((-k) ** (k - 1), factorial(k)) for k in range(2, W0_SERIES_TERMS + 2)]
    w("")
    w("   !> Coefficients a_k = (-k)**(k-1)/k!, k = 2, 3, ..., of W0(z) = z + sum a_k z**k")
    w(f"   real(wp), parameter :: w0_series(2:{W0_SERIES_TERMS + 1}) = [ &")
    vals = [fortran_real(float(c)) for c in zc]
    for g in range(0, len(vals), 3):
        last = g + 3 >= len(vals)
        w("      & " + ", ".join(vals[g:g + 3]) + ("]" if last else ", &"))
    w("")
    w("end module hcimpact_lambertw_tables")
    with open(out, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print(f"wrote {os.path.relpath(out)}", file=sys.stderr)


if __name__ == "__main__":
    main()
