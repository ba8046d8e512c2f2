#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""High-precision references of the contact-force element (hcimpact_contact_force).

For the power law f = c x^n, damping b, deformation x and deformation rate v:

    F = c x^n max(0, 1 + b v)          dF/dx, dF/dv
    Pi = c x^(n+1)/(n+1)               dissipation (F - c x^n) v

at exact double inputs, in 60-digit arithmetic. The derivatives are not taken from
their formulas: they come from mpmath's numerical differentiation of F (steps relative
to x and to 1 + b v, far below the distance to the kink at 1 + b v = 0), and the
potential from quadrature (checked against its closed form), so they check the
library's formulas independently. Regions:

    typical   the physical range (c 1 .. 1e12, n 0.5 .. 3 and 1, 1.5, 2, b 0 .. 10,
              x 1e-9 .. 1e-2, v of both signs)
    clamp     1 + b v = +-delta with delta 1e-16 .. 1e-1 (the naive 1 + b*v cancels)
    small_x   n 0.05 .. 1 and x down to 1e-300 (dF/dx grows without bound)
    extreme   every argument over the whole double range (results beyond it are
              written as inf, below the smallest subnormal as 0)
    edges     subnormal and largest arguments, n at its bounds, v = 0, b = 0
    underflow the force or the potential next to half the smallest subnormal

