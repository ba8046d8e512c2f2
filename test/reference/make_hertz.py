#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Reference values of the two-body functions (src/hcimpact/model/hertz.f90).

Writes ``hertz.csv`` next to this script (or to ``--output``): one row per test
point, ``region,func,x1,x2,x3,x4,x5,x6,ref_hi,ref_lo``. The inputs are doubles
(unused ones 0), ``ref_hi`` is the exact value at those doubles rounded to the
nearest double (``inf`` beyond the largest double) and ``ref_lo`` the rest rounded
to the nearest double. See README.md in this directory.

func (what the Fortran test evaluates)
    hertz            hertz_constant(E1, nu1, R1, E2, nu2, R2) = x1 .. x6 (R = inf: a plate)
    effective_mass   effective_mass(m1, m2) = x1, x2 (m2 = inf: a wall)
    v1_after         velocity1_after of two_body_velocities(m1, m2, v1, v2, k) = x1 .. x5
    v2_after         velocity2_after of the same

The effective mass and the velocities after the impact are rational functions of the
inputs: computed exactly with fractions.Fraction, rounded by Python's correctly
rounded int/int division, and checked exactly against both neighbours of the result
(ties to even). No finite precision would do: equal masses put some results exactly
halfway between two doubles, nearly equal ones within 2^-400 of halfway. Hertz's constant
is c = (4/3) sqrt(Q)/S with the rationals Q = R1 R2/(R1 + R2) (R1 for a plate R2) and
S = (1 - nu1^2)/E1 + (1 - nu2^2)/E2: c^2 is formed exactly, its square root by mpmath
at 400 bits, and checked against the textbook formula (4/3)/(S sqrt(1/R1 + 1/R2))
evaluated by mpmath at 300 bits from the doubles (no overflow in mpmath). The two must
agree to 1e-80 relative, or the script stops.

Deterministic: each region draws from its own random.Random seeded with a fixed string
and the region's name. Requires mpmath only; about 10 s.
"""

import argparse
import math
import os
import random
import sys
from fractions import Fraction

from mpmath import mp, mpf

from doubles import is_even, nearest_double

mp.prec = 400

#: Seed shared by every region (each region mixes in its own name)
SEED = "hcimpact-hertz-1"

#: The largest double, and the smallest positive subnormal
DBL_MAX = sys.float_info.max
TINY_SUB = math.ldexp(1.0, -1074)
INF = math.inf

#: Values from 2^1024 (1 - 2^-54) up round to infinity
OVERFLOW = Fraction(2**1024) - Fraction(2**969)


def rng_for(region):
    return random.Random(f"{SEED}:{region}")


def random_double(rng, e_lo, e_hi):
    """A positive double with a binary exponent uniform in [e_lo, e_hi] (frexp's
    convention, x = f 2^e with f in [1/2, 1)) and a random significand; exponents
    below -1021 give subnormals with the bits they can hold."""
    e = rng.randint(e_lo, e_hi)
    if e >= -1021:
        return math.ldexp(0.5 + rng.getrandbits(52) / 2.0**53, e)
    # subnormal: an integer multiple of 2^-1074 in [2^(e-1), 2^e)
    bits = e + 1074
    n = rng.randint(2 ** (bits - 1), 2**bits - 1)
    return math.ldexp(float(n), -1074)


def loguniform(rng, lo, hi):
    """A double log-uniform in [lo, hi] (0 < lo < hi, both normal)."""
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def split_fraction(q):
    """The rational q as (hi, lo): q rounded to the nearest double (inf beyond the
    largest), and the rest rounded to the nearest double; checked against mpmath."""
    if abs(q) >= OVERFLOW:
        return (INF if q > 0 else -INF), 0.0
    hi = float(q)        # int/int true division: correctly rounded, subnormals included
    check_nearest(q, hi)
    rest = q - Fraction(hi)
    lo = float(rest) if rest != 0 else 0.0
    return hi, lo


def check_nearest(q, x):
    """Stop unless the double x is the rational q rounded to nearest, ties to even
    (compared exactly with both neighbours of x)."""
    error = abs(q - Fraction(x))
    for other in (math.nextafter(x, -INF), math.nextafter(x, INF)):
        if math.isinf(other):
            continue
        other_error = abs(q - Fraction(other))
        if other_error < error or (other_error == error and is_even(other)):
            raise SystemExit(f"{x!r} is not the nearest double to {q}")


def split_mpf(x):
    """A positive mpf as (hi, lo), inf beyond the largest double."""
    if x >= mpf(OVERFLOW.numerator) / OVERFLOW.denominator:
        return INF, 0.0
    hi = nearest_double(x)
    lo = nearest_double(x - mpf(hi)) if hi != 0 else 0.0
    return hi, lo


# ---------------------------------------------------------------------------
# The exact values
# ---------------------------------------------------------------------------


def hertz(e1, nu1, r1, e2, nu2, r2):
    """Hertz's constant at the doubles, as (hi, lo)."""
    s = (1 - Fraction(nu1) ** 2) / Fraction(e1) + (1 - Fraction(nu2) ** 2) / Fraction(e2)
    if math.isinf(r1):
        q = Fraction(r2)
    elif math.isinf(r2):
        q = Fraction(r1)
    else:
        q = Fraction(r1) * Fraction(r2) / (Fraction(r1) + Fraction(r2))
    c2 = Fraction(16, 9) * q / (s * s)
    c = mp.sqrt(mpf(c2.numerator) / mpf(c2.denominator))
    # method B: the textbook formula in mpmath from the doubles, at another precision
    with mp.workprec(300):
        curvature = (0 if math.isinf(r1) else 1 / mpf(r1)) + (0 if math.isinf(r2) else 1 / mpf(r2))
        compliance = (1 - mpf(nu1) ** 2) / mpf(e1) + (1 - mpf(nu2) ** 2) / mpf(e2)
        other = (mpf(4) / 3) / (compliance * mp.sqrt(curvature))
    if abs(other / c - 1) > mpf(10) ** -80:
        raise SystemExit(f"hertz: the two methods disagree at {(e1, nu1, r1, e2, nu2, r2)}")
    return split_mpf(c)


