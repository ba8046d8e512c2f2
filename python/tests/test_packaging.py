# SPDX-License-Identifier: Apache-2.0
"""How the package finds its library and components, what it says when one is missing,
and the NumPy conventions of simulate, time_law and the results."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hcimpact
from hcimpact import _api, _library

BALL = dict(mass=0.1, stiffness=1.7135e10, exponent=1.5, damping=0.1, velocity=5.0)
PLACES = ("HCIMPACT_PREFIX", "the package (a wheel)", "sys.prefix", "dynamic loader",
          "/usr/local")


def test_library_where_expected():
    """CI's wheel check: the library must be the one inside the installed package."""
    expected = os.environ.get("HCIMPACT_EXPECT_LIBRARY_UNDER")
    if not expected:
        pytest.skip("HCIMPACT_EXPECT_LIBRARY_UNDER not set")
    path = Path(hcimpact.library_path()).resolve()
    assert Path(expected).resolve() in path.parents, f"{path} is not under {expected}"


def test_components_where_expected():
    expected = os.environ.get("HCIMPACT_EXPECT_COMPONENTS", "").split()
    if not expected:
        pytest.skip("HCIMPACT_EXPECT_COMPONENTS not set")
    if "cvode" in expected:
        assert hcimpact.has_simulate()
    if "lapack" in expected:
        assert _library.component("hcimpact_fit_damping", "hcimpact_lapack") is not None


def test_every_place_is_listed(tmp_path):
    """A package that finds no library says where it looked, every place, in order."""
    package = tmp_path / "hcimpact"
    shutil.copytree(Path(hcimpact.__file__).resolve().parent, package,
                    ignore=shutil.ignore_patterns("lib", "_build.json", "__pycache__"))
    env = {k: v for k, v in os.environ.items() if not k.startswith("HCIMPACT_")}
    env.update(PYTHONPATH=str(tmp_path), HCIMPACT_PREFIX=str(tmp_path / "prefix"),
               LD_LIBRARY_PATH="")
    code = ("import hcimpact\n"
            "try:\n    print(hcimpact.library_path())\n"
            "except hcimpact.LibraryNotFoundError as e:\n    print('NOT FOUND', e)\n")
    result = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                            text=True, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    if "NOT FOUND" not in result.stdout:
        pytest.skip(f"a library is installed system-wide: {result.stdout.strip()}")
    text = result.stdout
    assert "no candidate found" not in text
    positions = [text.find(place + ":") for place in PLACES]
    assert all(p >= 0 for p in positions), text
    assert positions == sorted(positions), text
    assert str(tmp_path / "prefix" / "lib") in text


def test_missing_component_names_the_missing_piece(monkeypatch):
    monkeypatch.setattr(_library, "component", lambda function, stem: None)
    monkeypatch.setattr(_library, "build_info", lambda: {"components": {
        "cvode": {"built": False, "status": "OFF (SUNDIALS not found: fcvode_mod.mod "
                                            "(libsundials-fortran-dev))"},
        "lapack": {"built": False, "status": "OFF (LAPACK not found)"}}})
    with pytest.raises(hcimpact.UnavailableError) as info:
        hcimpact.simulate(**BALL)
    assert "fcvode_mod.mod" in str(info.value) and "libsundials-fortran-dev" in str(info.value)
    with pytest.raises(hcimpact.UnavailableError, match="LAPACK not found"):
        hcimpact.fit_damping([1.0, 2.0], [0.9, 0.8])
    # outside a wheel: what to install
    monkeypatch.setattr(_library, "build_info", lambda: {})
    with pytest.raises(hcimpact.UnavailableError, match="libsundials-fortran-dev"):
        hcimpact.simulate(**BALL)


@pytest.mark.cvode
def test_solver_failure_carries_cvode_flag():
    if not hcimpact.has_simulate():
        pytest.skip("no CVODE component in this library")
    with pytest.raises(hcimpact.ComputationError) as info:
        hcimpact.simulate(**dict(BALL, velocity=1.0), rtol=1e-20)
    assert info.value.status == 11
    assert "CV_TOO_MUCH_ACC" in str(info.value)


