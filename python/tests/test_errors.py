# SPDX-License-Identifier: Apache-2.0
"""Which exception a status becomes (hcimpact._types.error_class, the one place that
decides): out of memory, status 16 (HCIMPACT_ERR_OUT_OF_MEMORY), is an OutOfMemoryError
(an HcimpactError and a MemoryError) from every function; a wrong size, status 14,
stays an InputError whatever the message. On Linux a real chain of 10^6 bodies, and
the time law and the fits on 2^21 values, run out of memory in a child process whose
address space is capped (setrlimit RLIMIT_AS, as test/cvode/chain_memory_test.c and
test/lapack/memory_test.c do in C).
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

import hcimpact
from hcimpact import _api, _types


@pytest.mark.parametrize("status, expected", [
    (16, hcimpact.OutOfMemoryError),
    (14, hcimpact.InputError),
    (8, hcimpact.InputError),
    (11, hcimpact.ComputationError),
    (17, hcimpact.InputError),
])
def test_the_status_chooses_the_exception(status, expected):
    assert _types.error_class(status) is expected


def test_out_of_memory_has_a_name_and_a_text():
    assert _types.STATUS_NAMES[16] == "HCIMPACT_ERR_OUT_OF_MEMORY"
    assert hcimpact.status_message(16).startswith("out of memory")


def test_out_of_memory_is_a_memory_error_and_an_hcimpact_error():
    with pytest.raises(MemoryError) as caught:
        _api._raise(16, "hcimpact_chain_simulate", detail="out of memory (the copies of "
                    "the input): the system is too large for the memory available")
    error = caught.value
    assert isinstance(error, hcimpact.OutOfMemoryError)
    assert isinstance(error, hcimpact.HcimpactError)
    assert not isinstance(error, ValueError)
    assert error.status == 16 and error.name == "HCIMPACT_ERR_OUT_OF_MEMORY"
    # the library's account of what did not fit, when it gives one
    assert error.message.startswith("out of memory (the copies of the input)")
    assert error.function == "hcimpact_chain_simulate"


def test_out_of_memory_without_a_message_has_the_status_text():
    with pytest.raises(hcimpact.OutOfMemoryError) as caught:
        _api._raise(16, "hcimpact_time_law")
    assert caught.value.message == hcimpact.status_message(16)


def test_a_wrong_size_stays_an_input_error():
    with pytest.raises(hcimpact.InputError) as caught:
        _api._raise(14, "hcimpact_chain_simulate", detail="contact_capacity < 0")
    assert isinstance(caught.value, ValueError)
    assert not isinstance(caught.value, MemoryError)


# A child's cap on its address space (Linux): what it uses now plus sys.argv[1] MiB, set
# once its arguments are built and the libraries loaded, so that what fails under it is
# an allocation made by the call; the report: the exception, whether it is a
# MemoryError, the status, and the library's message.
_CAP = """
    import resource
    def cap_address_space(headroom_mib):
        with open("/proc/self/statm") as statm:
            used = int(statm.read().split()[0]) * resource.getpagesize()
        limit = used + (headroom_mib << 20)
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    def report(call):
        try:
            call()
        except hcimpact.HcimpactError as error:
            print(type(error).__name__, isinstance(error, MemoryError), error.status)
            print(error.message)
        else:
            print("no error")
"""

# The child: a row of 10^6 balls with gaps, neighbours approaching in pairs (the first
# case of chain_memory_test.c); its arguments built in full before the cap, the cap its
# address space now plus 160 MB, enough for this package's own arrays (the
# laws, the outputs: 48 MB is too little for them, 96 MB enough) and far too little for
# the library's copies and engine (which fail at 96, 200 and 400 MB, succeed at 800 MB).
_CHILD = textwrap.dedent("""
    import sys
    import numpy as np
    import hcimpact
""") + textwrap.dedent(_CAP) + textwrap.dedent("""
    n = 10**6
    masses = np.full(n, 4.1e-3)
    velocities = np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    gaps = np.full(n - 1, 1e-3)
    stiffness = np.full(n - 1, 8.6e9)
    hcimpact.has_chain()
    cap_address_space(int(sys.argv[1]))
    report(lambda: hcimpact.chain(masses, velocities, gaps=gaps, stiffness=stiffness,
                                  damping=0.01, t_end=6e-4, max_contacts=0))