def log2_hertz(e1, nu1, r1, e2, nu2, r2):
    """log2 of Hertz's constant within a few units (to select points cheaply)."""
    def log2(x):
        return math.log2(x) if x >= 2.0**-1022 else math.log2(x * 2.0**100) - 100
    terms = [math.log2((1 - nu) * (1 + nu)) - log2(e) for e, nu in ((e1, nu1), (e2, nu2))]
    log_s = max(terms) + math.log2(1 + 2.0 ** (min(terms) - max(terms)))
    log_q = min(log2(r) for r in (r1, r2))
    return 0.5 * log_q - log_s


def effective_mass(m1, m2):
    if math.isinf(m2):
        return split_fraction(Fraction(m1))
    a, b = Fraction(m1), Fraction(m2)
    return split_fraction(a * b / (a + b))


def velocities(m1, m2, v1, v2, k):
    """(v1', v2') exactly: v1' = v1 - (1 + k)(v1 - v2) m2/(m1 + m2), v2' likewise."""
    v1f, v2f, kf = Fraction(v1), Fraction(v2), Fraction(k)
    exchange = (1 + kf) * (v1f - v2f)
    if math.isinf(m2):
        share1, share2 = Fraction(0), Fraction(1)
    else:
        a, b = Fraction(m1), Fraction(m2)
        share1, share2 = a / (a + b), b / (a + b)
    return split_fraction(v1f - exchange * share2), split_fraction(v2f + exchange * share1)


# ---------------------------------------------------------------------------
# Regions
# ---------------------------------------------------------------------------


def poisson_uniform(rng):
    """nu uniform in (-1, 0.5]."""
    while True:
        nu = rng.uniform(-1.0, 0.5)
        if nu > -1.0:
            return nu


def poisson_edge(rng):
    """nu within a power of two of -1 or of 1/2 (or exactly 1/2)."""
    j = rng.randint(1, 53)
    u = rng.random()
    choice = rng.randrange(3)
    if choice == 0:
        nu = -1.0 + math.ldexp(0.5 + u / 2, -j)      # -1 + [2^(-j-1), 2^-j)
    elif choice == 1:
        nu = 0.5 - math.ldexp(0.5 + u / 2, -j - 1)
    else:
        nu = 0.5
    return nu if nu > -1.0 else math.nextafter(-1.0, 0.0)


def hertz_rows(region, rng, count, draw):
    rows = []
    while len(rows) < count:
        args = draw(rng)
        if math.isinf(args[2]) and math.isinf(args[5]):
            continue
        hi, lo = hertz(*args)
        rows.append((region, "hertz", *args, hi, lo))
    return rows


