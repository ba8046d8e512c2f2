# SPDX-License-Identifier: Apache-2.0
"""Watching a run of hcimpact.chain (hcimpact/_watch.py): ``progress`` is called with
the time and the work in order, a true answer stops the run (ComputationError), an
exception it raises is raised, a run that nobody stops equals the run without
``progress``, a run made again for a longer contact list is shown once, and Ctrl-C (a real SIGINT from another thread, while the library
computes) stops a long run within a poll and raises KeyboardInterrupt, with the
SIGINT handler of before put back."""

from __future__ import annotations

import os
import signal
import threading
import time

import numpy as np
import pytest

import hcimpact
from hcimpact import _chain

pytestmark = pytest.mark.cvode


@pytest.fixture(autouse=True)
def needs_chain():
    if not hcimpact.has_chain():
        pytest.skip("the library has no CVODE component")


def struck_row(**kwargs):
    """Twelve touching steel beads, the first struck at 1 m/s (some thousand steps)."""
    n = 12
    v = np.zeros(n)
    v[0] = 1.0
    return hcimpact.chain(np.full(n, 0.0163), v, stiffness=1.7135e10 / np.sqrt(2.0), **kwargs)


def resting_stack(**kwargs):
    """A ball of 10 g under one of 1 g dropped 1 m onto a floor, b = 0.01 s/m, to rest:
    minutes of computing (doc/chains.md, "Left to do")."""
    law = {"stiffness": 1e8, "exponent": 1.5, "damping": 0.01, "gap": 1.0}
    return hcimpact.chain([0.01, 0.001], [0.0, 0.0], gaps=[0.0], stiffness=1e8, damping=0.01,
                          wall_left=law, gravity=-9.81, rtol=1e-8, **kwargs)


def test_progress_sees_the_run_and_changes_nothing():
    seen = []
    plain = struck_row()
    watched = struck_row(progress=lambda t, steps, events: seen.append((t, steps, events)))
    assert np.array_equal(watched.velocities, plain.velocities)
    assert np.array_equal(watched.positions, plain.positions)
    assert watched.counters == plain.counters and watched.time == plain.time
    assert len(seen) >= plain.counters["steps"] // 64 > 0
    assert seen == sorted(seen)                          # time, steps, events in order
    assert all(isinstance(s, int) and isinstance(c, int) for _, s, c in seen)
    assert seen[-1][0] <= plain.time and seen[-1][1] <= plain.counters["steps"]


def test_a_true_answer_stops_the_run():
    calls = []

    def stop_at_third(t, steps, events):
        calls.append(t)
        return len(calls) >= 3

    with pytest.raises(hcimpact.ComputationError, match="stopped by the caller's monitor"):
        struck_row(progress=stop_at_third)
    assert len(calls) == 3


def test_an_exception_of_progress_is_raised():
    calls = []

    def fails(t, steps, events):
        calls.append(t)
        raise ValueError("from progress")

    with pytest.raises(ValueError, match="from progress"):
        struck_row(progress=fails)
    assert len(calls) == 1


def test_a_run_made_again_is_shown_once(monkeypatch):
    """chain makes a run again when its contacts did not fit the first array: progress
    sees the calls of one run, in order, as many as without the second run."""
    once, twice = [], []
    struck_row(progress=lambda *seen: once.append(seen))
    monkeypatch.setattr(_chain, "_FIRST_CAPACITY", 2 - 8 * 12)   # room for 2
    result = struck_row(progress=lambda *seen: twice.append(seen))
    assert result.n_contacts > 2 and len(result.contacts) == result.n_contacts
    assert twice == once and len(once) > 0


def test_ctrl_c_wins_over_an_exception_of_progress():
    def interrupted_then_fails(t, steps, events):
        signal.raise_signal(signal.SIGINT)
        raise ValueError("after the signal")

    if threading.current_thread() is not threading.main_thread():
        pytest.skip("signals reach the main thread only")
    with pytest.raises(KeyboardInterrupt) as info:
        struck_row(progress=interrupted_then_fails)
    assert isinstance(info.value.__context__, ValueError)


def test_progress_must_be_a_function():
    with pytest.raises(hcimpact.InputError, match="progress"):
        struck_row(progress=3)


def test_ctrl_c_stops_a_long_run():
    if threading.current_thread() is not threading.main_thread():
        pytest.skip("signals reach the main thread only")
    before = signal.getsignal(signal.SIGINT)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            resting_stack()
    finally:
        timer.cancel()
    elapsed = time.monotonic() - start
    assert elapsed < 30.0, f"the run went on for {elapsed:.1f} s after Ctrl-C"
    assert signal.getsignal(signal.SIGINT) is before
