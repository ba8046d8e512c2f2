#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Reference values of the damping rules of multibody codes
(src/hcimpact/model/legacy_damping.f90, doc/legacy-models.md).

Writes ``legacy_damping.csv`` next to this script (or to ``--output``): one row per
test point, ``region,rule,e,ref_hi,ref_lo``, where ``e`` is the target restitution (an
exact double), ``rule`` is ``r1`` ... ``r8`` and ``ref_hi + ref_lo`` is the rule's
chi(e) at that double, ref_hi the nearest double and ref_lo the nearest double to the
rest (``inf,0`` where chi exceeds the double range). See README.md in this directory.

The rules (the module's comment, evaluated exactly):

    1 Hunt-Crossley        3(1-e)/2             5 Zhiying-Qishao  3(1-e^2) exp(2(1-e))/4
    2 Herbert-McWhannell   6(1-e)/((2e-1)^2+3)  6 Flores et al.   8(1-e)/(5e)
    3 Lankarani-Nikravesh  3(1-e^2)/4           7 Hu-Guo          3(1-e)/(2e)
    4 Gonthier et al.      (1-e^2)/e            8 Carvalho-Martins 3(1-e)(11-e)/(2(1+9e))

Regions of e (every rule at every point):

    one        e = 1 exactly (chi = 0)
    near1      e = 1 - k 2^-53 (k = 1 ... 64), 1 - 2^-j (j = 1 ... 52), and e = 1 - d for
               d log-uniform in [2^-53, 1e-2]: where 1 - e^2 loses its digits
    uniform    e uniform in (0, 1)
    small      e log-uniform in [1e-300, 1e-2]
    subnormal  e from 2^-1074 up to the smallest normals, with the thresholds where
               rules 4, 6 and 7 overflow

Computed with mpmath at 200 bits (e is exact, the rules are rational but for rule 5's
exponential, whose argument 2(1-e) is exact too). Deterministic (random.Random seeded
with a fixed string); requires mpmath only; about a second.
"""

import argparse
import math
import os
import random
import sys

from mpmath import mp, mpf, exp

from doubles import nearest_double

mp.prec = 200

#: Seed of every region (each region mixes in its own name)
SEED = "hcimpact-legacy-damping-1"

#: Largest double and the exact value halfway to the next power of two: above it a
#: value rounds to infinity
MAX_DOUBLE = mpf(sys.float_info.max)
OVERFLOW = MAX_DOUBLE + mpf(2) ** 970


def rule(number, e):
    """chi(e) of rule `number`, exact at the double e (mpf)."""
    one = mpf(1)
    if number == 1:
        return 3 * (one - e) / 2
    if number == 2:
        return 6 * (one - e) / ((2 * e - 1) ** 2 + 3)
    if number == 3:
        return 3 * (one - e * e) / 4
    if number == 4:
        return (one - e * e) / e
    if number == 5:
        return 3 * (one - e * e) * exp(2 * (one - e)) / 4
    if number == 6:
        return 8 * (one - e) / (5 * e)
    if number == 7:
        return 3 * (one - e) / (2 * e)
    if number == 8:
        return 3 * (one - e) * (11 - e) / (2 * (1 + 9 * e))
    raise ValueError(number)


def split(x):
    """x as (hi, lo): the nearest double and the nearest double to the rest; (inf, 0)
    beyond the double range."""
    if x >= OVERFLOW:
        return math.inf, 0.0
    hi = nearest_double(x)
    return hi, nearest_double(x - mpf(hi))


def points():
    """(region, e) pairs, in a fixed order."""
    yield "one", 1.0
    for k in range(1, 65):
        yield "near1", 1.0 - k * 2.0 ** -53
    for j in range(1, 53):
        yield "near1", 1.0 - 2.0 ** -j
    rng = random.Random(SEED + "near1")
    for _ in range(300):
        d = math.exp(rng.uniform(math.log(2.0 ** -53), math.log(1e-2)))
        yield "near1", 1.0 - d
    # the points of issue 13
    yield "near1", 0.9857
    yield "near1", 1.0 - 7.7e-9
    rng = random.Random(SEED + "uniform")
    for _ in range(400):
        e = rng.random()
        if e > 0.0:
            yield "uniform", e
    rng = random.Random(SEED + "small")
    for _ in range(200):
        yield "small", math.exp(rng.uniform(math.log(1e-300), math.log(1e-2)))
    # subnormal e, the thresholds of overflow of 1/e (2^-1024) and 1.6/e, and the
    # smallest normal numbers
    for k in (0, 1, 2, 10, 30, 48, 49, 50, 51):
        yield "subnormal", math.ldexp(1.0, -1074 + k)
    for m in (1.0, 1.25, 1.5, 1.6, 1.75, 2.0 - 2.0 ** -52):
        yield "subnormal", math.ldexp(m, -1025)
        yield "subnormal", math.ldexp(m, -1024)
    yield "subnormal", math.ldexp(1.0, -1022) - math.ldexp(1.0, -1074)
    for k in (-1022, -1021, -1000):
        yield "subnormal", math.ldexp(1.0, k)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=os.path.join(os.path.dirname(
        os.path.abspath(__file__)), "legacy_damping.csv"))
    args = parser.parse_args()
    rows = []
    for region, e in points():
        for number in range(1, 9):
            hi, lo = split(rule(number, mpf(e)))
            rows.append(f"{region},r{number},{e!r},{hi!r},{lo!r}")
    with open(args.output, "w", encoding="ascii") as out:
        out.write("# Written by test/reference/make_legacy_damping.py: the damping rules of\n")
        out.write("# src/hcimpact/model/legacy_damping.f90 at exact double e, by mpmath at 200 bits.\n")
        out.write("# region,rule,e,ref_hi,ref_lo (ref_hi + ref_lo = chi(e); inf,0: overflow)\n")
        out.write("\n".join(rows) + "\n")
    print(f"{len(rows)} rows written to {args.output}")


if __name__ == "__main__":
    main()
