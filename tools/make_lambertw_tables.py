#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write the generated tables of two modules:
src/hcimpact/special/lambertw_tables.f90 (hcimpact_lambertw_tables, used by lambertw.f90) and
src/hcimpact/model/restitution_tables.f90 (hcimpact_restitution_tables: the Taylor tables of
the restitution k(beta), used by restitution_law.f90).

* Geometric tables (GEO below), the ones lambertw.f90 evaluates on almost every path: a
  key x >= 0 that the Fortran code forms exactly (z + 1/e_hi, |z|, z, t, ln z, -ln(-z)) is
  cut into intervals [2^k (1 + j/32), 2^k (1 + (j+1)/32)), indexed by the bits of x; on
  each the function is the polynomial (degree 8, in x - centre) that interpolates it at
  Chebyshev nodes, computed with mpmath at 50 digits and checked against mpmath on the
  interval with its coefficients rounded to doubles (relative error below 2^-57). Some
  tables have a row below their intervals (the Taylor polynomial of W0 at 0, or the
  constant -1 at the branch point) or above them (the constant 1), reached by clamping.
* ln_tab: 1/m0 and ln(m0) for the table-driven logarithm of lambertw_ln.inc.
* Row 0 of the Taylor table s: the series at the branch point of
  V(s) = 1 + W(-exp(-1 - s^2/2)), s = +-sqrt(2t) (DLMF 4.13), by series reversion in
  exact rational arithmetic; V solves -V - ln(1 - V) = s^2/2.
* k and m: local Taylor polynomials of k(beta) on a uniform grid, by composing the
  power series of h(beta) = beta - ln(1 + beta), s = sqrt(2h) and V(s) (the ODE
  V V' = s (1 - V) gives V's Taylor coefficients by a recurrence at 60 digits).

Each Taylor coefficient c0 and c1 is stored as a pair of doubles (hi + lo), the others
as one double.