def hertz_regions():
    rows = []

    def steel(rng):
        r2 = INF if rng.random() < 0.25 else loguniform(rng, 1e-6, 10.0)
        return (loguniform(rng, 1e6, 1e12), rng.uniform(-0.5, 0.5), loguniform(rng, 1e-6, 10.0),
                loguniform(rng, 1e6, 1e12), rng.uniform(-0.5, 0.5), r2)

    def wide(rng):
        r2 = INF if rng.random() < 0.2 else random_double(rng, -1073, 1024)
        return (random_double(rng, -1073, 1024), poisson_uniform(rng), random_double(rng, -1073, 1024),
                random_double(rng, -1073, 1024), poisson_uniform(rng), r2)

    def nu_edges(rng):
        r2 = INF if rng.random() < 0.25 else loguniform(rng, 1e-6, 10.0)
        nu2 = poisson_edge(rng) if rng.random() < 0.5 else poisson_uniform(rng)
        return (loguniform(rng, 1e6, 1e12), poisson_edge(rng), loguniform(rng, 1e-6, 10.0),
                loguniform(rng, 1e6, 1e12), nu2, r2)

    def subnormal(rng):
        def pick():
            return random_double(rng, -1073, -1022) if rng.random() < 0.6 else random_double(rng, -1073, 1024)
        r2 = INF if rng.random() < 0.2 else pick()
        return (pick(), poisson_uniform(rng), pick(), pick(), poisson_uniform(rng), r2)

    rows += hertz_rows("steel", rng_for("hertz-steel"), 1000, steel)
    rows += hertz_rows("wide", rng_for("hertz-wide"), 2000, wide)
    rows += hertz_rows("nu_edges", rng_for("hertz-nu-edges"), 1000, nu_edges)
    rows += hertz_rows("subnormal", rng_for("hertz-subnormal"), 500, subnormal)

    # results near the ends of the doubles: drawn from `wide`, kept by the size of c
    big, small = [], []
    rng = rng_for("hertz-extreme")
    while len(big) < 300 or len(small) < 300:
        args = wide(rng)
        if math.isinf(args[2]) and math.isinf(args[5]):
            continue
        if abs(log2_hertz(*args)) < 990:
            continue
        hi, lo = hertz(*args)
        if hi >= 2.0**1000 and len(big) < 300:
            big.append(("extreme", "hertz", *args, hi, lo))
        elif 0 < hi <= 2.0**-1000 and len(small) < 300:
            small.append(("extreme", "hertz", *args, hi, lo))
    rows += big + small

    steel_e, steel_nu = 2e11, 0.25
    edge = [
        (steel_e, steel_nu, 0.01452, steel_e, steel_nu, INF),          # the seed's example
        (steel_e, steel_nu, INF, steel_e, steel_nu, 0.01452),
        (steel_e, steel_nu, 0.01452, steel_e, steel_nu, 5e-324),       # issue 13: 3.16e-151
        (steel_e, steel_nu, 5e-324, steel_e, steel_nu, 5e-324),
        (steel_e, steel_nu, DBL_MAX, steel_e, steel_nu, INF),
        (steel_e, math.nextafter(-1.0, 0.0), 0.01, steel_e, math.nextafter(-1.0, 0.0), 0.02),
        (steel_e, -0.9999999, 0.01452, steel_e, -0.9999999999, INF),   # issue 27, auxetic
        (steel_e, 0.5, 0.01, 1e9, 0.5, 0.01),
        (DBL_MAX, 0.25, DBL_MAX, DBL_MAX, 0.25, INF),                  # c beyond the doubles
        (5e-324, 0.25, 0.01, 5e-324, 0.25, INF),                       # subnormal moduli
        (5e-324, 0.25, 5e-324, DBL_MAX, 0.5, 5e-324),
        (DBL_MAX, math.nextafter(-1.0, 0.0), 0.01, DBL_MAX, math.nextafter(-1.0, 0.0), INF),
    ]
    rows += [("edge", "hertz", *args, *hertz(*args)) for args in edge]
    return rows


def effective_mass_regions():
    rows = []

    def add(region, rng, count, draw):
        for _ in range(count):
            m1, m2 = draw(rng)
            rows.append((region, "effective_mass", m1, m2, 0.0, 0.0, 0.0, 0.0, *effective_mass(m1, m2)))

    add("typical", rng_for("mass-typical"), 1000,
        lambda rng: (loguniform(rng, 1e-6, 1e6), loguniform(rng, 1e-6, 1e6)))
    add("wide", rng_for("mass-wide"), 2000,
        lambda rng: (random_double(rng, -1073, 1024),
                     INF if rng.random() < 0.1 else random_double(rng, -1073, 1024)))
    add("subnormal", rng_for("mass-subnormal"), 500,
        lambda rng: (random_double(rng, -1073, -1022),
                     random_double(rng, -1073, -1022) if rng.random() < 0.5 else random_double(rng, -1073, 1024)))
    add("near_overflow", rng_for("mass-near-overflow"), 300,
        lambda rng: (random_double(rng, 1020, 1024),
                     random_double(rng, 1020, 1024) if rng.random() < 0.7 else random_double(rng, -1073, 1024)))
    edge = [(1e300, 1e-20), (DBL_MAX, 0.5), (1.0, 1e-310),             # issue 8
            (0.1, INF), (1.0, 1.0), (DBL_MAX, DBL_MAX), (5e-324, 5e-324), (5e-324, DBL_MAX),
            (DBL_MAX, 5e-324), (3e-310, 1e-310), (0.1, 0.2)]
    rows += [("edge", "effective_mass", m1, m2, 0.0, 0.0, 0.0, 0.0, *effective_mass(m1, m2))
             for m1, m2 in edge]
    return rows


