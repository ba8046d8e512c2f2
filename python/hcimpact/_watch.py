# SPDX-License-Identifier: Apache-2.0
"""Watching a run of ``hcimpact.chain``: the monitor it hands to
``hcimpact_chain_simulate_monitored`` (include/hcimpact_cvode.h).

The library calls the monitor's poll every 64 passes of its loop (steps of a cluster,
contacts). The poll calls the caller's ``progress(time, steps, contacts)``, whose true
answer stops the run, and stops it on Ctrl-C: while the library computes, Python runs
no signal handler, so a SIGINT is caught by a handler installed for the call that only
notes it; the next poll sees it and stops the run, and once the library has returned
the handler that was there before is called with it (Python's default raises
``KeyboardInterrupt``). An exception that ``progress`` raises stops the run too and is
raised once the library has returned (raised inside the callback, ctypes would print
and drop it).

Only the main thread can install a signal handler: a run in another thread is
stopped by its ``progress`` alone (Python delivers Ctrl-C to the main thread).
"""

from __future__ import annotations

import signal
import threading
from types import FrameType
from typing import Any, Callable

from ._types import ChainMonitor, ChainPoll

__all__ = ["Watch"]


class Watch:
    """The monitor of one call, as a context manager around it (the SIGINT handler is
    installed on entry and put back on exit); :meth:`raise_pending` raises what
    stopped the run, if the caller has to see it."""

    def __init__(self, progress: Callable[[float, int, int], Any] | None) -> None:
        self._progress = progress
        self._error: BaseException | None = None
        self._signal: tuple[int, FrameType | None] | None = None
        self._previous: Any = None
        # (kept here: the library calls it until the call returns)
        self._poll = ChainPoll(self._on_poll)
        self.monitor = ChainMonitor(self._poll, None)

    def __enter__(self) -> Watch:
        if threading.current_thread() is threading.main_thread():
            previous = signal.getsignal(signal.SIGINT)
            if callable(previous):
                self._previous = previous
                signal.signal(signal.SIGINT, self._on_signal)
        return self

    def __exit__(self, *exc_info: Any) -> None:
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)

    def _on_signal(self, signum: int, frame: FrameType | None) -> None:
        self._signal = (signum, frame)

    def _on_poll(self, data: Any, time: float, steps: int, contacts: int) -> int:
        try:
            if self._signal is None and self._error is None and self._progress is not None:
                if self._progress(time, steps, contacts):
                    return 1
            return int(self._signal is not None or self._error is not None)
        except BaseException as error:  # noqa: B036 (raised after the call returns)
            self._error = error
            return 1

    def raise_pending(self) -> None:
        """Raise what stopped the run: the exception of ``progress``, or the SIGINT
        through the handler there was before (KeyboardInterrupt by default); nothing
        when neither happened."""
        if self._error is not None:
            error, self._error = self._error, None
            raise error
        if self._signal is not None:
            signum, frame = self._signal
            self._signal = None
            self._previous(signum, frame)