Usage: python3 tools/make_lambertw_tables.py  (writes both modules; takes a few minutes)
"""
from fractions import Fraction
from math import factorial
import os
import sys

import mpmath as mp

mp.mp.dps = 60

TABLES = {
    # name: (spacing, first centre index, last centre index, number of coefficients);
    # s goes to the Lambert W module, k and m to the restitution module
    # Only the series at the branch point (row 0) of the s table is used by
    # lambertw.f90 now (the geometric tables below replaced the other rows).
    "s": (Fraction(1, 8), 0, 0, 14),        # V(s) at s = 0
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
    # s: F(V) = -V - ln(1 - V) = sum_{k>=2} V^k / k
    coef = [Fraction(0), Fraction(0)] + [Fraction(1, k) for k in range(2, n + 3)]
    return [mp.mpf(c.numerator) / c.denominator for c in revert(coef, n)]


def restitution_value(beta):
    """k(beta) = (1 + W0(-(1 + beta) exp(-(1 + beta))))/beta (seed eq. 21)."""
    z = -(1 + beta) * mp.exp(-(1 + beta))
    return (1 + mp.lambertw(z, 0).real) / beta


def value_at(kind, xc):
    """V(s) (kind s) or k (kind k) at a non-zero centre, 60 digits."""
    if kind == "k":
        return restitution_value(xc)
    z = -mp.exp(-1 - xc * xc / 2)
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
    # s-table: V V' = s (1 - V), so the coefficients of V V' are those of s (1 - V)
    A = []      # coefficients of V V'
    for k in range(0, n - 1):
        one_minus = (1 - a[0]) if k == 0 else -a[k]
        prev = 0 if k == 0 else ((1 - a[0]) if k == 1 else -a[k - 1])
        Ak = xc * one_minus + prev
        A.append(Ak)
        # A_k = a0 (k+1) a_{k+1} + sum_{j=1..k} a_j (k-j+1) a_{k-j+1}
        acc = Ak - sum(a[j] * (k - j + 1) * a[k - j + 1] for j in range(1, k + 1))
        a.append(acc / ((k + 1) * a[0]))
    return a


def exact_value(kind, x):
    if kind in ("k", "m"):
        return mp.mpf(1) if x == 0 else restitution_value(x)
    if x == 0:
        return mp.mpf(0)
    return value_at(kind, x)


def split(v):
    hi = float(v)
    lo = float(v - mp.mpf(hi))
    return hi, lo


def write_rows(w, rows):
    """The body of an array constructor: every row's values, three to a line, in order;
    the last line closes the constructor."""
    for i, row in enumerate(rows):
        vals = [fortran_real(v) for v in row]
        for g in range(0, len(vals), 3):
            last = i == len(rows) - 1 and g + 3 >= len(vals)
            w("      & " + ", ".join(vals[g:g + 3]) + ("], &" if last else ", &"))


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


# ---------------------------------------------------------------------------------------
# Geometric tables: the polynomials that lambertw.f90 evaluates in plain double.
#
# A key x >= 0 (a double the Fortran code forms exactly: |z|, z + 1/e_hi, t or ln|z|) is
# cut into intervals [2**k (1 + j/32), 2**k (1 + (j+1)/32)), k = kmin..kmax, j = 0..31:
# the row is (bits of x >> 47) - base + off, i.e. the biased exponent and the first five
# fraction bits. On each interval the function is approximated, in the offset
# delta = x - xc from the centre xc (an exact double, so delta is exact by Sterbenz), by
# the polynomial interpolating it at Chebyshev nodes (near-minimax). Relative to the
# distance of the nearest singularity an interval is at most 1/65 wide, so NTERMS terms
# reach far below an ulp. Each row is [xc, lo(c0), c0, c1, ..., c(NTERMS-1)], c0 as the
# unevaluated sum of two doubles.
#
# A table may have a row below its intervals (`bottom`), which the code reaches by
# clamping the row index from below (max(row, row0): no branch) for every key under
# 2**kmin: "taylor" is the Taylor polynomial of the function at key 0 (centre 0), for the
# keys |z| < 2**kmin of W0; a number is a constant row (centre 0), -1 for the keys
# d = z + 1/e_hi < 2**kmin of W at the branch point, where only d = 0 is a double.
# And a row above them (`top`): a constant, which the code reaches by clamping the key
# itself from above at 2**(kmax+1) (1 + W0 = 1 in double for t >= 64).
# ---------------------------------------------------------------------------------------

GEO_J = 32                # intervals per binade (five fraction bits)
GEO_TERMS = 9             # coefficients per interval (degree 8)
GEO_MARGIN = mp.mpf(1) / 64   # fit and check a little beyond each interval
GEO_DPS = 50

INV_E_HI = 0.36787944117144233   # the double nearest 1/e (as in lambertw.f90)

# name: (kmin, kmax, what, bottom row, top row) -- what documents the key and the function
GEO = {
    # d = z + 1/e_hi is a multiple of 2**-54 for z <= -1/4: 2**-54 is its least nonzero value
    "wa": (-54, -4, "W0(z), key d = z + 1/e_hi for -1/e_hi <= z <= -1/4", -1, None),
    "wb": (-54, -4, "W-1(z), key d = z + 1/e_hi for -1/e_hi <= z <= -1/4", -1, None),
    "wc": (-9, -3, "W0(z), key -z for -1/4 < z < 0", "taylor", None),
    "wd": (-9, 9, "W0(z), key z for 0 < z < 2**10", "taylor", None),
    "we": (-20, -3, "W-1(z), key -z for -1/4 < z <= -2**-20", None, None),
    # t >= 2**-54: z + 1/e ~ t/e is then at least the spacing of the doubles at -1/e
    "ta": (-54, 5, "1 + W0(-exp(-1 - t)), key min(t, 64) for t >= 2**-54", None, 1),
    "tb": (-54, 9, "1 + W-1(-exp(-1 - t)), key t for 2**-54 <= t < 2**10", None, None),
    "ya": (2, 9, "W0(exp(y)), key y = ln z for z >= 2**10", None, None),
    "yb": (3, 9, "W-1(-exp(-y)), key y = -ln(-z) for 0 < -z < 2**-20", None, None),
}


def geo_value(name, x):
    """The tabulated function at the key x (an mpf at the current precision)."""
    if name in ("wa", "wb"):
        z = x - mp.mpf(INV_E_HI)
        return mp.re(mp.lambertw(z, 0 if name == "wa" else -1))
    if name == "wc":
        return mp.re(mp.lambertw(-x, 0))
    if name == "wd":
        return mp.re(mp.lambertw(x, 0))
    if name == "we":
        return mp.re(mp.lambertw(-x, -1))
    if name in ("ta", "tb"):
        z = -mp.exp(-1 - x)
        return 1 + mp.re(mp.lambertw(z, 0 if name == "ta" else -1))
    if name == "ya":
        return mp.re(mp.lambertw(mp.exp(x), 0))
    return mp.re(mp.lambertw(-mp.exp(-x), -1))


def chebyshev_fit(f, xc, r, n):
    """Monomial coefficients in delta = x - xc of the polynomial of degree n-1 that
    interpolates f at the n Chebyshev nodes of [xc - r, xc + r]."""
    nodes = [mp.cos(mp.pi * (i + mp.mpf(1) / 2) / n) for i in range(n)]
    vals = [f(xc + r * u) for u in nodes]
    a = []
    for j in range(n):
        s = sum(v * mp.cos(j * mp.pi * (i + mp.mpf(1) / 2) / n) for i, v in enumerate(vals))
        a.append(2 * s / n)
    a[0] /= 2
    # Chebyshev to monomials in u, then u = delta / r
    tm = [[mp.mpf(1)], [mp.mpf(0), mp.mpf(1)]]
    for j in range(2, n):
        nxt = [mp.mpf(0)] + [2 * c for c in tm[j - 1]]
        for k, c in enumerate(tm[j - 2]):
            nxt[k] -= c
        tm.append(nxt)
    b = [mp.mpf(0)] * n
    for j in range(n):
        for k, c in enumerate(tm[j]):
            b[k] += a[j] * c
    return [b[k] / r**k for k in range(n)]


def w0_taylor(n):
    """Taylor coefficients of W0 at 0: (-m)**(m-1)/m! for m = 0..n-1 (exact fractions)."""
    return [Fraction(0)] + [Fraction((-m) ** (m - 1), factorial(m)) for m in range(1, n)]


def bottom_row(name, kind):
    """The row below the intervals of a table, and its worst relative error on the keys
    it serves (0 <= x < 2**kmin, checked at a spread of points)."""
    kmin = GEO[name][0]
    if kind == "taylor":
        sign = -1 if name == "wc" else 1          # wc: W0(-x) = sum a_m (-x)**m
        coef = [c * sign**m for m, c in enumerate(w0_taylor(GEO_TERMS))]
        row = [0.0, 0.0] + [float(c) for c in coef]
        worst = mp.mpf(0)
        with mp.workdps(GEO_DPS):
            top = mp.ldexp(mp.mpf(1), kmin)
            for i in range(1, 41):
                x = top * i / 40
                ref = geo_value(name, x)
                approx = sum(mp.mpf(row[2 + m]) * x**m for m in range(1, GEO_TERMS))
                worst = max(worst, abs(approx - ref) / abs(ref))
        return row, worst
    # A constant: the keys d = z + 1/e_hi are multiples of 2**-54 (z <= -1/4 is a multiple
    # of 2**-54, and so is 1/e_hi), so the only key below 2**-54 is d = 0, the double
    # nearest -1/e, which stands for the branch point: W = -1 there by the library's
    # convention (doc/lambertw.md), exactly.
    if not (name in ("wa", "wb") and kind == -1 and kmin == -54):
        raise SystemExit(f"table {name}: no constant bottom row is defined for it")
    row = [0.0, 0.0, float(kind)] + [0.0] * (GEO_TERMS - 1)
    return row, mp.mpf(0)


def top_row(name, value):
    """The constant row above the intervals, centre 2**(kmax+1), and how far the function
    is from it at 2**(kmax+1) in units of 2**-54 (it must round to the constant there and,
    being monotone towards it, beyond)."""
    kmax = GEO[name][1]
    xc = 2.0 ** (kmax + 1)
    row = [xc, 0.0, float(value)] + [0.0] * (GEO_TERMS - 1)
    with mp.workdps(GEO_DPS):
        gap = abs(geo_value(name, mp.mpf(xc)) - value) / mp.ldexp(mp.mpf(1), -54)
    return row, gap


def geo_rows(name):
    """Rows of the intervals of one geometric table and their worst relative error
    (double coefficients)."""
    kmin, kmax = GEO[name][0], GEO[name][1]
    rows, worst = [], mp.mpf(0)
    with mp.workdps(GEO_DPS):
        for k in range(kmin, kmax + 1):
            for j in range(GEO_J):
                lo = mp.ldexp(mp.mpf(GEO_J + j), k) / GEO_J
                hi = mp.ldexp(mp.mpf(GEO_J + j + 1), k) / GEO_J
                xc = (lo + hi) / 2
                assert float(xc) == xc
                r = (hi - lo) / 2 * (1 + GEO_MARGIN)
                c = chebyshev_fit(lambda x: geo_value(name, x), xc, r, GEO_TERMS)
                hi0, lo0 = split(c[0])
                row = [float(xc), lo0, hi0] + [float(ck) for ck in c[1:]]
                for frac in range(-8, 9):
                    d = r * frac / 8
                    ref = geo_value(name, xc + d)
                    approx = (mp.mpf(hi0) + mp.mpf(lo0)) + sum(
                        mp.mpf(row[2 + m]) * d**m for m in range(1, GEO_TERMS))
                    worst = max(worst, abs(approx - ref) / abs(ref))
                rows.append(row)
    return rows, worst


#: The tables in two arrays, one per kind of key (gfortran limits an array constructor to
#: 65535 elements without an option): z + 1/e_hi, |z| and ln|z| in geo_z; t in geo_t. A
#: function chooses among tables of one array only.
GEO_ARRAYS = {"geo_z": ("wa", "wb", "wc", "wd", "we", "ya", "yb"), "geo_t": ("ta", "tb")}
MAX_CONSTRUCTOR = 65535


def write_geo(w):
    """The geometric tables in the arrays of GEO_ARRAYS: table `name` holds its bottom row
    (if any) at name_row0, its intervals from name_off (name_rows of them), and its top row
    (if any) right after them, all row indices of its array."""
    width = GEO_TERMS + 2
    assert sorted(sum(GEO_ARRAYS.values(), ())) == sorted(GEO)
    w("")
    w(f"   !> [centre, lo(c0), c0, ..., c{GEO_TERMS - 1}] per row: number of entries")
    w(f"   integer, parameter :: geo_width = {width}")
    w(f"   !> Right shift of the bits of a key that leaves its exponent and first fraction bits")
    w(f"   integer, parameter :: geo_shift = {52 - (GEO_J.bit_length() - 1)}")
    for array, names in GEO_ARRAYS.items():
        all_rows, off = [], 0
        for name in names:
            kmin, kmax, what, bottom, top = GEO[name]
            rows, worst = geo_rows(name)
            print(f"table {name}: {len(rows)} rows, worst relative error {mp.nstr(worst, 3)}",
                  file=sys.stderr)
            if worst > 2.0**-57:
                raise SystemExit(f"table {name}: error {worst} too large; use more terms")
            w("")
            w(f"   !> {what}: {len(rows)} rows of {array}, relative error below {mp.nstr(worst, 2)}")
            if bottom is not None:
                row, err = bottom_row(name, bottom)
                print(f"table {name}: bottom row ({bottom}) relative error {mp.nstr(err, 3)}",
                      file=sys.stderr)
                if err > 2.0**-57:
                    raise SystemExit(f"table {name}: bottom row error {err} too large")
                kind = "the Taylor polynomial at 0" if bottom == "taylor" else f"the constant {bottom}"
                w(f"   !> Its row for the keys below 2**{kmin}: {kind}")
                w(f"   integer, parameter :: {name}_row0 = {off}")
                all_rows.append(row)
                off += 1
            w(f"   integer, parameter :: {name}_off = {off}, {name}_rows = {len(rows)}")
            w(f"   !> Bits of the key 2**{kmin} shifted right by geo_shift")
            w(f"   integer, parameter :: {name}_base = {(1023 + kmin) * GEO_J}")
            all_rows += rows
            off += len(rows)
            if top is not None:
                row, gap = top_row(name, top)
                print(f"table {name}: top row {top}, function - {top} at 2**{kmax + 1}: "
                      f"{mp.nstr(gap, 3)} x 2**-54", file=sys.stderr)
                if gap > 0.25:
                    raise SystemExit(f"table {name}: the function is not {top} at 2**{kmax + 1}")
                w(f"   !> Its row for the keys clamped at 2**{kmax + 1}: the constant {top}")
                w(f"   integer, parameter :: {name}_top = {off}")
                w(f"   !> The key at which it is clamped")
                w(f"   real(wp), parameter :: {name}_key_max = {fortran_real(2.0 ** (kmax + 1))}")
                all_rows.append(row)
                off += 1
        n = len(all_rows)
        if n * width > MAX_CONSTRUCTOR:
            raise SystemExit(f"{array}: {n * width} elements, more than an array constructor "
                             f"may hold ({MAX_CONSTRUCTOR}); split it")
        w("")
        w(f"   !> The rows of the tables {', '.join(names)}")
        w(f"   !> (a protected variable, not a parameter: read only, SAVEd and never written,")
        w(f"   !> so that a procedure that uses it does not copy the whole constructor into its")
        w(f"   !> own code; as a parameter it cost gfortran a minute of parsing per build)")
        w(f"   real(wp), protected :: {array}(0:{width - 1}, 0:{n - 1}) = reshape([ &")
        write_rows(w, all_rows)
        w(f"      & [{width}, {n}])")

LN_BITS = 7     # log table: m0 = 1 + (j + 1/2)/2**LN_BITS, j = first LN_BITS fraction bits


def write_log(w):
    """Table of the logarithm: per j, [1/m0 rounded, ln(m0) hi, ln(m0) lo]."""
    n = 2**LN_BITS
    w("")
    w(f"   !> First fraction bits of x that index `ln_tab`")
    w(f"   integer, parameter :: ln_bits = {LN_BITS}")
    w(f"   !> For m0 = 1 + (j + 1/2)/2**ln_bits, j = 0..{n - 1}: [1/m0 (rounded), ln(m0) as hi + lo]")
    w(f"   real(wp), parameter :: ln_tab(0:2, 0:{n - 1}) = reshape([ &")
    with mp.workdps(GEO_DPS):
        for j in range(n):
            m0 = 1 + (mp.mpf(j) + mp.mpf(1) / 2) / n
            hi, lo = split(mp.log(m0))
            vals = [fortran_real(float(1 / m0)), fortran_real(hi), fortran_real(lo)]
            w("      & " + ", ".join(vals) + ("], &" if j == n - 1 else ", &"))
    w(f"      & [3, {n}])")


LAMBERTW_TAYLOR = ("s",)       # Taylor tables of hcimpact_lambertw_tables
RESTITUTION_TAYLOR = ("k", "m")    # Taylor tables of hcimpact_restitution_tables


def write_taylor(w, kind):
    """One Taylor table (high parts of the coefficients and low parts of c0 and c1)."""
    h, i0, i1, nterms = TABLES[kind]
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
        hi0, lo0 = split(c[0])
        hi1, lo1 = split(c[1])
        rows.append([hi0, hi1] + [float(ck) for ck in c[2:]])
        lows.append([lo0, lo1])
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
    write_rows(w, rows)
    w(f"      & [{kind}_ncoef, {n}])")
    w(f"   !> Low parts of c0 and c1, one row per centre")
    w(f"   real(wp), parameter :: {kind}_lo(0:1, {i0}:{i1}) = reshape([ &")
    for j, row in enumerate(lows):
        sep = ", &" if j < n - 1 else "], &"
        w("      & " + ", ".join(fortran_real(v) for v in row) + sep)
    w(f"      & [2, {n}])")


def lambertw_module():
    """Lines of src/hcimpact/special/lambertw_tables.f90."""
    lines = []
    w = lines.append
    w("! SPDX-License-Identifier: Apache-2.0")
    w("! GENERATED by tools/make_lambertw_tables.py: do not edit by hand.")
    w("!> Tables of Lambert W (hcimpact_lambertw).")
    w("!>")
    w("!> Row i of a Taylor table holds the coefficients c0, c1, ... at centre xc = i*h, used")
    w("!> for |x - xc| <= h/2; c0 and c1 carry a low part (columns 0 and 1 of the `_lo` table).")
    w("!> `s` table: V(s) = 1 + W(-exp(-1 - s**2/2)), s = +-sqrt(2t) (+: W0, -: W-1): its row 0")
    w("!> only, the series at the branch point.")
    w("!> Geometric tables (`wa` ... `yb`, see tools/make_lambertw_tables.py): one polynomial")
    w("!> per interval [2**k (1 + j/32), 2**k (1 + (j+1)/32)) of a key, indexed by the key's")
    w("!> exponent and first five fraction bits; row = [centre, low part of c0, c0, c1, ...];")
    w("!> some tables have a row below their intervals (`_row0`) or above them (`_top`). Two")
    w("!> arrays (an array constructor is limited to 65535 elements): geo_z holds the tables")
    w("!> keyed by z + 1/e_hi, |z| and ln|z|, geo_t those keyed by t.")
    w("module hcimpact_lambertw_tables")
    w("   use hcimpact_kinds, only : wp")
    w("   implicit none")
    w("   private")
    w("")
    for kind in LAMBERTW_TAYLOR:
        w(f"   public :: {kind}_ncoef, {kind}_step_inv, {kind}_first, {kind}_last, {kind}_coef, {kind}_lo")
    w("   public :: ln_tab, ln_bits")
    w(f"   public :: {', '.join(GEO_ARRAYS)}, geo_width, geo_shift")
    for name, (_, _, _, bottom, top) in GEO.items():
        extra = (f", {name}_row0" if bottom is not None else "") \
            + (f", {name}_top, {name}_key_max" if top is not None else "")
        w(f"   public :: {name}_off, {name}_base, {name}_rows{extra}")
    for kind in LAMBERTW_TAYLOR:
        write_taylor(w, kind)
    write_geo(w)
    write_log(w)
    w("")
    w("end module hcimpact_lambertw_tables")
    return lines


def restitution_module():
    """Lines of src/hcimpact/model/restitution_tables.f90."""
    lines = []
    w = lines.append
    w("! SPDX-License-Identifier: Apache-2.0")
    w("! GENERATED by tools/make_lambertw_tables.py: do not edit by hand.")
    w("!> Taylor tables of the restitution k(beta) of the Hunt-Crossley impact")
    w("!> (hcimpact_restitution_law).")
    w("!>")
    w("!> Row i of a table holds the Taylor coefficients c0, c1, ... of k at centre xc = i*h,")
    w("!> used for |beta - xc| <= h/2; c0 and c1 carry a low part (columns 0 and 1 of the `_lo`")
    w("!> table). `k` tables: 0 <= beta < 3.66; `m` tables: the same, coarser, for")
    w("!> 3.66 <= beta < 40.125.")
    w("module hcimpact_restitution_tables")
    w("   use hcimpact_kinds, only : wp")
    w("   implicit none")
    w("   private")
    w("")
    for kind in RESTITUTION_TAYLOR:
        w(f"   public :: {kind}_ncoef, {kind}_step_inv, {kind}_first, {kind}_last, {kind}_coef, {kind}_lo")
    for kind in RESTITUTION_TAYLOR:
        write_taylor(w, kind)
    w("")
    w("end module hcimpact_restitution_tables")
    return lines


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    outputs = [
        (os.path.join(root, "src", "hcimpact", "special", "lambertw_tables.f90"), lambertw_module),
        (os.path.join(root, "src", "hcimpact", "model", "restitution_tables.f90"), restitution_module),
    ]
    for path, make in outputs:
        lines = make()
        with open(path, "w") as fh:
            fh.write("\n".join(lines) + "\n")
        print(f"wrote {os.path.relpath(path)}", file=sys.stderr)


if __name__ == "__main__":
    main()