def velocity_rows(region, args):
    (h1, l1), (h2, l2) = velocities(*args)
    return [(region, "v1_after", *args, 0.0, h1, l1), (region, "v2_after", *args, 0.0, h2, l2)]


def two_body_regions():
    rows = []

    def signed(rng, e_lo, e_hi):
        x = random_double(rng, e_lo, e_hi)
        return x if rng.random() < 0.5 else -x

    def restitution(rng):
        u = rng.random()
        return 0.0 if u < 0.05 else 1.0 if u < 0.1 else rng.random()

    def approaching(v1, v2):
        return (v1, v2) if v1 > v2 else (v2, v1)

    def add(region, rng, count, draw):
        n = 0
        while n < count:
            m1, m2, v1, v2, k = draw(rng)
            if v1 == v2:
                continue
            v1, v2 = approaching(v1, v2)
            rows.extend(velocity_rows(region, (m1, m2, v1, v2, k)))
            n += 1

    add("typical", rng_for("v-typical"), 1000,
        lambda rng: (loguniform(rng, 1e-3, 1e3), loguniform(rng, 1e-3, 1e3),
                     rng.uniform(-100, 100), rng.uniform(-100, 100), restitution(rng)))
    add("wide", rng_for("v-wide"), 2000,
        lambda rng: (random_double(rng, -1073, 1024),
                     INF if rng.random() < 0.1 else random_double(rng, -1073, 1024),
                     signed(rng, -1073, 1024), signed(rng, -1073, 1024), restitution(rng)))
    add("subnormal", rng_for("v-subnormal"), 500,
        lambda rng: (random_double(rng, -1073, -1022) if rng.random() < 0.5 else random_double(rng, -1073, 1024),
                     random_double(rng, -1073, -1022) if rng.random() < 0.5 else random_double(rng, -1073, 1024),
                     signed(rng, -1073, -1022), signed(rng, -1073, -1000), restitution(rng)))
    add("near_overflow", rng_for("v-near-overflow"), 500,
        lambda rng: (random_double(rng, -1073, 1024), random_double(rng, -1073, 1024),
                     signed(rng, 1018, 1024), signed(rng, 1018, 1024), restitution(rng)))
    # body 1 stops (k = m1/m2, v2 = 0), or body 2 does (v2 = -v1 m1 (1 + k)/(m2 - k m1)):
    # the terms of the centre-of-mass form cancel to the rounding of k or v2, or to 0
    rng = rng_for("v-cancel")
    for _ in range(500):
        m1, m2 = sorted((loguniform(rng, 1e-3, 1e3), loguniform(rng, 1e-3, 1e3)))
        v1 = rng.uniform(1e-3, 100.0)
        k = m1 / m2
        rows.extend(velocity_rows("cancel", (m1, m2, v1, 0.0, k)))
        k = rng.random()
        if m2 > k * m1:
            v2 = -v1 * m1 * (1 + k) / (m2 - k * m1)
            if v2 < v1:
                rows.extend(velocity_rows("cancel", (m1, m2, v1, v2, k)))
    edge = [(1e300, 1e-300, 1.0, 0.0, 1.0), (1.0, 5e-324, 1.0, 0.0, 0.5),   # issue 7
            (1.0, 1.0, DBL_MAX, -DBL_MAX, 0.5),
            (1.0, 1.0, 1.0, -1.0, 0.5), (0.1, INF, 5.0, 0.0, 0.75), (1.0, 1.0, 2.0, 0.0, 1.0),
            (1.0, 1.0, 2.0, 0.0, 0.0), (1.0, 1e10, DBL_MAX, -DBL_MAX, 1.0),
            (5e-324, 5e-324, 5e-324, -5e-324, 1.0), (1e-300, 1e10, 1e300, 0.0, 1.0)]
    for args in edge:
        rows.extend(velocity_rows("edge", args))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--output", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                         "hertz.csv"))
    args = parser.parse_args()
    rows = hertz_regions() + effective_mass_regions() + two_body_regions()
    with open(args.output, "w") as fh:
        fh.write("# Reference values of hcimpact_hertz: written by test/reference/make_hertz.py "
                 "(exact rationals, mpmath at 400 bits); do not edit.\n")
        fh.write("# region,func,x1,x2,x3,x4,x5,x6,ref_hi,ref_lo: ref_hi + ref_lo is the exact "
                 "value of func at the double inputs x1..x6 (unused: 0); inf beyond the largest double\n")
        for row in rows:
            fh.write(",".join([row[0], row[1]] + [repr(float(x)) for x in row[2:]]) + "\n")
    print(f"{args.output}: {len(rows)} rows")


if __name__ == "__main__":
    main()
