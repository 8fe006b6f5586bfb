"""The one wrapper of UWrMaxSat (through hermax): weighted MaxSAT in a child process.

UWrMaxSat (Piotrów, ICTAI 2020; the competition version of hermax's
``UWrMaxSATCompetition``) proves the optimum of the hardest goals of the hard presets
about ten times as fast as RC2 (BENCHMARKS.md, "UWrMaxSat after RC2"), but its
Python binding can be neither interrupted nor asked for a lower bound.  So it runs in
a child process of its own (:class:`Solver`), which a deadline or a halt kills; one
child serves one process's goals one after another and is started again after a
kill.  It prints nothing on the caller's output: the child's standard output is
/dev/null, its answers travel on a pipe of their own.

A problem is a weighted partial MaxSAT formula: hard clauses over variables
``1..nvars`` and soft unit literals with positive integer weights; the answer is the
optimum's true variables (``"optimal"``), ``"infeasible"`` (the hard clauses have no
model) or ``"stopped"`` (cut short, or the solver failed: no answer).
"""

from __future__ import annotations

import os
import pickle
import queue
import select
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

#: how often the caller looks at the clock and its halt while the child solves (seconds)
POLL_S = 0.02


#: a child that dies this many times in a row without an answer (not killed by the caller) is
#: not started again in this process: the solver is taken as broken, and RC2 answers alone
GIVE_UP_AFTER = 2


def available() -> bool:
    """Is hermax (with its UWrMaxSat) installed, and its solver not found broken here?"""
    if _solver is not None and _solver.broken:
        return False
    try:
        from hermax.core.ipamir_solver_interface import SolveStatus  # noqa: F401
        from hermax.non_incremental import UWrMaxSATCompetition  # noqa: F401
    except ImportError:
        return False
    return True


class Solver:
    """A child process that solves MaxSAT problems one at a time (see the module)."""

    def __init__(self) -> None:
        self._child: subprocess.Popen | None = None
        self._lock = threading.Lock()
        #: children that died in a row without an answer
        self._deaths = 0
        #: the child keeps dying: no more solves in this process (they answer "stopped" at once)
        self.broken = False

    def _start(self) -> subprocess.Popen:
        if self._child is None or self._child.poll() is not None:
            read_end, write_end = os.pipe()  # the child's answers, apart from its standard output
            try:
                self._child = _spawn(
                    # the file as a script (-P: its folder not on the path): the child imports hermax, not foon2asp
                    [sys.executable, "-P", os.path.abspath(__file__), str(write_end), str(os.getpid())],
                    stdin=subprocess.PIPE,
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                    pass_fds=(write_end,),
                )
            finally:
                os.close(write_end)
            self._answers = os.fdopen(read_end, "rb")
        return self._child

    def stop(self) -> None:
        """Kill the child (a new one starts at the next solve)."""
        child, self._child = self._child, None
        if child is not None:
            child.kill()
            child.wait()
            try:
                self._answers.close()
            except OSError:  # pragma: no cover - already closed
                pass

    def solve(
        self,
        nvars: int,
        hard: Sequence[Sequence[int]],
        soft: Sequence[tuple[int, int]],
        deadline: float | None = None,
        halt: Callable[[], bool] | None = None,
    ) -> tuple[str, set[int] | None]:
        """``("optimal", true variables)``, ``("infeasible", None)`` or ``("stopped", None)``
        (the ``deadline``, ``time.perf_counter()``, or ``halt()`` came first)."""
        while not self._lock.acquire(timeout=POLL_S):  # another thread's problem is being solved
            if _over(deadline, halt):
                return "stopped", None
        try:
            if self.broken:
                return "stopped", None
            try:
                child = self._start()
                assert child.stdin is not None
                pickle.dump((nvars, [list(c) for c in hard], list(soft)), child.stdin, pickle.HIGHEST_PROTOCOL)
                child.stdin.flush()
                while True:
                    ready, _, _ = select.select([self._answers], [], [], POLL_S)
                    if ready:
                        status, model = pickle.load(self._answers)
                        self._deaths = 0
                        if status == "error":  # the solver failed: no answer from it
                            return "stopped", None
                        return status, (None if model is None else set(model))
                    if _over(deadline, halt):
                        self.stop()
                        return "stopped", None
            except (OSError, EOFError, pickle.UnpicklingError):  # the child died (killed from outside, crashed)
                self.stop()
                self._deaths += 1
                self.broken = self._deaths >= GIVE_UP_AFTER
                return "stopped", None
            except BaseException:  # an interrupt here: the child must not outlive the call
                self.stop()
                raise
        finally:
            self._lock.release()


