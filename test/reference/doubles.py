# SPDX-License-Identifier: Apache-2.0
"""Correct rounding of mpmath numbers to doubles, shared by the reference scripts
(test/reference/make_*.py) and the table generators (tools/make_*_tables.py).

float(x) of an mpf is only a first guess (mpmath may round twice in the subnormal
range); the guess and its two neighbours are compared with x in the current
precision, ties going to the even significand.
"""

import math
import struct

from mpmath import mpf


def is_even(x):
    """True if the last significand bit of the double x is zero."""
    return struct.unpack("<q", struct.pack("<d", x))[0] & 1 == 0


def nearest_double(x):
    """The mpf x rounded to the nearest double, ties to even, subnormals included."""
    if x == 0:
        return 0.0
    guess = float(x)
    if math.isinf(guess):
        raise OverflowError(f"{x} does not fit in a double")
    best, best_err = guess, abs(x - mpf(guess))
    for other in (math.nextafter(guess, -math.inf), math.nextafter(guess, math.inf)):
        err = abs(x - mpf(other))
        if err < best_err or (err == best_err and is_even(other) and not is_even(best)):
            best, best_err = other, err
    return best


def split_double(x):
    """The mpf x as hi + lo: x rounded to a double, and the rest rounded to a double."""
    hi = nearest_double(x)
    if math.isinf(hi):
        return hi, 0.0
    return hi, nearest_double(x - mpf(hi))
