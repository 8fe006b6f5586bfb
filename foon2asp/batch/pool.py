"""Where a batch's goals run: a pool of worker processes or a Dask cluster, runners built once per worker.

How workers start, stop and exit with their parent, and how Dask is used: docs/batch.md, "Workers and Dask".
``multiprocessing`` is imported only where a pool starts: importing it reads 32 bytes of the
kernel's randomness in the way that waits until the kernel has gathered enough, which on a
freshly started machine can take a minute, and most commands start no pool.
"""

from __future__ import annotations

import ctypes
import json
import os
import signal
import sys
import threading
import time
import uuid
from collections.abc import Callable, Generator, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from foon2asp.analysis.compare import judge
from foon2asp.asp.interrupts import SOLVE_WATCHDOG, deferred_signals
from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem
from foon2asp.methods.runner import AHEAD, GoalRunner, Parts
from foon2asp.tree.serialize import tree_json

if TYPE_CHECKING:
    from multiprocessing.context import BaseContext

#: ``workers``: one process, then a pool on every usable core once the batch is long
AUTO = 0
#: seconds in this process before ``AUTO`` hands the remaining tasks to a pool
SWITCH_S = 5.0
#: the start method of the pool's workers; None: :func:`start_method` chooses
START_METHOD: str | None = None
#: why a pool could not start: its workers ran the main script again and reached the batch
NEEDS_GUARD = (
    "the worker processes run this script again and it starts the batch again: put the script's code under "
    '`if __name__ == "__main__":` (or use workers=1)'
)
#: the name of the process that checks that workers can start
_PROBE = "foon2asp-probe"


def usable_cores() -> int:
    """The cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def reruns_main() -> bool:
    """Whether a ``spawn`` or ``forkserver`` worker runs this process's main module again (a script
    run by its path, or a module run with ``-m`` that is not a package's ``__main__``)."""
    main = sys.modules.get("__main__")
    name = getattr(getattr(main, "__spec__", None), "name", None)
    if name is not None:
        return not (name == "__main__" or name.endswith(".__main__"))
    return getattr(main, "__file__", None) is not None


def start_method() -> str:
    """The start method of a pool's workers: :data:`START_METHOD` if set; ``fork`` on Linux when a
    spawned worker would run the main script again and no other thread runs here; else ``spawn``."""
    if START_METHOD is not None:
        return START_METHOD
    # tqdm's monitor and the solve watchdog wait holding no lock a forked worker could need
    here, quiet = threading.current_thread(), ("tqdm_monitor", SOLVE_WATCHDOG)
    others = [t for t in threading.enumerate() if t is not here and t.name not in quiet]
    return "fork" if sys.platform.startswith("linux") and reruns_main() and not others else "spawn"


def refuse_while_starting() -> None:
    """Stop a worker that is being started and has reached a batch while running the main
    script again (no ``if __name__ == "__main__":`` guard), before it opens any results file."""
    started = sys.modules.get("multiprocessing")
    if started is None:  # a worker being started has imported it
        return
    process = started.current_process()
    if not getattr(process, "_inheriting", False):  # Python's own mark of a worker being prepared
        return
    if process.name != _PROBE:
        print(f"foon2asp: {NEEDS_GUARD}", file=sys.stderr)
    raise SystemExit(1)


def _probe() -> None:
    """A worker that only starts (:func:`_check_start`)."""


def _check_start(context: BaseContext) -> None:
    """Raise :data:`NEEDS_GUARD` if a worker of ``context`` cannot start (checked only where it
    would run the main script again)."""
    if context.get_start_method() == "fork" or not reruns_main():
        return
    probe = context.Process(target=_probe, name=_PROBE)  # type: ignore[attr-defined]
    probe.start()
    probe.join()
    if probe.exitcode != 0:
        raise InputError(NEEDS_GUARD)


