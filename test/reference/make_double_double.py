#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Reference values of the double-double arithmetic (src/hcimpact/numerics/double_double.f90).

Writes ``double_double.csv`` next to this script (or to ``--output``): one row per
test point, ``region,func,a_hi,a_lo,b_hi,b_lo,ref_hi,ref_lo``. The inputs are exact
double-double numbers a = a_hi + a_lo and b = b_hi + b_lo (normalised:
|lo| <= ulp(hi)/2; b is 0,0 for the functions of one argument), and
``ref_hi + ref_lo`` is the exact result at those inputs, ref_hi the nearest double
and ref_lo the nearest double to the rest. See README.md in this directory.

func (what the Fortran test evaluates)
    exp, log, sqrt       dd_exp(a), dd_log(a), dd_sqrt(a)
    add, sub, mul, div   a + b, a - b, a * b, a / b (both double-double)
    addr, mulr, divr     a + b_hi, a * b_hi, a / b_hi (b a double, b_lo = 0)
    rsub, rdiv           b_hi - a, b_hi / a

Computed with mpmath at 320 bits: every input is exact in mpmath, every function is
evaluated once, and each double is rounded from the exact value by comparing the
neighbours (ties to even), subnormals included. Deterministic: each region draws from
its own random.Random seeded with a fixed string. Requires mpmath only; about 5 s.
"""

import argparse
import math
import os
import random
import sys

from mpmath import mp, mpf

from doubles import nearest_double as nearest, split_double as split

mp.prec = 320

#: Seed shared by every region (each region mixes in its own name)
SEED = "hcimpact-double-double-1"

#: Smallest positive subnormal double
TINY_SUB = math.ldexp(1.0, -1074)


def random_dd(rng, hi):
    """The double hi with a random trailing part of up to half its ulp (normalised)."""
    ulp = math.ulp(hi)
    if ulp <= TINY_SUB:     # subnormal (or tiny normal) leading part: no room
        return hi, 0.0
    lo = nearest(mpf(ulp) * (mpf(rng.random()) - mpf("0.5")))
    return hi, lo


def loguniform(rng, lo, hi):
    """A double log-uniform in [lo, hi] (lo > 0)."""
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def value(a):
    return mpf(a[0]) + mpf(a[1])


def row(region, func, a, b, ref):
    hi, lo = split(ref)
    return f"{region},{func},{a[0]!r},{a[1]!r},{b[0]!r},{b[1]!r},{hi!r},{lo!r}"


def exp_rows(rng, region, args):
    return [row(region, "exp", a, (0.0, 0.0), mp.exp(value(a))) for a in args]


def log_rows(rng, region, args):
    return [row(region, "log", a, (0.0, 0.0), mp.log(value(a))) for a in args]


def regions():
    """Yield (region, list of rows)."""
    ln2 = math.log(2.0)

    rng = random.Random(SEED + "exp_wide")
    args = [random_dd(rng, rng.uniform(-745.0, 709.78)) for _ in range(2000)]
    yield "exp_wide", exp_rows(rng, "exp_wide", args)

    rng = random.Random(SEED + "exp_mid")
    args = [random_dd(rng, rng.uniform(-2.0, 2.0)) for _ in range(1000)]
    yield "exp_mid", exp_rows(rng, "exp_mid", args)

    rng = random.Random(SEED + "exp_small")
    args = [random_dd(rng, rng.choice((-1.0, 1.0)) * loguniform(rng, 1e-300, 1.0))
            for _ in range(1000)]
    yield "exp_small", exp_rows(rng, "exp_small", args)

    # seams of the reduction: a near (m + 1/2) ln(2)/2^16 (k changes), near the ends
    # of the j2 and j1 ranges and near multiples of ln 2 (e changes)
    rng = random.Random(SEED + "exp_seam")
    args = []
    for _ in range(1000):
        kind = rng.randrange(3)
        if kind == 0:
            m = rng.randrange(-70000000, 67000000)
        elif kind == 1:
            m = 256 * rng.randrange(-270000, 260000) + rng.choice((-129, -128, 127, 128))
        else:
            m = 65536 * rng.randrange(-1074, 1023) + rng.choice((-32769, -32768, 32767, 32768))
        x = (mpf(m) + mpf("0.5")) * mp.log(2) / 65536
        hi = nearest(x)
        for _ in range(rng.randrange(-3, 4) + 3):
            hi = math.nextafter(hi, rng.choice((-math.inf, math.inf)))
        if -745.0 < hi < 709.78:
            args.append(random_dd(rng, hi))
    yield "exp_seam", exp_rows(rng, "exp_seam", args)

    # large and small results: near overflow, near the end of the normal range,
    # subnormal results, results that round to zero
    rng = random.Random(SEED + "exp_edge")
    args = [random_dd(rng, rng.uniform(700.0, 709.782712893384)) for _ in range(200)]
    args += [random_dd(rng, rng.uniform(-710.0, -700.0)) for _ in range(200)]
    args += [random_dd(rng, rng.uniform(-745.1332191019411, -708.4)) for _ in range(300)]
    args += [(709.782712893384, -5e-14), (709.782712893384, 0.0), (709.78, 0.0),
             (-745.1332191019411, 0.0), (-745.0, 0.0), (-744.5, 0.0), (-708.3964185322641, 0.0),
             (-708.4, 0.0), (1024 * ln2, 0.0), (-1022 * ln2, 0.0), (-1074 * ln2, 0.0)]
    yield "exp_edge", exp_rows(rng, "exp_edge", args)

    rng = random.Random(SEED + "log_wide")
    args = [random_dd(rng, loguniform(rng, 2.3e-308, 1.7e308)) for _ in range(2000)]
    args += [(1.7976931348623157e308, 0.0), (1.7976931348623157e308, -9.9e291),
             (2.2250738585072014e-308, 0.0), (2.0, 0.0), (0.5, 0.0), (1e300, 0.0)]
    yield "log_wide", log_rows(rng, "log_wide", args)

    # a = 1 + d, |d| from 1e-32 to 0.4, either sign: ln(a) ~ d is the hard case
    rng = random.Random(SEED + "log_near1")
    args = []
    for _ in range(2000):
        d = rng.choice((-1.0, 1.0)) * loguniform(rng, 1e-32, 0.4)
        args.append(split(1 + mpf(d) * (1 + mpf(rng.random()) * mpf(2) ** -60)))
    args += [(1.0, 0.0), (1.0, 1e-30), (1.0, -1e-30), (1.0, 1.1102230246251565e-16),
             (1.0, -5.551115123125783e-17), (0.9999999999999999, 0.0), (1.0000000000000002, 0.0)]
    yield "log_near1", log_rows(rng, "log_near1", args)

    # seams: the reduction to [sqrt(1/2), sqrt(2)) and the edge |y| = ln(2)/2 of exp's
    # tables, at several binades
    rng = random.Random(SEED + "log_seam")
    args = []
    for _ in range(600):
        e = rng.randrange(-1020, 1020)
        hi = nearest(mp.sqrt(2) * mpf(2) ** e)
        for _ in range(rng.randrange(0, 8)):
            hi = math.nextafter(hi, rng.choice((-math.inf, math.inf)))
        args.append(random_dd(rng, hi))
    # ln f near (m + 1/2) ln(2)/2^16, where exp's reduction switches
    for _ in range(400):
        m = rng.randrange(-32768, 32768)
        hi = nearest(mpf(2) ** ((mpf(m) + mpf("0.5")) / 65536))
        for _ in range(rng.randrange(0, 4)):
            hi = math.nextafter(hi, rng.choice((-math.inf, math.inf)))
        args.append(random_dd(rng, hi))
    yield "log_seam", log_rows(rng, "log_seam", args)

    rng = random.Random(SEED + "log_subnormal")
    args = [(loguniform(rng, TINY_SUB, 2.2e-308), 0.0) for _ in range(300)]
    args += [(TINY_SUB, 0.0), (2.225073858507201e-308, 0.0)]
    yield "log_subnormal", log_rows(rng, "log_subnormal", args)

    rng = random.Random(SEED + "sqrt")
    args = [random_dd(rng, loguniform(rng, 1e-290, 1e300)) for _ in range(1000)]
    args += [random_dd(rng, rng.uniform(0.25, 4.0)) for _ in range(500)]
    args += [(1.0, 0.0), (4.0, 0.0), (2.0, 0.0), (1.7976931348623157e308, 0.0),
             (2.2250738585072014e-308, 0.0)]
    yield "sqrt", [row("sqrt", "sqrt", a, (0.0, 0.0), mp.sqrt(value(a))) for a in args]

    # the operators: random signs and exponents over +-2^300 (so that no result
    # leaves the normal range), and cancelling sums
    rng = random.Random(SEED + "ops")
    rows = []

    def rand_dd(span=300):
        return random_dd(rng, rng.choice((-1.0, 1.0)) * math.ldexp(rng.uniform(1.0, 2.0),
                                                                   rng.randrange(-span, span)))
    for func in ("add", "sub", "mul", "div", "addr", "mulr", "divr", "rsub", "rdiv"):
        for i in range(400):
            a = rand_dd()
            b = rand_dd()
            if func in ("add", "sub", "addr", "rsub") and i % 2 == 0:
                # cancelling: b close to -a (add) or a (sub), exponents equal
                t = value(a) * (1 + mpf(rng.uniform(-1.0, 1.0)) * mpf(2) ** -rng.randrange(1, 100))
                b = split(-t if func in ("add", "addr") else t)
                if func in ("addr", "rsub"):
                    b = (b[0], 0.0)
            elif func in ("add", "sub") and i % 4 == 1:
                # exponents close
                b = random_dd(rng, a[0] * rng.uniform(-4.0, 4.0))
            if func in ("addr", "mulr", "divr", "rsub", "rdiv"):
                b = (b[0], 0.0)
            va, vb = value(a), value(b)
            ref = {"add": va + vb, "sub": va - vb, "mul": va * vb, "div": va / vb,
                   "addr": va + vb, "mulr": va * vb, "divr": va / vb, "rsub": vb - va,
                   "rdiv": vb / va}[func]
            rows.append(row("ops", func, a, b, ref))
    yield "ops", rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--output", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                         "double_double.csv"))
    args = parser.parse_args()
    lines = ["# Reference values of the double-double arithmetic: written by "
             "test/reference/make_double_double.py (mpmath, 320 bits); do not edit.",
             "# region,func,a_hi,a_lo,b_hi,b_lo,ref_hi,ref_lo: ref_hi + ref_lo is the exact "
             "func(a, b) at the double-double inputs a = a_hi + a_lo, b = b_hi + b_lo"]
    count = 0
    for _, rows in regions():
        lines += rows
        count += len(rows)
    with open(args.output, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print(f"wrote {count} rows to {args.output}", file=sys.stderr)


if __name__ == "__main__":
    main()
