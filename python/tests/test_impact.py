# SPDX-License-Identifier: Apache-2.0
"""One impact, the phase curves and the time law through the Python package, against
the mpmath references (test/reference/impact.csv, timelaw.csv) and MODEL.md."""

from __future__ import annotations

import math

import numpy as np
import pytest

import hcimpact
from conftest import read_reference, ulp_error

STEEL = dict(mass=0.1, stiffness=1.7135e10, exponent=1.5, damping=0.1)
# MODEL.md: V, k, x_max, F_max, t_contact, t_compression
SEED_TABLE = [
    (0.5, 0.9677385785309325, 1.9893579643308693e-5, 1521.9160892838993,
     1.1904584326151915e-4, 5.8859751374268991e-5),
    (1, 0.93747557994990506, 3.4204625278143626e-5, 3441.1122331638547,
     1.0399469349496538e-4, 5.0856853135224197e-5),
    (2, 0.88218998624730638, 5.8156728355576902e-5, 7709.8673680931372,
     9.1181013535146273e-5, 4.3649774771233254e-5),
    (3, 0.83286979226560167, 7.8679668816420547e-5, 12322.929545918441,
     8.4701327451018694e-5, 3.9721750506275539e-5),
    (4, 0.78853912590706515, 9.7008052543829528e-5, 17199.324205797322,
     8.0573545729318647e-5, 3.7040161639485758e-5),
    (5, 0.74843493159743416, 1.1372585556115339e-4, 22315.267380743067,
     7.7655384043269703e-5, 3.5014163526885175e-5),
]

FIELDS = {  # impact.csv column -> ImpactResult field
    "x_max": "max_compression", "peak_force": "peak_force",
    "compression_at_peak": "compression_at_peak_force",
    "compression_time": "compression_time", "contact_time": "contact_time",
    "restitution": "restitution",
}


@pytest.mark.parametrize("row", SEED_TABLE, ids=[f"V={r[0]}" for r in SEED_TABLE])
def test_seed_table(row):
    v, k, xmax, fmax, tc, tcomp = row
    r = hcimpact.impact(**STEEL, velocity=v)
    assert isinstance(r, hcimpact.ImpactResult)
    # the table is for the decimal inputs, the data for the doubles: 1e-15 apart
    for got, want in [(r.restitution, k), (r.max_compression, xmax), (r.peak_force, fmax),
                      (r.contact_time, tc), (r.compression_time, tcomp)]:
        assert got == pytest.approx(want, rel=1e-14)
    assert r.rebound_velocity == pytest.approx(-k * v, rel=1e-14)
    assert r.energy_loss_ratio == pytest.approx(1 - k * k, rel=1e-13)


def test_seed_table_array():
    """The whole table in one call (broadcasting), identical to the scalar calls."""
    speeds = np.array([row[0] for row in SEED_TABLE], dtype=float)
    r = hcimpact.impact(**STEEL, velocity=speeds)
    assert r.contact_time.shape == (6,)
    for i, v in enumerate(speeds):
        one = hcimpact.impact(**STEEL, velocity=float(v))
        for name, value in one.as_dict().items():
            assert getattr(r, name)[i] == value


def test_reference_cases():
    """Every case of impact.csv, in one array call."""
    rows = read_reference("impact.csv")
    get = lambda name: np.array([float(r[name]) for r in rows])  # noqa: E731
    r = hcimpact.impact(mass=get("m"), stiffness=get("c"), exponent=get("n"),
                        damping=get("b"), velocity=get("V"))
    for column, field in FIELDS.items():
        err = ulp_error(getattr(r, field), get(column + "_hi"), get(column + "_lo"))
        # the Fortran suite holds these to ~1.2 ulp; here a binding check with slack
        assert np.max(err) <= 8.0, (field, int(np.argmax(err)), float(np.max(err)))


def test_timelaw_reference():
    """x(t), x'(t), F(t) of timelaw.csv, weighted by the condition number t v / x."""
    cases = read_reference("impact.csv")
    rows = read_reference("timelaw.csv")
    by_case: dict[int, list] = {}
    for row in rows:
        by_case.setdefault(int(row["case_id"]), []).append(row)
    worst = 0.0
    for case_id, points in by_case.items():
        c = cases[case_id - 1]
        contact = dict(mass=float(c["m"]), stiffness=float(c["c"]), exponent=float(c["n"]),
                       damping=float(c["b"]), velocity=float(c["V"]))
        t = np.array([float(p["t"]) for p in points])
        x, v, f = hcimpact.time_law(t, **contact)
        x_ref = np.array([float(p["x_hi"]) for p in points])
        v_ref = np.array([float(p["v_hi"]) for p in points])
        tc = float(c["contact_time_hi"])
        # skip the last points before the end of contact (ill-conditioned, IMPACT.md)
        keep = (tc - t) > 1e-6 * tc
        scale = np.maximum(np.abs(x_ref), 1e-300)
        cond = np.maximum(1.0, np.abs(t * v_ref) / scale)
        rel = np.abs(x - x_ref) / scale / cond
        worst = max(worst, float(np.max(rel[keep])))
        assert np.all(np.isfinite(f))
    assert worst <= 1e-13