_spawns: queue.Queue = queue.Queue()


def _spawner() -> None:
    """Start the children asked for: on Linux a child is killed when the *thread* that started
    it ends (its parent-death signal), so one thread that lives as long as the process starts them all."""
    while True:
        args, kwargs, box, ready = _spawns.get()
        try:
            box.append(subprocess.Popen(args, **kwargs))
        except BaseException as error:  # noqa: BLE001 (handed to the caller)
            box.append(error)
        ready.set()


_spawner_lock = threading.Lock()
_spawner_thread: threading.Thread | None = None


def _spawn(args: list[str], **kwargs: Any) -> subprocess.Popen:
    """``subprocess.Popen(args, **kwargs)`` on the spawning thread (:func:`_spawner`)."""
    global _spawner_thread
    with _spawner_lock:
        if _spawner_thread is None or not _spawner_thread.is_alive():
            _spawner_thread = threading.Thread(target=_spawner, name="uwrmaxsat-spawner", daemon=True)
            _spawner_thread.start()
    box: list = []
    ready = threading.Event()
    _spawns.put((args, kwargs, box, ready))
    ready.wait()
    if isinstance(box[0], BaseException):
        raise box[0]
    return box[0]


def _over(deadline: float | None, halt: Callable[[], bool] | None) -> bool:
    """Has the ``deadline`` passed, or does ``halt()`` say stop?"""
    return (halt is not None and halt()) or (deadline is not None and time.perf_counter() >= deadline)


_solver: Solver | None = None


def solver() -> Solver:
    """This process's child solver (one per process, made on first use)."""
    global _solver
    if _solver is None:
        _solver = Solver()
    return _solver


def _serve(answers_fd: int, parent: int) -> None:
    """The child: read problems on standard input, answer each on ``answers_fd``."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent stops the child; Ctrl-C is the parent's
    if sys.platform.startswith("linux"):  # never outlive the parent (the solver holds the
        try:  # interpreter while it runs: no thread of the child could watch for it)
            import ctypes

            ctypes.CDLL(None).prctl(1, 9)  # PR_SET_PDEATHSIG, SIGKILL
        except (OSError, AttributeError):  # pragma: no cover - no prctl
            pass
        if os.getppid() != parent:  # the parent died before that
            return
    from hermax.core.ipamir_solver_interface import SolveStatus
    from hermax.non_incremental import UWrMaxSATCompetition
    from pysat.formula import WCNF

    out = os.fdopen(answers_fd, "wb")
    source = sys.stdin.buffer
    while True:
        try:
            nvars, hard, soft = pickle.load(source)
        except EOFError:
            return
        formula = WCNF()
        formula.hard = hard
        formula.soft = [[lit] for lit, _ in soft]
        formula.wght = [w for _, w in soft]
        formula.nv = nvars
        formula.topw = sum(formula.wght) + 1
        solver = UWrMaxSATCompetition(formula)
        solver.solve()
        status = solver.get_status()
        answer: tuple[str, list[int] | None] = ("error", None)
        if status == SolveStatus.OPTIMUM:
            answer = ("optimal", [lit for lit in solver.get_model() or () if lit > 0])
        elif status == SolveStatus.UNSAT:
            answer = ("infeasible", None)
        pickle.dump(answer, out, pickle.HIGHEST_PROTOCOL)
        out.flush()


if __name__ == "__main__":
    _serve(int(sys.argv[1]), int(sys.argv[2]))
