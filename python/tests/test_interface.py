# SPDX-License-Identifier: Apache-2.0
"""The package around the physics: loading, version, status messages, exceptions,
two bodies, the components (CVODE, LAPACK) and the lazy import."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hcimpact


def test_version():
    assert hcimpact.version() == hcimpact.__version__
    major, minor, patch = (int(p) for p in hcimpact.version().split("."))
    assert hcimpact.version_number() == 10000 * major + 100 * minor + patch
    assert os.path.isfile(hcimpact.library_path())


def test_array_threads_same_results():
    # OMP_NUM_THREADS as the test run sets it (1 without OpenMP); large arrays go through
    # the parallel array forms and must equal element-wise scalar calls bit for bit
    threads = hcimpact.array_threads()
    assert threads >= 1
    if "OMP_NUM_THREADS" in os.environ and threads > 1:
        assert threads == int(os.environ["OMP_NUM_THREADS"])
    rng = np.random.default_rng(17)
    z = 10.0 ** rng.uniform(-5, 5, 40000)
    w = hcimpact.lambert_w0(z)
    assert all(w[i] == hcimpact.lambert_w0(float(z[i])) for i in range(0, z.size, 97))
    speeds = 10.0 ** rng.uniform(-2, 1, 64)
    batch = hcimpact.impact(mass=0.1, stiffness=1.7135e10, exponent=1.5, damping=0.1,
                            velocity=speeds)
    for i in range(0, speeds.size, 7):
        one = hcimpact.impact(mass=0.1, stiffness=1.7135e10, exponent=1.5, damping=0.1,
                              velocity=float(speeds[i]))
        assert float(batch.contact_time[i]) == float(one.contact_time)
        assert float(batch.peak_force[i]) == float(one.peak_force)


def test_status_messages():
    assert hcimpact.status_message(0) == "success"
    assert "NULL" in hcimpact.status_message(10)
    assert hcimpact.status_message(1000) == "unknown status code"
    assert hcimpact.status_message(-1) == "unknown status code"
    names = hcimpact.STATUS_NAMES
    assert names[0] == "HCIMPACT_OK" and names[14] == "HCIMPACT_ERR_SIZE"
    texts = {hcimpact.status_message(code) for code in names}
    assert len(texts) == len(names)


def test_exception_classes():
    assert issubclass(hcimpact.InputError, ValueError)
    assert issubclass(hcimpact.InputError, hcimpact.HcimpactError)
    assert issubclass(hcimpact.ComputationError, ArithmeticError)
    assert issubclass(hcimpact.UnavailableError, RuntimeError)
    assert issubclass(hcimpact.LibraryNotFoundError, ImportError)


def test_two_bodies():
    c = hcimpact.hertz_constant(2e11, 0.25, 0.01452, 2e11, 0.25)
    assert c == pytest.approx(1.7138e10, rel=1e-4)  # MODEL.md
    assert math.isnan(hcimpact.hertz_constant(2e11, 0.25, math.inf, 2e11, 0.25, math.inf))
    assert hcimpact.effective_mass(1.0, 1.0) == 0.5
    assert hcimpact.effective_mass(0.1) == 0.1
    v1, v2 = hcimpact.two_body_velocities(1.0, 1.0, 1.0, -1.0, 0.5)
    assert (v1, v2) == pytest.approx((-0.5, 0.5))
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.two_body_velocities(1.0, 1.0, -1.0, 1.0, 0.5)
    assert info.value.status == 5


@pytest.mark.cvode
def test_simulate():
    if not hcimpact.has_simulate():
        with pytest.raises(hcimpact.UnavailableError) as info:
            hcimpact.simulate(mass=0.1, stiffness=1.7135e10, damping=0.1, velocity=5.0)
        assert info.value.status == 12
        pytest.skip("no CVODE component in this library (UnavailableError checked)")
    ode = hcimpact.simulate(mass=0.1, stiffness=1.7135e10, damping=0.1, velocity=5.0,
                            rtol=1e-10)
    exact = hcimpact.impact(mass=0.1, stiffness=1.7135e10, damping=0.1, velocity=5.0)
    for name, value in exact.as_dict().items():
        assert getattr(ode, name) == pytest.approx(value, rel=1e-6), name
    with pytest.raises(hcimpact.InputError):
        hcimpact.simulate(mass=0.1, stiffness=1.7135e10, damping=0.1, velocity=5.0, rtol=2.0)


@pytest.mark.lapack
def test_calibration():
    """fit_damping recovers b from restitution data that follows the exact law."""
    speeds = np.array([0.5, 1.0, 2.0, 3.0, 4.0, 5.0])
    e = hcimpact.restitution(0.1 * speeds)
    try:
        fit = hcimpact.fit_damping(speeds, e)
    except hcimpact.UnavailableError:
        pytest.skip("no LAPACK component in this library")
    assert fit.parameters["damping"] == pytest.approx(0.1, rel=1e-10)
    assert np.max(np.abs(fit.residuals)) < 1e-12
    linear = hcimpact.fit_damping_linear(speeds, e)
    assert linear.parameters["damping"] < 0.1  # MODEL.md: the linear law is biased low
    deflection = np.array([1e-6, 2e-6, 5e-6, 1e-5])
    static = hcimpact.fit_static(deflection, 1.7135e10 * deflection**1.5)
    assert static.parameters["exponent"] == pytest.approx(1.5, rel=1e-10)
    assert static.parameters["stiffness"] == pytest.approx(1.7135e10, rel=1e-9)


def test_lazy_import():
    """import hcimpact neither loads the library nor imports NumPy; hcimpact.plot works
    without the library."""
    code = (
        "import sys, hcimpact\n"
        "assert 'numpy' not in sys.modules, 'numpy imported'\n"
        "assert 'hcimpact._library' not in sys.modules\n"
        "import hcimpact.plot\n"
        "print('ok')\n")
    env = dict(os.environ, HCIMPACT_LIBRARY="/nonexistent/libhcimpact.so",
               PYTHONPATH=str(Path(hcimpact.__file__).resolve().parents[1]),
               MPLBACKEND="Agg")
    result = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                            text=True)
    assert result.returncode == 0, result.stderr
    code = ("import hcimpact\n"
            "try:\n    hcimpact.restitution(0.5)\n"
            "except hcimpact.LibraryNotFoundError as e:\n    print('not found:', e)\n")
    result = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                            text=True)
    assert "not found" in result.stdout and "HCIMPACT_LIBRARY" in result.stdout