def test_velocity_at_depth():
    r = hcimpact.impact(**STEEL, velocity=5.0)
    assert hcimpact.velocity_at_depth(0.0, **STEEL, velocity=5.0) == pytest.approx(5.0)
    assert hcimpact.velocity_at_depth(0.0, **STEEL, velocity=5.0, branch="restitution") == \
        pytest.approx(r.rebound_velocity, rel=1e-13)
    x = np.linspace(0.0, r.max_compression, 9)
    up = hcimpact.velocity_at_depth(x, **STEEL, velocity=5.0, branch=hcimpact.COMPRESSION)
    down = hcimpact.velocity_at_depth(x, **STEEL, velocity=5.0, branch="restitution")
    assert np.all(np.diff(up) < 0) and np.all(up >= 0) and np.all(down <= 0)
    # b = 0: V(x)^2 = V^2 - 2 Pi(x)/m exactly (MODEL.md)
    elastic = dict(STEEL, damping=0.0)
    xe = hcimpact.impact(**elastic, velocity=1.0).max_compression * np.array([0.1, 0.5, 0.9])
    ve = hcimpact.velocity_at_depth(xe, **elastic, velocity=1.0)
    pi = 1.7135e10 * xe**2.5 / 2.5
    assert ve == pytest.approx(np.sqrt(1.0 - 2 * pi / 0.1), rel=1e-13)
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.velocity_at_depth(2 * r.max_compression, **STEEL, velocity=5.0)
    assert info.value.status == 8
    with pytest.raises(ValueError):
        hcimpact.velocity_at_depth(0.0, **STEEL, velocity=5.0, branch="up")


def test_time_law_samples():
    r = hcimpact.impact(**STEEL, velocity=2.0)
    t, x, v, f = hcimpact.time_law_samples(101, **STEEL, velocity=2.0)
    assert t.shape == x.shape == v.shape == f.shape == (101,)
    assert t[0] == 0.0 and t[-1] == r.contact_time
    assert x.max() == pytest.approx(r.max_compression, rel=1e-3)
    assert f.max() <= r.peak_force * (1 + 1e-12)
    # the hysteresis loop: its area, the integral of F dx = F v dt, is the kinetic
    # energy lost (MODEL.md, seed fig. 6)
    trapezoid = getattr(np, "trapezoid", None) or np.trapz
    work = trapezoid(f * v, t)
    assert work == pytest.approx(0.5 * 0.1 * 4.0 * r.energy_loss_ratio, rel=1e-4)
    with pytest.raises(hcimpact.InputError):
        hcimpact.time_law_samples(1, **STEEL, velocity=2.0)
    x1, v1, f1 = hcimpact.time_law(r.compression_time, **STEEL, velocity=2.0)
    assert isinstance(x1, float) and x1 == pytest.approx(r.max_compression, rel=1e-12)


@pytest.mark.parametrize("field, value, status", [
    ("mass", 0.0, 2), ("stiffness", -1.0, 3), ("exponent", 0.0, 4), ("damping", -0.1, 6),
    ("velocity", 0.0, 5), ("mass", math.nan, 1), ("velocity", math.inf, 1),
])
def test_errors(field, value, status):
    args = dict(STEEL, velocity=1.0)
    args[field] = value
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.impact(**args)
    assert info.value.status == status
    assert info.value.message == hcimpact.status_message(status)
    assert "hcimpact_impact" in str(info.value)
    nan = hcimpact.impact(**args, errors="nan")
    assert all(math.isnan(value) for value in nan.as_dict().values())


def test_array_errors():
    masses = np.array([[0.1, 0.1], [-1.0, 0.1]])
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.impact(mass=masses, stiffness=1.7135e10, damping=0.1, velocity=1.0)
    assert info.value.index == (1, 0) and info.value.status == 2
    r = hcimpact.impact(mass=masses, stiffness=1.7135e10, damping=0.1, velocity=1.0,
                        errors="nan")
    assert np.isnan(r.contact_time[1, 0]) and np.isfinite(r.contact_time[0, 0])
    with pytest.raises(ValueError):
        hcimpact.impact(**STEEL, velocity=1.0, errors="ignore")


def test_impact_law_matches_power_law():
    """The Hertz law given as Python functions gives the closed forms of the power law."""
    c = 1.7135e10
    reference = hcimpact.impact(mass=0.1, stiffness=c, exponent=1.5, damping=0.1, velocity=2.0)
    result = hcimpact.impact_law(lambda x: c * x**1.5, lambda x: c * x**2.5 / 2.5,
                                 lambda x: 1.5 * c * math.sqrt(x),
                                 mass=0.1, damping=0.1, velocity=2.0)
    assert result.restitution == pytest.approx(reference.restitution, rel=1e-14)
    assert result.max_compression == pytest.approx(reference.max_compression, rel=1e-12)
    assert result.peak_force == pytest.approx(reference.peak_force, rel=1e-12)
    assert result.contact_time == pytest.approx(reference.contact_time, rel=1e-12)


def test_impact_law_errors():
    """Bad input and a failing law raise; an exception in a callback is raised again
    (test_inputs.py checks that it stops the computation at once)."""
    law = (lambda x: x, lambda x: 0.5 * x * x, lambda x: 1.0)
    with pytest.raises(hcimpact.InputError):
        hcimpact.impact_law(*law, mass=-1.0, damping=0.1, velocity=1.0)

    def broken(x):
        raise RuntimeError("not a law")

    with pytest.raises(RuntimeError, match="not a law"):
        hcimpact.impact_law(broken, law[1], law[2], mass=1.0, damping=0.1, velocity=1.0)