""")


def _run_capped(child: str, *args: str) -> list[str]:
    """The lines a child prints (skipped where the address space is capped already)."""
    try:
        import resource
        limit = resource.getrlimit(resource.RLIMIT_AS)
    except (ImportError, OSError) as exc:
        pytest.skip(f"no address-space limit here: {exc}")
    if limit[1] != resource.RLIM_INFINITY:
        pytest.skip(f"the address space is limited already ({limit[1]} bytes)")
    run = subprocess.run([sys.executable, "-c", child, *args], capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert run.stdout, run.stderr
    return run.stdout.splitlines()


@pytest.mark.cvode
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS and /proc: Linux")
def test_a_real_chain_out_of_memory():
    if not hcimpact.has_chain():
        pytest.skip("the library has no hcimpact_chain_simulate (CVODE component)")
    lines = _run_capped(_CHILD, "160")
    assert lines[0] == "OutOfMemoryError True 16", lines
    assert lines[1].startswith("out of memory ("), lines


# The time law and the fits on 2^21 times or points, in a child as the chain's: the
# data built before the cap; under it this package's own arrays still fit (the outputs,
# the fits' residuals: up to three series, 48 MiB) and the library's copies and work
# arrays of the same size do not. A status 14 ("wrong size", an InputError) there was
# the library's out of memory told as a wrong input.
_CALLS = textwrap.dedent("""
    import sys
    import numpy as np
    import hcimpact
""") + textwrap.dedent(_CAP) + textwrap.dedent("""
    n = 2**21
    contact = dict(mass=0.1, stiffness=1.7e10, exponent=1.5, damping=0.1, velocity=2.0)
    v = np.linspace(0.5, 5.0, n)
    e = 1.0 - 0.06 * v
    x = np.linspace(1e-6, 1e-4, n)
    times = 1e-4 * v**-0.2
    forces = 1e3 * v**1.2
    t = np.linspace(0.0, 2e-4, n)
    calls = {
        "time_law": lambda: hcimpact.time_law(t, **contact),
        "time_law_samples": lambda: hcimpact.time_law_samples(n, **contact),
        "fit_damping": lambda: hcimpact.fit_damping(v, e),
        "fit_damping_linear": lambda: hcimpact.fit_damping_linear(v, e),
        "fit_static": lambda: hcimpact.fit_static(x, 1.7e10 * x**1.5),
        "fit_elastic": lambda: hcimpact.fit_elastic(v, mass=0.1, damping=0.1,
                                                    contact_time=times, peak_force=forces),
        "fit_impact": lambda: hcimpact.fit_impact(v, mass=0.1, contact_time=times,
                                                  peak_force=forces, restitution=e),
    }
    name, headroom = sys.argv[2], int(sys.argv[1])
    if name.startswith("fit_"):
        hcimpact.fit_damping(v[:8], e[:8])    # the LAPACK component loaded
    else:
        hcimpact.time_law(0.0, **contact)
    cap_address_space(headroom)
    report(calls[name])
""")


def _has_fits() -> bool:
    from hcimpact import _library
    return _library.component("hcimpact_fit_damping", "hcimpact_lapack") is not None


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS and /proc: Linux")
@pytest.mark.parametrize("name, headroom", [
    ("time_law", 80), ("time_law_samples", 96),
    pytest.param("fit_damping", 64, marks=pytest.mark.lapack),
    pytest.param("fit_damping_linear", 64, marks=pytest.mark.lapack),
    pytest.param("fit_static", 64, marks=pytest.mark.lapack),
    pytest.param("fit_elastic", 80, marks=pytest.mark.lapack),
    pytest.param("fit_impact", 96, marks=pytest.mark.lapack),
])
def test_time_law_and_fits_out_of_memory(name, headroom):
    if name.startswith("fit_") and not _has_fits():
        pytest.skip("the library has no fits (LAPACK component)")
    lines = _run_capped(_CALLS, str(headroom), name)
    assert lines[0] == "OutOfMemoryError True 16", lines
    assert lines[1].startswith("out of memory"), lines
