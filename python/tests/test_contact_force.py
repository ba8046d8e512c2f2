# SPDX-License-Identifier: Apache-2.0
"""hcimpact.contact_force: the element through the C interface, with NumPy broadcasting,
against mpmath at the exact double inputs, the clamp, and bad input."""

import math

import numpy as np
import pytest
from mpmath import mp, mpf

import hcimpact

STEEL = dict(stiffness=1.7135e10, exponent=1.5, damping=0.1)


def exact(x, v, c, n, b):
    """The five fields in 50-digit arithmetic (the formulas of doc/contact-force.md)."""
    with mp.workdps(50):
        x, v, c, n, b = (mpf(float(t)) for t in (x, v, c, n, b))
        if x <= 0:
            return [0.0] * 5
        f = c * x ** n
        s = 1 + b * v
        if s > 0:
            fields = [f * s, n * f / x * s, b * f, f * x / (n + 1), b * f * v * v]
        else:
            fields = [0, 0, 0, f * x / (n + 1), -f * v]
        return [float(t) for t in fields]


def ulps(a, b):
    if a == b:
        return 0.0
    return abs(a - b) / math.ulp(abs(b))


def test_scalar_against_mpmath():
    r = hcimpact.contact_force(5.0e-5, 2.0, **STEEL)
    ref = exact(5.0e-5, 2.0, 1.7135e10, 1.5, 0.1)
    for name, value in zip(("force", "dforce_dx", "dforce_dv", "potential", "dissipation"), ref):
        assert ulps(getattr(r, name), value) <= 4, name
    assert isinstance(r.force, float)
    assert "ContactForce(force=" in repr(r)


def test_broadcasting_and_clamp_accuracy():
    rng = np.random.default_rng(20261125)
    b = 10.0 ** rng.uniform(-3, 3, 200)
    delta = np.where(rng.random(200) < 0.5, -1, 1) * 10.0 ** rng.uniform(-15, -1, 200)
    v = -(1 + delta) / b
    x = 10.0 ** rng.uniform(-8, -3, 200)
    r = hcimpact.contact_force(x, v, 1.0e9, 1.5, b)
    assert r.force.shape == (200,)
    assert "shape=(200,)" in repr(r)
    worst = max(ulps(r.force[i], exact(x[i], v[i], 1.0e9, 1.5, b[i])[0]) for i in range(200))
    assert worst <= 4
    # the naive expression loses far more next to the clamp
    naive = 1.0e9 * x ** 1.5 * np.maximum(0.0, 1 + b * v)
    assert max(ulps(naive[i], exact(x[i], v[i], 1.0e9, 1.5, b[i])[0])
               for i in range(200)) > 1000


def test_shapes_broadcast():
    x = np.linspace(-1e-5, 1e-4, 6).reshape(2, 3)
    r = hcimpact.contact_force(x, np.array([1.0, -1.0, 3.0]), **STEEL)
    assert r.potential.shape == (2, 3)
    assert np.all(r.force[x <= 0] == 0.0)
    assert np.all(r.dissipation >= 0.0)


def test_bad_input():
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.contact_force([1e-5, 1e-5], 1.0, stiffness=[1.0, -1.0])
    assert info.value.index == 1
    r = hcimpact.contact_force([1e-5, 1e-5], 1.0, stiffness=[1.0, -1.0], errors="nan")
    assert r.force[0] > 0 and math.isnan(r.force[1])
    with pytest.raises(hcimpact.InputError):
        hcimpact.contact_force(1e-5, float("nan"), stiffness=1.0)
    with pytest.raises(hcimpact.InputError):
        hcimpact.contact_force(1e-5, 1.0, stiffness=1.0, exponent=1e-7)
    with pytest.raises(hcimpact.InputError, match="complex"):
        hcimpact.contact_force(1e-5 + 1j, 1.0, stiffness=1.0)
    with pytest.raises(ValueError):
        hcimpact.contact_force(1e-5, 1.0, stiffness=1.0, errors="ignore")