@pytest.mark.cvode
def test_simulate_broadcasts():
    if not hcimpact.has_simulate():
        pytest.skip("no CVODE component in this library")
    speeds = np.array([[0.5, 1.0, 2.0], [3.0, 4.0, 5.0]])
    ode = hcimpact.simulate(**dict(BALL, velocity=speeds), rtol=1e-9)
    exact = hcimpact.impact(**dict(BALL, velocity=speeds))
    assert ode.contact_time.shape == speeds.shape
    np.testing.assert_allclose(ode.contact_time, exact.contact_time, rtol=1e-6)
    bad = hcimpact.simulate(**dict(BALL, velocity=np.array([1.0, -1.0])), errors="nan")
    assert np.isfinite(bad.restitution[0]) and np.isnan(bad.restitution[1])
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.simulate(**dict(BALL, velocity=np.array([1.0, -1.0])))
    assert info.value.index == 1


def test_time_law_broadcasts_contacts():
    speeds = np.array([1.0, 2.0, 5.0])
    t = np.array([1e-5, 2e-5, 3e-5])
    x, v, f = hcimpact.time_law(t, **dict(BALL, velocity=speeds))
    for i in range(3):
        xi, vi, fi = hcimpact.time_law(t[i], **dict(BALL, velocity=speeds[i]))
        assert (x[i], v[i], f[i]) == (xi, vi, fi)
    # a column of times against a row of speeds: a table
    x2, _, _ = hcimpact.time_law(t[:, None], **dict(BALL, velocity=speeds[None, :]))
    assert x2.shape == (3, 3) and x2[1, 2] == hcimpact.time_law(t[1], **BALL)[0]
    with pytest.raises(hcimpact.InputError, match="broadcast"):
        hcimpact.time_law(np.zeros(4), **dict(BALL, velocity=speeds))
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.time_law(t, **dict(BALL, mass=np.array([0.1, -0.1, 0.1])))
    assert info.value.index == 1


def test_single_contact_functions_say_so():
    with pytest.raises(hcimpact.InputError, match="scalar"):
        hcimpact.time_law_samples(11, **dict(BALL, velocity=[1.0, 2.0]))


def test_short_reprs():
    one = repr(hcimpact.impact(**BALL))
    assert one.startswith("ImpactResult(restitution=0.748435") and len(one) < 160
    many = repr(hcimpact.impact(**dict(BALL, velocity=np.linspace(0.5, 5.0, 10000))))
    assert "shape=(10000,)" in many and len(many) < 260


@pytest.mark.lapack
def test_fit_repr_and_data():
    speeds = np.array([0.5, 1.0, 2.0, 3.0])
    try:
        fit = hcimpact.fit_damping(speeds, hcimpact.restitution(0.1 * speeds))
    except hcimpact.UnavailableError:
        pytest.skip("no LAPACK component in this library")
    assert repr(fit).startswith("FitResult(damping: damping=0.1")
    assert np.array_equal(fit.data["velocity"], speeds) and fit.kind == "damping"


def test_plot_result_and_fit(tmp_path):
    pytest.importorskip("matplotlib")
    from hcimpact import plot

    speeds = np.linspace(0.5, 5.0, 6)
    result = hcimpact.impact(**dict(BALL, velocity=speeds))
    fig = plot.plot_result(result, speeds, path=str(tmp_path / "result.png"))
    assert (tmp_path / "result.png").stat().st_size > 0 and len(fig.axes) == 4
    try:
        fit = hcimpact.fit_impact(speeds, mass=0.1, contact_time=result.contact_time,
                                  restitution=result.restitution)
        damping = hcimpact.fit_damping(speeds, result.restitution)
    except hcimpact.UnavailableError:
        pytest.skip("no LAPACK component in this library")
    fig = plot.plot_fit(fit, path=str(tmp_path / "fit.png"))
    assert len(fig.axes) == 2                         # contact time, restitution
    line = fig.axes[0].lines[1]                       # the model through the data
    np.testing.assert_allclose(np.interp(speeds, *line.get_data()), result.contact_time,
                               rtol=1e-3)
    assert len(plot.plot_fit(damping).axes) == 1
