"""Stopping clingo calls safely: signals deferred while a call runs, and the solve watchdog.

Why a control is never left in the middle of a call: docs/proofs/solving.md, "The watchdog
and signals".
"""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager

import clingo

#: how often a waiting solve looks for a deferred signal (seconds)
POLL_S = 0.05


class _Watchdog:
    """One thread per process that interrupts solve calls running in their callers' threads
    once their time is up."""

    NAME = "foon2asp-solve-watchdog"

    def __init__(self) -> None:
        self.reset()
        os.register_at_fork(after_in_child=self.reset)

    def reset(self) -> None:
        self._cond = threading.Condition()
        self._jobs: dict[int, tuple[clingo.Control, float]] = {}
        self._next = 0
        self._thread: threading.Thread | None = None
        #: the thread looks at the jobs every POLL_S seconds (else it waits to be told)
        self._awake = False

    @contextmanager
    def limit(self, ctl: clingo.Control, seconds: float) -> Iterator[None]:
        """The body's solve call on ``ctl`` is interrupted after ``seconds``."""
        job = self._add(ctl, seconds)
        try:
            yield
        finally:
            with self._cond:
                self._jobs.pop(job, None)

    def interrupt(self, ctl: clingo.Control) -> None:
        """Interrupt the solve call running on ``ctl`` now, from the watchdog's thread."""
        self._add(ctl, 0.0)

    def forget(self, ctl: clingo.Control) -> None:
        """Drop the interrupts of ``ctl`` not yet made."""
        with self._cond:
            for job in [job for job, (c, _) in self._jobs.items() if c is ctl]:
                del self._jobs[job]

    def _add(self, ctl: clingo.Control, seconds: float) -> int:
        with self._cond:
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name=self.NAME, daemon=True)
                self._thread.start()
            self._next += 1
            self._jobs[self._next] = (ctl, time.monotonic() + seconds)
            if not seconds or not self._awake:  # awake, it looks every POLL_S seconds anyway
                self._awake = True
                self._cond.notify()
            return self._next

    def _run(self) -> None:
        with self._cond:
            idle = 0.0
            while True:
                now = time.monotonic()
                for job, (ctl, at) in list(self._jobs.items()):
                    if at <= now:
                        del self._jobs[job]
                        ctl.interrupt()
                if self._jobs:
                    idle = 0.0
                    soonest = min(at for _, at in self._jobs.values())
                    self._cond.wait(min(POLL_S, max(soonest - now, 0.0)))
                elif idle < 1.0:
                    idle += POLL_S
                    self._cond.wait(POLL_S)
                else:  # a second without jobs: sleep until the next one
                    self._awake = False
                    self._cond.wait()


#: the watchdog of this process
WATCHDOG = _Watchdog()
#: the name of the watchdog's thread
SOLVE_WATCHDOG = _Watchdog.NAME


_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class _Deferral:
    depth = 0
    pending: int | None = None


_DEFER = _Deferral()


def _record(signum, frame) -> None:
    if _DEFER.pending is None:
        _DEFER.pending = signum


def signal_pending() -> bool:
    """Did SIGINT or SIGTERM arrive during the current deferred section?"""
    return _DEFER.pending is not None


def _deliver(signum: int, handler) -> None:
    if callable(handler):
        handler(signum, None)
    elif handler == signal.SIG_DFL:
        if signum == signal.SIGINT:
            raise KeyboardInterrupt
        os.kill(os.getpid(), signum)


@contextmanager
def deferred_signals() -> Iterator[None]:
    """Run the body with SIGINT/SIGTERM recorded instead of raised; deliver the first one afterwards.

    Outside the main thread this does nothing; ignored signals stay ignored.
    """
    if _DEFER.depth or threading.current_thread() is not threading.main_thread():
        yield  # nested: the outer section delivers
        return
    saved = {}
    for signum in _SIGNALS:
        handler = signal.getsignal(signum)
        if handler is not signal.SIG_IGN and handler is not None:
            saved[signum] = handler
            signal.signal(signum, _record)
    _DEFER.depth, _DEFER.pending = 1, None
    try:
        yield
    finally:
        _DEFER.depth = 0
        for signum, handler in saved.items():
            signal.signal(signum, handler)
        pending, _DEFER.pending = _DEFER.pending, None
        if pending is not None and pending in saved:
            _deliver(pending, saved[pending])
