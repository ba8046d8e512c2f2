# SPDX-License-Identifier: Apache-2.0
"""Lambert W through the Python package against the mpmath references
(test/reference/lambertw.csv) and against mpmath itself."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

import hcimpact
from conftest import read_reference, ulp_error

FUNCTIONS = {
    "w0": hcimpact.lambert_w0,
    "wm1": hcimpact.lambert_wm1,
    "w0p1": hcimpact.lambert_w0p1,
    "wm1p1": hcimpact.lambert_wm1p1,
}


@pytest.fixture(scope="module")
def rows():
    return read_reference("lambertw.csv", ["region", "func", "x", "ref_hi", "ref_lo"])


@pytest.mark.parametrize("func", sorted(FUNCTIONS))
def test_reference_array_form(rows, func):
    """Every reference point of a function in one call of the array form: <= 2 ulp."""
    mine = [r for r in rows if r["func"] == func]
    x = np.array([float(r["x"]) for r in mine])
    hi = np.array([float(r["ref_hi"]) for r in mine])
    lo = np.array([float(r["ref_lo"]) for r in mine])
    err = ulp_error(FUNCTIONS[func](x), hi, lo)
    worst = int(np.argmax(err))
    assert err[worst] <= 2.0, (
        f"{func}({x[worst]!r}): {err[worst]:.3g} ulp over {x.size} points")
    assert np.median(err) <= 0.5


@pytest.mark.parametrize("func", sorted(FUNCTIONS))
def test_scalar_equals_array(rows, func):
    """The scalar form returns exactly what the array form returns."""
    x = np.array([float(r["x"]) for r in rows if r["func"] == func][::37])
    array = FUNCTIONS[func](x)
    scalar = np.array([FUNCTIONS[func](float(v)) for v in x])
    assert np.array_equal(array, scalar, equal_nan=True)
    assert isinstance(FUNCTIONS[func](float(x[0])), float)


def test_against_mpmath():
    """Fresh points, references from mpmath at 40 digits."""
    rng = np.random.default_rng(5)
    mpmath.mp.dps = 40
    for z in list(rng.uniform(-0.3678, 5.0, 200)) + list(10.0 ** rng.uniform(-20, 300, 50)):
        ref = mpmath.lambertw(mpmath.mpf(float(z)), 0)
        assert ulp_error(hcimpact.lambert_w0(float(z)), float(ref),
                         float(ref - mpmath.mpf(float(ref)))) <= 2.0, z
    for z in -(10.0 ** rng.uniform(-300, math.log10(0.3678), 200)):
        ref = mpmath.lambertw(mpmath.mpf(float(z)), -1)
        assert ulp_error(hcimpact.lambert_wm1(float(z)), float(ref.real),
                         float(ref.real - mpmath.mpf(float(ref.real)))) <= 2.0, z


def test_domain_and_shapes():
    assert math.isnan(hcimpact.lambert_w0(-1.0))
    assert math.isnan(hcimpact.lambert_wm1(0.5))
    # z = 0 of either sign ends the domain of W-1: -inf (include/hcimpact.h)
    assert hcimpact.lambert_wm1(0.0) == -math.inf
    assert hcimpact.lambert_wm1(-0.0) == -math.inf
    assert math.isnan(hcimpact.lambert_wm1(5e-324))
    assert math.isnan(hcimpact.lambert_w0p1(-1e-300))
    assert hcimpact.lambert_w0p1(math.inf) == 1.0
    assert hcimpact.lambert_wm1p1(math.inf) == -math.inf
    grid = np.linspace(0.0, 3.0, 12).reshape(3, 4)
    out = hcimpact.lambert_w0p1(grid)
    assert out.shape == (3, 4) and out.dtype == np.float64
    assert hcimpact.lambert_w0(np.array([])).shape == (0,)
    # a list and a non-contiguous view work too
    assert np.array_equal(hcimpact.lambert_w0([1.0, 2.0]),
                          hcimpact.lambert_w0(np.array([1.0, 2.0])))
    view = np.arange(10.0)[::3]
    assert np.array_equal(hcimpact.lambert_w0(view), hcimpact.lambert_w0(view.copy()))