@dataclass
class BatchSpec:
    """Everything a process needs to build its runners (picklable)."""

    problem: Problem
    methods: list[str]
    options: AspOptions = field(default_factory=AspOptions)
    #: "whole" | "per-goal" | "auto" (resolved by run_batch with choose_grounding)
    grounding: str = "whole"
    shortcuts: bool = True


class Worker:
    """The runners of one process: built once, then asked goal after goal."""

    def __init__(self, spec: BatchSpec):
        self.spec = spec
        parts = Parts(spec.problem)
        self.runners = {
            name: GoalRunner(name, spec.problem, spec.options, spec.grounding, spec.shortcuts, parts)
            for name in spec.methods
        }

    def ahead(self, tasks: list[tuple[int, str]]) -> None:
        """Plan ``tasks``, the next ones this worker runs, and decide their goals together where
        the plan can (:meth:`GoalRunner.ahead`)."""
        for name, runner in self.runners.items():
            runner.ahead([goal for goal, method in tasks if method == name])

    def planned(self, goal: int, method: str) -> bool:
        """Was ``goal`` planned ahead for ``method`` (:meth:`ahead`) and not run yet?"""
        return self.runners[method].planned(goal)

    def run_block(self, tasks: list[tuple[int, str]]) -> list[str]:
        """The results of ``tasks`` (:meth:`run`), planned together first (:meth:`ahead`): a Dask
        chunk's, whose results come back together."""
        self.ahead(tasks)
        return [self.run(goal, method) for goal, method in tasks]

    def run(self, goal: int, method: str) -> str:
        """The result of ``method`` for ``goal`` as one JSON line (with newline)."""
        tree = judge(self.spec.problem, self.runners[method](goal), self.spec.options.substitutes)  # as compare
        record = tree_json(self.spec.problem, tree)
        record["requested_method"] = method
        return json.dumps(record, ensure_ascii=False) + "\n"


#: the worker of a pool process (built by the pool's initializer)
_WORKER: Worker | None = None


def _exit_with_parent() -> None:
    """Make this process exit when its parent dies (also by SIGKILL)."""
    parent = os.getppid()
    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, signal.SIGTERM, 0, 0, 0)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):  # pragma: no cover - no prctl
            pass

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="parent-watch", daemon=True).start()


#: the signals a worker may start with blocked (:func:`_workers_starting`)
_WORKER_SIGNALS = {signal.SIGINT, signal.SIGTERM}


@contextmanager
def _workers_starting(method: str) -> Iterator[None]:
    """The body starts the pool's workers: a signal meanwhile waits until they are all started
    (none is left with a half-sent start), and they start with SIGINT blocked, forked ones with
    SIGTERM too, until :func:`_init_worker` has set their own handlers. So Ctrl-C on a terminal,
    which reaches the workers as well, and the pool's SIGTERM never run a handler of the parent's
    that a forked worker inherits; a spawned worker, a fresh interpreter, ends at once on SIGTERM.
    The pool's threads inherit the block, and so do the workers they start later."""
    blocked = {signal.SIGINT} | ({signal.SIGTERM} if method == "fork" else set())
    with deferred_signals():
        if not hasattr(signal, "pthread_sigmask"):  # pragma: no cover - not POSIX
            yield
            return
        before = signal.pthread_sigmask(signal.SIG_BLOCK, blocked)
        try:
            yield
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, before)


def _init_worker(spec: BatchSpec) -> None:
    global _WORKER
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # an interrupt is the parent's to handle
    # the pool ends its workers with SIGTERM: a forked worker must not run the parent's handler
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _WORKER_SIGNALS)  # blocked since it started
    _exit_with_parent()
    _WORKER = Worker(spec)


def _run_in_worker(task: tuple[int, str]) -> str:
    """One task in a pool's worker: goal by goal, so that each result is sent, and written, as soon
    as it is found (a worker handed a block would hold the block's results until its end)."""
    assert _WORKER is not None, "worker not initialised"
    return _WORKER.run(*task)


