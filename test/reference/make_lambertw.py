#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Reference values of the real Lambert W branches for the accuracy tests (issue #2).

Writes ``lambertw.csv`` next to this script (or to ``--output``): one row per
test point, ``region,func,x,ref_hi,ref_lo``, where ``x`` is the exact double
input and ``ref_hi + ref_lo`` is the exact function value at that double to
about 106 bits.  See README.md in this directory for the format and regions.

func ``w0`` and ``wm1``
    W0(z) and W-1(z) at the double ``z``, from ``mpmath.lambertw`` at 60 and
    80 significant digits (the two must agree, and ``W e^W = z`` must hold).
func ``w0p1`` and ``wm1p1``
    ``1 + W(-exp(-1-t))`` at the double ``t``, never through a double ``z``:
    ``1 + W = -u`` where ``h(u) = u - ln(1+u) = t`` (MODEL.md, seed eq. 14),
    with ``u >= 0`` for W-1 and ``-1 < u <= 0`` for W0.  ``u`` is found by a
    safeguarded Newton iteration at ``50 + max(0, -log10 t)`` digits, and a
    sample is compared with ``mpmath.lambertw`` at a higher precision.

The generator is deterministic: every region draws from its own
``random.Random`` seeded with a fixed string.  Requires mpmath only.
"""

import argparse
import math
import os
import random
import sys
import time

import mpmath
from mpmath import mp, mpf

from doubles import nearest_double

#: Seed shared by every region (each region mixes in its own name)
SEED = "hcimpact-lambertw-2"

#: Points per region (the first-300-doubles region has its own count)
POINTS = 2000

#: Points of the subnormal regions
POINTS_SUBNORMAL = 500

#: Significant digits of the W(z) references and of their check
DPS_Z, DPS_Z_CHECK = 60, 80

#: Largest finite double
HUGE = sys.float_info.max

#: Smallest positive subnormal and smallest positive normal double
TINY_SUB, TINY_NORMAL = math.ldexp(1.0, -1074), sys.float_info.min


# --------------------------------------------------------------------------
# Rounding to doubles
# --------------------------------------------------------------------------

def split(value, extra=0):
    """(hi, lo): value + extra rounded to a double, and the rest rounded to a double.

    ``value + extra`` is the reference; ``extra`` carries a part far below the
    working precision of ``value`` (``-v`` in ``1 - v`` for W0 at large t), so
    that the low word is right even when ``value + extra`` rounds to ``value``.
    """
    hi = nearest_double(value + extra)
    lo = nearest_double((value - mpf(hi)) + extra)
    return hi, lo


# --------------------------------------------------------------------------
# References
# --------------------------------------------------------------------------

def w_of_z(z, branch):
    """W_branch(z) at the exact double z, as an mpf at DPS_Z_CHECK digits."""
    with mp.workdps(DPS_Z):
        w_lo = mp.lambertw(mpf(z), branch)
    with mp.workdps(DPS_Z_CHECK):
        w = mp.lambertw(mpf(z), branch)
        if mp.im(w) != 0 or mp.im(w_lo) != 0:
            raise ArithmeticError(f"W{branch}({z!r}) is not real")
        w, w_lo = mp.re(w), mp.re(w_lo)
        if abs(w - w_lo) > abs(w) * mpf(10) ** (-(DPS_Z - 8)):
            raise ArithmeticError(f"W{branch}({z!r}) differs between 60 and 80 digits")
        if z != 0 and abs(w * mp.exp(w) - z) > abs(z) * mpf(10) ** (-(DPS_Z - 8)):
            raise ArithmeticError(f"W{branch}({z!r}) fails W e^W = z")
    return w


def digits_for(t):
    """Working digits for t: 50 plus the digits lost to the cancellation in h(u) = t."""
    extra = 0
    if 0 < t < 1:
        extra = int(math.ceil(-float(mp.log10(t))))
    elif t > 1:
        # only for the W0 form at large t, where ln(1+u) ~ -1-t must be exact
        extra = int(math.ceil(float(mp.log10(t))))
    return 50 + extra


def _newton(func, dfunc, start, lo, hi, tol, what):
    """Root of func in (lo, hi), func(lo) and func(hi) of opposite signs.

    Newton's iteration from start; a step that leaves the bracket is replaced
    by bisection, and the bracket shrinks with every evaluation, so the
    iteration cannot fail to converge.
    """
    sign_lo = mp.sign(func(lo))
    x = start if lo < start < hi else (lo + hi) / 2
    for _ in range(400):
        fx = func(x)
        if fx == 0:
            return x
        if mp.sign(fx) == sign_lo:
            lo = x
        else:
            hi = x
        step = fx / dfunc(x)
        x_new = x - step
        if not lo < x_new < hi:
            x_new = (lo + hi) / 2
        if abs(x_new - x) <= abs(x_new) * tol:
            return x_new
        x = x_new
    raise ArithmeticError(f"no convergence for {what}")


def one_plus_w(t, branch):
    """(value, extra) with value + extra = 1 + W_branch(-exp(-1-t)), t >= 0 an mpf or float.

    Computed at the current mp precision, which the caller sets with digits_for(t).
    """
    t = mpf(t)
    if t == 0:
        return mpf(0), mpf(0)
    tol = mpf(10) ** (-(mp.dps - 8))
    sigma = mp.sqrt(2 * t)

    def h(u):
        return u - mp.log1p(u)

    def dh(u):
        return u / (1 + u)

    if branch == -1:
        # u >= 0 (compression branch); 1 + W-1 = -u.
        if t < 2:
            start = sigma + sigma**2 / 3 + sigma**3 / 36 - sigma**4 / 270
        else:
            start = t + mp.log1p(t + mp.log1p(t))
        hi = 2 * start + 1
        while h(hi) <= t:
            hi *= 2
        u = _newton(lambda u: h(u) - t, dh, start, mpf(0), hi, tol, f"W-1 form, t={t}")
        residual = h(u) - t
        if abs(residual) > t * mpf(10) ** -40:
            raise ArithmeticError(f"W-1 form at t={t}: residual {residual}")
        return -u, mpf(0)

    if t <= 1:
        # -1 < u <= 0 (restitution branch); 1 + W0 = -u.
        start = -sigma + sigma**2 / 3 - sigma**3 / 36 - sigma**4 / 270
        u = _newton(lambda u: h(u) - t, dh, start, mpf(-1), mpf(0), tol, f"W0 form, t={t}")
        residual = h(u) - t
        if abs(residual) > t * mpf(10) ** -40:
            raise ArithmeticError(f"W0 form at t={t}: residual {residual}")
        return -u, mpf(0)

    # Large t: 1 + u = v = exp(L) is tiny, 1 + W0 = 1 - v.  h(u) = t reads
    # exp(L) - 1 - L = t, decreasing in L < 0, with the root in (-1-t, -t).
    def g(ell):
        return mp.expm1(ell) - ell - t

    def dg(ell):
        return mp.expm1(ell)

    start = -1 - t + mp.exp(-1 - t)
    ell = _newton(g, dg, start, -1 - t, -t, tol, f"W0 form, t={t}")
    v = mp.exp(ell)
    residual = g(ell)
    if abs(residual) > t * mpf(10) ** -40:
        raise ArithmeticError(f"W0 form at t={t}: residual {residual}")
    return mpf(1), -v


def one_plus_w_ref(t, branch):
    """(value, extra) of one_plus_w at the precision digits_for(t)."""
    with mp.workdps(digits_for(mpf(t))):
        value, extra = one_plus_w(t, branch)
        return +value, +extra


# --------------------------------------------------------------------------
# Cross-checks between the two methods
# --------------------------------------------------------------------------

def check_t_form(t, branch, value, extra):
    """1 + W from the u-equation must agree with mpmath.lambertw to 1e-30."""
    with mp.workdps(digits_for(mpf(t)) + 20):
        z = -mp.exp(-1 - mpf(t))
        w = mp.lambertw(z, branch)
        if mp.im(w) != 0:
            raise ArithmeticError(f"lambertw({z}, {branch}) is not real")
        direct = 1 + mp.re(w)
        ours = value + extra
        if abs(direct - ours) > abs(ours) * mpf(10) ** -30:
            raise ArithmeticError(f"1+W{branch} at t={t!r}: {ours} vs lambertw {direct}")


def check_z_by_t(z, branch, w):
    """W(z) from lambertw must agree with -1 - u(t), t = -1 - ln(-z), to 1e-30."""
    with mp.workdps(DPS_Z_CHECK):
        t = -1 - mp.log(-mpf(z))
    if t < 0:
        raise ArithmeticError(f"z={z!r} lies below -1/e")
    with mp.workdps(digits_for(t)):
        value, extra = one_plus_w(t, branch)
        w_by_t = (value - 1) + extra
        if abs(w_by_t - w) > abs(w) * mpf(10) ** -30:
            raise ArithmeticError(f"W{branch}({z!r}): lambertw {w} vs u-equation {w_by_t}")


# --------------------------------------------------------------------------
# Test points
# --------------------------------------------------------------------------

def log_uniform(rng, a, b):
    """A double drawn log-uniformly from [a, b] (0 < a < b)."""
    return math.exp(rng.uniform(math.log(a), math.log(b)))


def minus_inv_e():
    """-1/e at the current precision."""
    return -mp.exp(-1)


def double_below_branch():
    """The double nearest -1/e; it lies below -1/e (checked)."""
    with mp.workdps(DPS_Z_CHECK):
        z = nearest_double(minus_inv_e())
        if not mpf(z) < minus_inv_e():
            raise AssertionError("the double nearest -1/e was expected below -1/e")
    return z


def first_doubles_above_branch(count):
    """The `count` smallest doubles z with z > -1/e exactly."""
    z = double_below_branch()
    points = []
    for _ in range(count):
        z = math.nextafter(z, 0.0)
        points.append(z)
    with mp.workdps(DPS_Z_CHECK):
        if not mpf(points[0]) > minus_inv_e():
            raise AssertionError("first double above -1/e is not above -1/e")
    return points


def near_branch(rng, lo, hi):
    """A double z with z + 1/e drawn log-uniformly from [lo, hi], then rounded."""
    offset = log_uniform(rng, lo, hi)
    with mp.workdps(DPS_Z_CHECK):
        z = nearest_double(minus_inv_e() + mpf(offset))
        if not mpf(z) > minus_inv_e():
            raise AssertionError(f"z={z!r} not above -1/e")
    return z


def double_windows(centres, half, lower):
    """`half` consecutive doubles on each side of every centre, all > lower; sorted."""
    points = set()
    for centre in centres:
        below = above = centre
        points.add(centre)
        for _ in range(half):
            below = math.nextafter(below, -math.inf)
            above = math.nextafter(above, math.inf)
            points.update((below, above))
    return sorted(x for x in points if x > lower)


def p_grid(count, step):
    """Doubles z nearest -1/e + p^2/(2e) for p = step, 2 step, ..., count step."""
    with mp.workdps(DPS_Z_CHECK):
        return [nearest_double(minus_inv_e() + (k * mpf(step)) ** 2 / (2 * mp.e))
                for k in range(1, count + 1)]


#: The double nearest 1/e, as lambertw.f90 uses it (the key z + 1/e_hi of its tables)
INV_E_HI = 0.36787944117144233


def geo_seams(kmin, kmax):
    """Boundaries 2**k (1 + j/16) of the geometric tables of lambertw.f90 (tools/
    make_lambertw_tables.py) for binades kmin..kmax, and the top 2**(kmax+1)."""
    return [math.ldexp(16 + j, k - 4) for k in range(kmin, kmax + 1) for j in range(16)] \
        + [math.ldexp(1.0, kmax + 1)]


def nearest_exp(y):
    """The double nearest exp(y) for the mpf or float y (None if it underflows to 0)."""
    with mp.workdps(DPS_Z_CHECK):
        v = mp.exp(mpf(y))
        if v < mpf(TINY_SUB) / 2:
            return None
        return nearest_double(v)


def seam_points(func):
    """Every seam of the tables of lambertw.f90 for func, with one double either side:
    the interval boundaries of each geometric table (in its key: z + 1/e_hi, |z|, z, t,
    ln z or -ln(-z); the ranges of tools/make_lambertw_tables.py) and the switches between
    methods and tables: z = -1/4 (wa/wb to wc/we), |z| = 2**-9 (the Taylor row of wc/wd),
    z = 2**10 (wd to the ln-keyed ya), z = -2**-20 (we to yb), t = 2**-54 (the series at
    the branch point to ta/tb), t = 64 (ta's clamp to 1), t = 2**10 (tb to Newton's
    method), and the scalings of subnormal arguments."""
    if func == "w0":
        zs = [d - INV_E_HI for d in geo_seams(-54, -4) if d - INV_E_HI <= -0.25]
        zs += [-s for s in geo_seams(-9, -3) if -0.25 <= -s]
        zs += [z for z in geo_seams(-9, 9) if z <= 1024.0]
        zs += [nearest_exp(y) for y in geo_seams(2, 9) if y < 709.7]
        zs += [-0.25, -2.0**-9, 2.0**-9, 1024.0, TINY_NORMAL, -TINY_NORMAL, HUGE]
        return [z for z in double_windows(zs, 1, double_below_branch()) if z <= HUGE]
    if func == "wm1":
        zs = [d - INV_E_HI for d in geo_seams(-54, -4) if d - INV_E_HI <= -0.25]
        zs += [-s for s in geo_seams(-20, -3) if -0.25 <= -s <= -2.0**-20]
        zs += [-v for v in (nearest_exp(-y) for y in geo_seams(3, 9)) if v is not None]
        zs += [-0.25, -2.0**-20, -TINY_NORMAL]
        points = double_windows(zs, 1, double_below_branch())
        return [z for z in points if z < 0]
    top = 5 if func == "w0p1" else 9
    ts = geo_seams(-54, top) + [2.0**-54, 2.0**-600, 2.0**10]
    return double_windows(ts, 1, 0.0)


def draw(rng, count, sampler, fixed=()):
    """count distinct doubles: the fixed ones, then sampler(rng) until full; sorted."""
    points = set(fixed)
    while len(points) < count:
        x = sampler(rng)
        if x != 0:
            points.add(x)
    return sorted(points)


def region_rng(func, region):
    """The random stream of one (func, region): reproducible and independent."""
    return random.Random(f"{SEED}:{func}:{region}")


def regions():
    """Yield (region, func, inputs) for every accuracy region, in file order."""
    for func in ("w0", "wm1"):
        yield "branch300", func, first_doubles_above_branch(300)
        yield "near16_6", func, draw(region_rng(func, "near16_6"), POINTS,
                                     lambda r: near_branch(r, 1e-16, 1e-6))
        yield "near6_2", func, draw(region_rng(func, "near6_2"), POINTS,
                                    lambda r: near_branch(r, 1e-6, 1e-2))
        # seams of tables in p = sqrt(2(1 + e z)) with spacings down to 1/64
        p_max = 1.5 if func == "w0" else 1.40625      # W-1 needs z < 0, p < sqrt(2)
        yield "pgrid", func, double_windows(p_grid(int(p_max * 64), 1 / 64), 8,
                                            double_below_branch())
        if func == "w0":
            # seams of the coarser W0 tables (p spacing 1/16 up to 4.34, then 1/2 up to
            # 64.25: seams at odd multiples of 1/32 and 1/4) and the method switches at
            # |z| = 0.05 and z = 758
            with mp.workdps(DPS_Z_CHECK):
                ps = [k / 32 for k in range(48, 145)] + [k / 4 for k in range(18, 259)]
                seams = [nearest_double(minus_inv_e() + mpf(q) ** 2 / (2 * mp.e)) for q in ps]
            yield "pgrid2", func, double_windows(seams + [-0.05, 0.05, 758.0], 8,
                                                 double_below_branch())
        # seams of the geometric tables and method switches of lambertw.f90
        yield "seams", func, seam_points(func)
        yield "neg", func, draw(region_rng(func, "neg"), POINTS,
                                lambda r: r.uniform(-0.358, -1e-3))
        top = 1e-3 if func == "w0" else 1e-1
        yield "negtiny", func, draw(region_rng(func, "negtiny"), POINTS,
                                    lambda r: -log_uniform(r, 1e-300, top))
        if func == "w0":
            yield "w0mid", func, draw(region_rng(func, "w0mid"), POINTS,
                                      lambda r: log_uniform(r, 1e-4, 1e4))
            yield "w0pos", func, draw(region_rng(func, "w0pos"), POINTS,
                                      lambda r: log_uniform(r, 1e-300, 1e300))
            yield "subnormal", func, draw(region_rng(func, "subnormal"), POINTS_SUBNORMAL,
                                          lambda r: r.choice((-1.0, 1.0))
                                          * log_uniform(r, TINY_SUB, TINY_NORMAL))
        else:
            yield "subnormal", func, draw(region_rng(func, "subnormal"), POINTS_SUBNORMAL,
                                          lambda r: -log_uniform(r, TINY_SUB, TINY_NORMAL))
    for func in ("w0p1", "wm1p1"):
        yield "tlog", func, draw(region_rng(func, "tlog"), POINTS,
                                 lambda r: log_uniform(r, 1e-300, 1e300), fixed=(0.0,))
        yield "tswitch", func, draw(region_rng(func, "tswitch"), POINTS,
                                    lambda r: log_uniform(r, 1e-3, 10.0))
        # next to the branch point, across the switch from the series to the tables at
        # t = 2**-54 and through the tables' lowest binades
        yield "tnear", func, draw(region_rng(func, "tnear"), POINTS,
                                  lambda r: log_uniform(r, 1e-18, 1e-3))
        # seams of tables in s = sqrt(2t) with spacings down to 1/32, s up to 4
        yield "sgrid", func, double_windows([(k / 32) ** 2 / 2 for k in range(1, 129)], 8, 0.0)
        yield "seams", func, seam_points(func)


BRANCH = {"w0": 0, "wm1": -1, "w0p1": 0, "wm1p1": -1}

#: Points per region cross-checked by the other method
CROSS_CHECKS = 40


def reference(func, x):
    """(hi, lo) of the reference of func at the double x."""
    branch = BRANCH[func]
    if func in ("w0", "wm1"):
        w = w_of_z(x, branch)
        with mp.workdps(DPS_Z_CHECK):
            return split(w)
    value, extra = one_plus_w_ref(x, branch)
    with mp.workdps(digits_for(mpf(x)) + 10):
        return split(value, extra)


def cross_check(func, x):
    """Check the reference of func at x by the other method (see module doc)."""
    branch = BRANCH[func]
    if func in ("w0", "wm1"):
        if x < 0:
            check_z_by_t(x, branch, w_of_z(x, branch))
    else:
        value, extra = one_plus_w_ref(x, branch)
        check_t_form(x, branch, value, extra)


def edge_rows():
    """Rows of region `edge`: values fixed by convention or exact, compared for equality."""
    z_branch = double_below_branch()
    rows = [
        ("edge", "w0", z_branch, -1.0, 0.0),
        ("edge", "wm1", z_branch, -1.0, 0.0),
        ("edge", "w0", 0.0, 0.0, 0.0),
        ("edge", "w0p1", 0.0, 0.0, 0.0),
        ("edge", "wm1p1", 0.0, 0.0, 0.0),
    ]
    # W0(z) = z - z^2 + ... rounds to z itself for the smallest subnormals
    # (ref_lo underflows to zero, so these too are compared for equality),
    # and W0 at the largest double is the top of the range.
    for z in (TINY_SUB, -TINY_SUB, HUGE):
        hi, lo = reference("w0", z)
        rows.append(("edge", "w0", z, hi, lo))
    return rows


def write_csv(path, rows):
    """Write the header and the rows; numbers by repr (shortest round trip)."""
    with open(path, "w", encoding="ascii", newline="\n") as out:
        out.write("# Reference values of the real Lambert W branches for hcimpact (issue #2).\n")
        out.write(f"# Written by test/reference/make_lambertw.py with mpmath {mpmath.__version__},"
                  f" seed {SEED!r}; do not edit, regenerate.\n")
        out.write("# Columns: region,func,x,ref_hi,ref_lo. func w0/wm1: x = z, reference W0(z) or"
                  " W-1(z); func w0p1/wm1p1: x = t, reference 1 + W(-exp(-1-t)).\n")
        out.write("# x is the exact double input; the exact value at x is ref_hi + ref_lo to about"
                  " 106 bits (ref_hi = nearest double).\n")
        out.write("# Region edge holds conventions and exact values: compare for equality when"
                  " ref_lo = 0.\n")
        for region, func, x, hi, lo in rows:
            out.write(f"{region},{func},{x!r},{hi!r},{lo!r}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--output", default=os.path.join(here, "lambertw.csv"),
                        help="CSV file to write (default: lambertw.csv next to this script)")
    args = parser.parse_args()

    start_all = time.time()
    rows = []
    for region, func, inputs in regions():
        start = time.time()
        for x in inputs:
            hi, lo = reference(func, x)
            rows.append((region, func, x, hi, lo))
        # a spread of points plus both ends of the region (t = 0 has no z to check)
        stride = max(1, len(inputs) // CROSS_CHECKS)
        sample = sorted(set(inputs[::stride] + inputs[:3] + inputs[-3:]) - {0.0})
        for x in sample:
            cross_check(func, x)
        print(f"{func:6s} {region:10s} {len(inputs):5d} points, {len(sample):3d} cross-checked,"
              f" {time.time() - start:6.1f} s", flush=True)
    rows.extend(edge_rows())
    write_csv(args.output, rows)
    print(f"wrote {len(rows)} rows to {args.output} in {time.time() - start_all:.1f} s")


if __name__ == "__main__":
    main()
