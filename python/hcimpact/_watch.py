# SPDX-License-Identifier: Apache-2.0
"""Watching a run of ``hcimpact.chain``: the monitor it hands to
``hcimpact_chain_simulate_monitored`` (include/hcimpact_cvode.h).

The library calls the monitor's poll every 64 passes of its loop (steps of a cluster,
events of the closed forms). The poll calls the caller's ``progress(time, steps,
events)``, whose true answer stops the run, and stops it on Ctrl-C: while the library
computes, Python runs no signal handler, so a SIGINT is caught by a handler installed
for the call that only notes it; the next poll sees it and stops the run, and once the
library has returned the handler that was there before is called with it (Python's
default raises ``KeyboardInterrupt``). An exception that ``progress`` raises stops the
run too and is raised once the library has returned (raised inside the callback,
ctypes would print and drop it); with a SIGINT noted as well, the SIGINT's exception
is raised, the other as its context.

``hcimpact.chain`` runs a system a second time when it made more contacts than its
first array held (the run is deterministic): :meth:`Watch.again` makes the polls of
that run, the same as the first one's, skip ``progress``, which thus sees one run.

Only the main thread of the main interpreter can install a signal handler: a run
elsewhere is stopped by its ``progress`` alone (Python delivers Ctrl-C to the main
thread). Other signal handlers of the program that raise (SIGTERM raising
``SystemExit``, an alarm) run at a poll's first instruction, before it can catch
anything: ctypes prints such an exception and drops it, and the run goes on.
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
        self._polls = 0       # polls of the current run
        self._shown = 0       # polls that called progress, over the runs
        # (kept here: the library calls it until the call returns)
        self._poll = ChainPoll(self._on_poll)
        self.monitor = ChainMonitor(self._poll, None)

    def __enter__(self) -> Watch:
        if threading.current_thread() is threading.main_thread():
            previous = signal.getsignal(signal.SIGINT)
            if callable(previous):
                try:
                    signal.signal(signal.SIGINT, self._on_signal)
                    self._previous = previous
                except ValueError:      # (a subinterpreter: no handler of its own)
                    pass
        return self

    def __exit__(self, *exc_info: Any) -> None:
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)

    def again(self) -> None:
        """The same run once more: its polls repeat those already shown."""
        self._polls = 0

    def _on_signal(self, signum: int, frame: FrameType | None) -> None:
        self._signal = (signum, frame)

    def _on_poll(self, data: Any, time: float, steps: int, events: int) -> int:
        try:
            self._polls += 1
            stopped = self._signal is not None or self._error is not None
            if stopped or self._progress is None or self._polls <= self._shown:
                return int(stopped)
            self._shown = self._polls
            return int(bool(self._progress(time, steps, events)))
        except BaseException as error:  # noqa: B036 (raised after the call returns)
            self._error = error
            return 1

    def raise_pending(self) -> None:
        """Raise what stopped the run: the SIGINT through the handler there was before
        (KeyboardInterrupt by default, with an exception of ``progress`` as its
        context), or the exception of ``progress``; nothing when neither happened."""
        error, self._error = self._error, None
        if self._signal is not None:
            signum, frame = self._signal
            self._signal = None
            try:
                self._previous(signum, frame)
            except BaseException as raised:
                if error is not None and raised.__context__ is None:
                    raised.__context__ = error
                raise
        if error is not None:
            raise error