class Execution:
    """Run ``tasks`` in a pool of ``workers`` processes (:data:`AUTO`: here, then a pool on every
    usable core); iterating yields the JSON lines of the results as they finish, and
    :meth:`close` terminates the pool's workers at once."""

    def __init__(self, spec: BatchSpec, tasks: list[tuple[int, str]], workers: int = 1):
        self.spec, self.tasks = spec, tasks
        self.requested = workers
        #: the most processes that ran tasks so far
        self.workers = 1 if workers == AUTO else workers
        self._results = self._run()

    def __iter__(self) -> Iterator[str]:
        return self._results

    def close(self) -> None:
        self._results.close()

    def _run(self) -> Generator[str, None, None]:
        tasks, workers = self.tasks, self.requested
        if workers <= 1:
            cores = usable_cores() if workers == AUTO else 1
            worker = Worker(self.spec)
            t0 = time.perf_counter()
            done = 0
            for goal, method in tasks:
                if cores > 1 and time.perf_counter() - t0 >= SWITCH_S:
                    break
                if not worker.planned(goal, method):
                    worker.ahead(tasks[done : done + AHEAD])
                yield worker.run(goal, method)
                done += 1
            with deferred_signals():  # its clingo controls are freed with no interrupt in the middle
                del worker
            tasks, workers = tasks[done:], cores
        if not tasks:
            return
        self.workers = workers
        import multiprocessing  # here only (the module's docstring says why)

        context = multiprocessing.get_context(start_method())
        _check_start(context)
        pool = None
        try:
            with _workers_starting(context.get_start_method()):
                pool = context.Pool(workers, initializer=_init_worker, initargs=(self.spec,))
            yield from pool.imap_unordered(_run_in_worker, tasks)
            pool.close()
        finally:
            if pool is not None:  # (an interrupt while it started comes once it has)
                pool.terminate()
                pool.join()


#: the runners of this thread of a Dask worker: ``token`` (the batch's) and ``worker``
_LOCAL = threading.local()


def _run_chunk(token: str, spec: BatchSpec, tasks: list[tuple[int, str]]) -> list[str]:
    """On a Dask worker: the results of ``tasks`` (runners built once per thread and batch)."""
    if getattr(_LOCAL, "token", None) != token:
        _LOCAL.token, _LOCAL.worker = token, Worker(spec)
    return _LOCAL.worker.run_block(tasks)


#: runs a batch's (goal, method) pairs somewhere, yielding their JSON lines as they finish
Executor = Callable[[BatchSpec, list[tuple[int, str]]], Generator[str, None, None]]


def dask_executor(scheduler, chunk: int = 8) -> Executor:
    """A batch executor for :func:`foon2asp.batch.results_file.run_batch` on the Dask ``scheduler``
    (an address such as ``tcp://host:8786`` or a ``distributed.Client``; the extra ``dask``)."""
    try:
        import distributed
    except ModuleNotFoundError:
        raise InputError(
            "--scheduler needs Dask: install the extra with  pip install 'foon2asp[dask]'  (dask[distributed])"
        ) from None

    def run(spec: BatchSpec, tasks: list[tuple[int, str]]) -> Generator[str, None, None]:
        if not tasks:
            return
        own = not isinstance(scheduler, distributed.Client)
        try:
            client = distributed.Client(scheduler) if own else scheduler
        except (OSError, ValueError, TypeError) as exc:
            raise InputError(f"cannot reach the Dask scheduler {scheduler}: {exc}") from None
        try:
            token = uuid.uuid4().hex
            [shared] = client.scatter([spec], broadcast=True)
            futures = [
                client.submit(_run_chunk, token, shared, tasks[i : i + chunk], pure=False)
                for i in range(0, len(tasks), chunk)
            ]
            for future in distributed.as_completed(futures):
                yield from future.result()
        finally:
            if own:
                client.close()

    return run
