#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Accuracy of scipy.special.lambertw on the mpmath reference test/reference/lambertw.csv.

Usage: scipy_accuracy.py [path/to/lambertw.csv]     (Markdown on stdout)

Same rules as bench/lambertw/peers_accuracy.cpp:
  * the result is scipy.special.lambertw(z, k).real with k = 0 (w0, w0p1) or
    k = -1 (wm1, wm1p1) and SciPy's default tolerance;
  * for the 1+W forms (w0p1, wm1p1, where the CSV's x is t) a user without a
    1+W function computes 1 + W(-exp(-1 - t)) with z rounded to double; exp is
    the C library's (math.exp), as in the C++ program;
  * error in ulps = |(y - ref_hi) - ref_lo| / ulp(ref), ulp(ref) the spacing of
    the doubles at the exact reference ref_hi + ref_lo: nextafter(|ref_hi|, inf)
    - |ref_hi|, halved when |ref_hi| is a normal power of two and ref_lo has the
    opposite sign; 2**-1074 for ref = 0; the spacing below at DBL_MAX;
  * "fail": an exception, or NaN/inf where the reference is finite (left out of
    max/median); where the reference is NaN, NaN or an exception counts as
    0 ulp and a finite result as a fail; an infinite reference needs an equal
    result;
  * "complex": points where SciPy's result has a nonzero (non-NaN) imaginary
    part (the table still scores .real, as a user taking .real would get).
"""

import math
import sys
import warnings

import numpy as np
import scipy
import scipy.special

FUNCS = ("w0", "wm1", "w0p1", "wm1p1")
DBL_MAX = sys.float_info.max
DBL_MIN = sys.float_info.min
DENORM_MIN = 5e-324


def parse_float(s):
    s = s.strip()
    try:
        return float(s)
    except ValueError:
        return float.fromhex(s)  # hexadecimal floats, as C's strtod accepts


def read_csv(path):
    rows = []
    with open(path) as fh:
        for lineno, line in enumerate(fh, 1):
            t = line.strip()
            if not t or t.startswith("#"):
                continue
            field = [f.strip() for f in t.split(",")]
            if field[0] == "region":
                continue
            try:
                if len(field) < 5:
                    raise ValueError("too few fields")
                x, hi, lo = (parse_float(f) for f in field[2:5])
            except ValueError:
                print(f"{path}:{lineno}: malformed row skipped: {t}", file=sys.stderr)
                continue
            if field[1] not in FUNCS:
                print(f"{path}:{lineno}: unknown func '{field[1]}' skipped", file=sys.stderr)
                continue
            rows.append((field[0], field[1], x, hi, lo))
    return rows


def ulp_at(hi, lo):
    a = abs(hi)
    if a == 0.0:
        return DENORM_MIN
    if a == DBL_MAX:
        return a - math.nextafter(a, 0.0)
    u = math.nextafter(a, math.inf) - a
    pow2 = math.frexp(a)[0] == 0.5
    below = lo != 0.0 and math.copysign(1.0, lo) != math.copysign(1.0, hi)
    if pow2 and below and a > DBL_MIN:
        u *= 0.5
    return u


def ulp_error(hi, lo, y, threw):
    """(failed, error in ulps)"""
    if math.isnan(hi):
        return (not (threw or math.isnan(y))), 0.0
    if threw or math.isnan(y):
        return True, 0.0
    if math.isinf(hi):
        return y != hi, 0.0
    if math.isinf(y):
        return True, 0.0
    return False, abs((y - hi) - lo) / ulp_at(hi, lo)


def evaluate(func, x):
    """(y, threw, complex) for one row"""
    k = 0 if func in ("w0", "w0p1") else -1
    p1 = func in ("w0p1", "wm1p1")
    try:
        z = -math.exp(-1.0 - x) if p1 else x
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            w = complex(scipy.special.lambertw(z, k))
    except Exception:  # noqa: BLE001 - any exception is a failed evaluation
        return math.nan, True, False
    y = w.real
    return (1.0 + y if p1 else y), False, (w.imag != 0.0 and not math.isnan(w.imag))


def fmt_ulp(u):
    if u is None:
        return "–"
    if u == 0.0:
        return "0"
    if u < 10.0:
        return f"{u:.2f}"
    if u < 1e4:
        return f"{u:.0f}"
    return f"{u:.1e}"


def fmt_g(v):
    return "%.17g" % v


def main(argv):
    path = argv[1] if len(argv) > 1 else "test/reference/lambertw.csv"
    try:
        rows = read_csv(path)
    except OSError as e:
        print(f"cannot open {path}: {e}", file=sys.stderr)
        return 1
    if not rows:
        print(f"{path}: no data rows", file=sys.stderr)
        return 1

    groups = []
    members = {}
    for f in FUNCS:
        for r in rows:
            if r[1] != f:
                continue
            key = (r[1], r[0])
            if key not in members:
                groups.append(key)
                members[key] = []
            members[key].append(r)

    print(f"### SciPy accuracy against the mpmath reference ({path}, {len(rows)} points)\n")
    print(f"SciPy {scipy.__version__}, NumPy {np.__version__}: scipy.special.lambertw(z, k).real, "
          "k = 0 or -1, default tol. Same error measure and \"fail\" rule as the table above; "
          "\"complex\" = points whose result had a nonzero imaginary part (.real still scored). "
          "1+W forms: 1 + W(-exp(-1-t)) with z rounded to double.\n")
    print("| func | region | n | SciPy max | SciPy median | fail | complex | worst x (t for 1+W) | result | reference (hi) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for key in groups:
        errs = []
        fails = 0
        ncomplex = 0
        worst = None  # (err or inf, x, y, hi, threw)
        for (_, func, x, hi, lo) in members[key]:
            y, threw, cplx = evaluate(func, x)
            ncomplex += bool(cplx)
            failed, err = ulp_error(hi, lo, y, threw)
            if failed:
                fails += 1
                if worst is None or worst[0] != math.inf:
                    worst = (math.inf, x, y, hi, threw)
                continue
            errs.append(err)
            if worst is None or (worst[0] != math.inf and err > worst[0]):
                worst = (err, x, y, hi, threw)
        emax = max(errs) if errs else None
        emed = float(np.median(errs)) if errs else None
        wx = fmt_g(worst[1])
        wy = "exception" if worst[4] else fmt_g(worst[2])
        if worst[0] == math.inf:
            wy += " (fail)"
        print(f"| {key[0]} | {key[1]} | {len(members[key])} | {fmt_ulp(emax)} | {fmt_ulp(emed)} | "
              f"{fails} | {ncomplex} | {wx} | {wy} | {fmt_g(worst[3])} |")
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