Writes contact_force.csv next to this script: rows `region,all,c,n,b,x,v,` then
(hi, lo) of F, dF/dx, dF/dv, Pi, dissipation. Usage: python3 make_contact_force.py
"""
import math
import os
import random
import sys

import mpmath as M
from mpmath import mp, mpf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doubles import split_double  # noqa: E402

mp.dps = 60
HERE = os.path.dirname(os.path.abspath(__file__))
SEED = 20261125
MAX = mpf(sys.float_info.max)
MIN_SUB = mpf(2) ** -1074


def exact_pair(x):
    """(hi, lo) of an mpf, with inf for values beyond the double range."""
    if x > MAX * (1 + mpf(2) ** -54):
        return math.inf, 0.0
    if x < -MAX * (1 + mpf(2) ** -54):
        return -math.inf, 0.0
    if abs(x) < MIN_SUB / 2:
        return 0.0, 0.0
    return split_double(x)


def force(c, n, b, x, v):
    if x <= 0:
        return mpf(0)
    return c * x ** n * max(mpf(0), 1 + b * v)


def element(c, n, b, x, v):
    c, n, b, x, v = (mpf(t) for t in (c, n, b, x, v))
    if x <= 0:
        return [mpf(0)] * 5
    f = c * x ** n
    s = 1 + b * v
    big_f = force(c, n, b, x, v)
    # derivatives by numerical differentiation of F (not from the formulas)
    if s > 0:
        # relative steps: x (1 + t), and v + u with b u = 1e-25 (1 + b v)
        dfdx = M.diff(lambda t: force(c, n, b, x * (1 + t), v), 0, h=mpf(10) ** -25) / x
        if b > 0:
            h = mpf(10) ** -25 * s / b
            dfdv = M.diff(lambda u: force(c, n, b, x, v + u), 0, h=h)
        else:
            dfdv = mpf(0)
    else:
        dfdx = mpf(0)
        dfdv = mpf(0)
    # the potential by quadrature, c x^(n+1) times the integral of u^n on [0, 1],
    # checked against the closed form c x^(n+1)/(n+1)
    potential = c * x ** n * x * M.quad(lambda u: u ** n, [0, 1])
    closed = c * x ** (n + 1) / (n + 1)
    assert abs(potential - closed) <= mpf(10) ** -40 * closed, (c, n, x)
    # (F - f(x)) v by its definition, in enough digits that F - f(x) keeps 60 of them
    # however small b v is
    lost = int(max(0, -M.log10(abs(b * v)))) if b * v != 0 else 0
    with mp.workdps(mp.dps + lost + 10):
        dissipation = (force(c, n, b, x, v) - c * x ** n) * v
    return [big_f, dfdx, dfdv, potential, dissipation]


def log_uniform(rng, lo, hi):
    return 10.0 ** rng.uniform(lo, hi)


def rows(rng):
    out = []
    # typical
    for _ in range(400):
        c = log_uniform(rng, 0, 12)
        n = rng.choice([1.0, 1.5, 2.0, rng.uniform(0.5, 3.0)])
        b = rng.choice([0.0, log_uniform(rng, -4, 1)])
        x = log_uniform(rng, -9, -2)
        v = rng.choice([-1, 1]) * log_uniform(rng, -4, 2)
        out.append(("typical", c, n, b, x, v))
    # next to the clamp: 1 + b v = +-delta
    for _ in range(300):
        c = log_uniform(rng, 0, 12)
        n = rng.choice([1.0, 1.5, rng.uniform(0.3, 4.0)])
        b = log_uniform(rng, -3, 3)
        x = log_uniform(rng, -8, -3)
        delta = rng.choice([-1, 1]) * log_uniform(rng, -16, -1)
        v = float(-(1 + mpf(delta)) / mpf(b))
        out.append(("clamp", c, n, b, x, v))
    # small x, n < 1
    for _ in range(150):
        c = log_uniform(rng, 0, 12)
        n = rng.uniform(0.05, 1.0)
        b = log_uniform(rng, -3, 1)
        x = log_uniform(rng, -300, -10)
        v = rng.choice([-1, 1]) * log_uniform(rng, -3, 1)
        out.append(("small_x", c, n, b, x, v))
    # the whole double range
    for _ in range(400):
        c = log_uniform(rng, -300, 300)
        n = log_uniform(rng, -6, 1.3)
        b = rng.choice([0.0, log_uniform(rng, -300, 300)])
        x = log_uniform(rng, -300, 300)
        v = rng.choice([-1, 1]) * log_uniform(rng, -300, 300)
        out.append(("extreme", c, n, b, x, v))
    # edges
    tiny, big = 5e-324, sys.float_info.max
    for c in (tiny, 1.0, big):
        for n in (1e-6, 1.0, 20.0):
            for x in (tiny, 2.2250738585072014e-308, 1e-3, 1.0, big):
                for b, v in ((0.0, 0.0), (1.0, -0.5), (0.5, big), (big, 1.0), (tiny, -1.0)):
                    out.append(("edges", c, n, b, x, v))
    # results next to half the smallest subnormal, 2^-1075: the force (or with
    # target Pi the potential) at 2^-1090 .. 2^-1060, where the library decides 0
    # from the binary exponents alone or takes the logarithms
    for _ in range(240):
        c = log_uniform(rng, -12, 12)
        n = rng.choice([1.0, 1.5, rng.uniform(0.3, 4.0)])
        b = rng.choice([0.0, log_uniform(rng, -4, 2)])
        v = rng.choice([-1, 1]) * log_uniform(rng, -4, 1)
        factor = abs(1 + mpf(b) * mpf(v))
        if factor == 0:
            factor = mpf(1)
        target = mpf(2) ** rng.uniform(-1090, -1060)
        if rng.random() < 0.5:
            x = (target / (c * factor)) ** (1 / mpf(n))
        else:
            x = (target * (n + 1) / c) ** (1 / mpf(n + 1))
        x = float(x)
        if x > 0:
            out.append(("underflow", c, n, b, x, v))
    return out


def main():
    rng = random.Random(SEED)
    path = os.path.join(HERE, "contact_force.csv")
    lines = ["# contact-force element references (make_contact_force.py, mpmath "
             f"{M.__version__}, {mp.dps} digits, seed {SEED})",
             "# region,all,c,n,b,x,v, then hi,lo of F, dF/dx, dF/dv, Pi, dissipation"]
    count = 0
    for region, c, n, b, x, v in rows(rng):
        values = element(c, n, b, x, v)
        fields = [region, "all"] + [repr(float(t)) for t in (c, n, b, x, v)]
        for value in values:
            hi, lo = exact_pair(value)
            fields += [repr(hi), repr(lo)]
        lines.append(",".join(fields))
        count += 1
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")
    print(f"wrote {count} rows to {os.path.relpath(path)}", file=sys.stderr)


if __name__ == "__main__":
    main()
