"""Stopping clingo calls safely: signals deferred while a call runs, and the solve watchdog.

An interrupt that a finaliser would drop is kept and raised again (:func:`kept_interrupts`). Why
a control is never left in the middle of a call, and why no interrupt is lost: docs/proofs/solving.md,
"The watchdog and signals".
"""

from __future__ import annotations

import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager

from foon2asp.errors import Terminated

TYPE_CHECKING = False  # typing's, without importing typing (the command line imports this module first)
if TYPE_CHECKING:
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
    #: a signal whose exception Python dropped (raised in a finaliser): raised again at the next safe point
    dropped: int | None = None
    #: an interrupt came (under :func:`kept_interrupts`)
    interrupted = False
    #: the ``sys.unraisablehook`` that :func:`keep_interrupts_until_exit` replaced
    hook: Callable | None = None


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


def raise_dropped() -> None:
    """Raise now the interrupt that a finaliser dropped (:func:`kept_interrupts`), if any: a safe point."""
    signum, _DEFER.dropped = _DEFER.dropped, None
    if signum is not None:
        _deliver(signum, signal.getsignal(signum))


class _Noted:
    """A signal handler that notes that an interrupt came, then calls ``handler``."""

    def __init__(self, handler) -> None:
        self.handler = handler

    def __call__(self, signum, frame) -> None:
        _DEFER.interrupted = True
        self.handler(signum, frame)


def _unraisable(unraisable) -> None:
    """``sys.unraisablehook`` of :func:`keep_interrupts_until_exit`."""
    exc = unraisable.exc_value
    if isinstance(exc, KeyboardInterrupt) and threading.current_thread() is threading.main_thread():
        _DEFER.interrupted = True
        if _DEFER.dropped is None:
            _DEFER.dropped = signal.SIGTERM if isinstance(exc, Terminated) else signal.SIGINT
    elif not _DEFER.interrupted and _DEFER.hook is not None:
        _DEFER.hook(unraisable)


def keep_interrupts_until_exit() -> None:
    """From now until the process ends, an interrupt raised in a finaliser is kept (:func:`kept_interrupts`),
    and once an interrupt has come, a finaliser that fails is not reported: its object was left half
    built by the interrupt (clingo's objects are freed by finalisers that assume a whole object).
    For a program's entry point, whose process ends with the command."""
    if sys.unraisablehook is not _unraisable:
        _DEFER.hook = sys.unraisablehook
        sys.unraisablehook = _unraisable


@contextmanager
def kept_interrupts() -> Iterator[None]:
    """Inside the body no interrupt is lost: one raised where Python can only drop it, in a
    finaliser (clingo's ``Control.__del__`` freeing a control, a generator closed by the collector),
    is kept and raised again at the next safe point: where a deferred section begins or ends
    (every clingo call), or when the body is over. Once an interrupt has come, a finaliser that
    fails is not reported (:func:`keep_interrupts_until_exit`, which goes on after the body)."""
    installed = sys.unraisablehook is not _unraisable
    keep_interrupts_until_exit()
    noted: dict[signal.Signals, _Noted] = {}
    for signum in _SIGNALS:
        current = signal.getsignal(signum)
        if callable(current) and not isinstance(current, _Noted):
            noted[signum] = _Noted(current)
            signal.signal(signum, noted[signum])
    try:
        yield
        raise_dropped()
    finally:
        for signum, note in noted.items():
            previous = note.handler
            if signal.getsignal(signum) is note:  # (else the body set a handler of its own)
                signal.signal(signum, previous)
        _DEFER.dropped = None
        if installed:
            sys.unraisablehook, _DEFER.hook = _DEFER.hook or sys.__unraisablehook__, None
            _DEFER.interrupted = False


@contextmanager
def deferred_signals() -> Iterator[None]:
    """Run the body with SIGINT/SIGTERM recorded instead of raised; deliver the first one afterwards
    (or, before the body, one that a finaliser dropped: :func:`kept_interrupts`).

    Outside the main thread this does nothing; ignored signals stay ignored.
    """
    if _DEFER.depth or threading.current_thread() is not threading.main_thread():
        yield  # nested: the outer section delivers
        return
    raise_dropped()
    # cleared before the handlers change: a signal recorded as they change is this section's
    _DEFER.pending = None
    saved = {}
    for signum in _SIGNALS:
        handler = signal.getsignal(signum)
        if handler is not signal.SIG_IGN and handler is not None:
            saved[signum] = handler
            signal.signal(signum, _record)
    _DEFER.depth = 1
    try:
        yield
    finally:
        _DEFER.depth = 0
        for signum, handler in saved.items():
            signal.signal(signum, handler)
        pending, _DEFER.pending = _DEFER.pending, None
        if pending is not None and pending in saved:
            _deliver(pending, saved[pending])
        else:
            raise_dropped()
