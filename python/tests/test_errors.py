# SPDX-License-Identifier: Apache-2.0
"""Which exception a status becomes (hcimpact._types.error_class, the one place that
decides): the chain's out of memory, status 14 with a message that begins "out of
memory", is an OutOfMemoryError (an HcimpactError and a MemoryError); a wrong size,
status 14 with any other message, stays an InputError. On Linux a real chain of 10^6
bodies runs out of memory in a child process whose address space is capped
(setrlimit RLIMIT_AS, as test/cvode/chain_memory_test.c does in C).
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

import hcimpact
from hcimpact import _api, _types


@pytest.mark.parametrize("status, detail, expected", [
    (14, "out of memory (the engine's arrays): the system is too large for the memory "
         "available", hcimpact.OutOfMemoryError),
    (14, "", hcimpact.InputError),
    (14, "sample times decrease: sample 3 is before sample 2", hcimpact.InputError),
    (14, "n = 0: a system needs at least one body (out of memory is not this)",
     hcimpact.InputError),
    (8, "out of memory", hcimpact.InputError),
    (11, "out of memory", hcimpact.ComputationError),
])
def test_status_and_message_choose_the_exception(status, detail, expected):
    assert _types.error_class(status, detail) is expected


def test_out_of_memory_is_a_memory_error_and_an_hcimpact_error():
    with pytest.raises(MemoryError) as caught:
        _api._raise(14, "hcimpact_chain_simulate", detail="out of memory (the copies of "
                    "the input): the system is too large for the memory available")
    error = caught.value
    assert isinstance(error, hcimpact.OutOfMemoryError)
    assert isinstance(error, hcimpact.HcimpactError)
    assert not isinstance(error, ValueError)
    assert error.status == 14 and error.name == "HCIMPACT_ERR_SIZE"
    # the library's account alone: status 14's text ("the wrong size") does not fit
    assert error.message.startswith("out of memory (the copies of the input)")
    assert error.function == "hcimpact_chain_simulate"


def test_a_wrong_size_stays_an_input_error():
    with pytest.raises(hcimpact.InputError) as caught:
        _api._raise(14, "hcimpact_chain_simulate", detail="contact_capacity < 0")
    assert isinstance(caught.value, ValueError)
    assert not isinstance(caught.value, MemoryError)


# The child: a row of 10^6 balls with gaps, neighbours approaching in pairs (the first
# case of chain_memory_test.c); its arguments built in full before the cap, the cap its
# address space now plus HEADROOM (160 MB), enough for this package's own arrays (the
# laws, the outputs: 48 MB is too little for them, 96 MB enough) and far too little for
# the library's copies and engine (which fail at 96, 200 and 400 MB, succeed at 800 MB).
_CHILD = textwrap.dedent("""
    import resource, sys
    import numpy as np
    import hcimpact
    HEADROOM = int(sys.argv[1]) << 20
    n = 10**6
    masses = np.full(n, 4.1e-3)
    velocities = np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    gaps = np.full(n - 1, 1e-3)
    stiffness = np.full(n - 1, 8.6e9)
    hcimpact.has_chain()
    with open("/proc/self/statm") as statm:
        used = int(statm.read().split()[0]) * resource.getpagesize()
    resource.setrlimit(resource.RLIMIT_AS, (used + HEADROOM, used + HEADROOM))
    try:
        hcimpact.chain(masses, velocities, gaps=gaps, stiffness=stiffness, damping=0.01,
                       t_end=6e-4, max_contacts=0)
    except hcimpact.HcimpactError as error:
        print(type(error).__name__, isinstance(error, MemoryError), error.status)
        print(error.message)
    else:
        print("no error")
""")


@pytest.mark.cvode
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS and /proc: Linux")
def test_a_real_chain_out_of_memory():
    if not hcimpact.has_chain():
        pytest.skip("the library has no hcimpact_chain_simulate (CVODE component)")
    try:
        import resource
        limit = resource.getrlimit(resource.RLIMIT_AS)
    except (ImportError, OSError) as exc:
        pytest.skip(f"no address-space limit here: {exc}")
    if limit[1] != resource.RLIM_INFINITY:
        pytest.skip(f"the address space is limited already ({limit[1]} bytes)")
    run = subprocess.run([sys.executable, "-c", _CHILD, "160"], capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert lines[0] == "OutOfMemoryError True 14", run.stdout + run.stderr
    assert lines[1].startswith("out of memory ("), lines
