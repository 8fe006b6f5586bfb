"""Batch solving: goals x methods, one JSON line per result, resumable.

Every finished result is appended to the output file at once as one complete
JSON line (the ``solve --format json`` shape of one tree plus
``"requested_method"``, the registry name it was asked for): the line is built
in full and written with one ``os.write`` on an append-only descriptor
before the next goal starts.  What is guaranteed:

* a *killed process* (SIGKILL, an interrupt, a crash of Python) loses no line
  it has finished: a line handed to ``os.write`` is in the operating system's
  cache and reaches the file whether or not the process lives on; a signal
  waits until the line is whole, so there is no broken line;
* a *crash of the machine* (power, kernel) can lose only lines not yet synced:
  with ``--fsync`` (the default) the file is ``fsync``-ed at most
  :data:`SYNC_INTERVAL_S` after the previous sync, at the first line finished
  after that interval (group commit), and when the batch ends; so at most the
  lines finished since the last sync are lost, and at worst a last line cut
  short, which ``--resume`` drops.  ``--no-fsync`` leaves syncing to the
  operating system.

``--resume`` skips every (goal, method) pair already in the file.

The file is self-describing and locked: its first line is a header
``{"foon2asp_results": 1, "config": {...}}`` recording the configuration that
produced it (objective, constraints, semantics, solver settings, a hash of
the input); ``--resume`` with another configuration is refused with one line
naming the keys that differ.  While a batch writes, it holds an exclusive
lock on the file (``flock``): a second writer gets a one-line error.

Pool workers ignore SIGINT (the parent stops them) and exit when the
parent dies, even by SIGKILL (``PR_SET_PDEATHSIG`` on Linux, and a thread
watching the parent process elsewhere).

Runners are built once per process (:class:`foon2asp.fastpath.BatchRunner`);
``workers > 1`` runs goals in a process pool whose initializer builds each
worker's runners once.  :mod:`foon2asp.dask_runner` runs the same tasks on a
Dask cluster.
"""

from __future__ import annotations

import ctypes
import hashlib
import json
import multiprocessing
import os
import signal
import statistics
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field, replace
from pathlib import Path

from tqdm import tqdm

try:
    import fcntl
except ModuleNotFoundError:  # pragma: no cover - not POSIX
    fcntl = None  # type: ignore[assignment]

from foon2asp import methods as methods_mod
from foon2asp.analysis.compare import judge
from foon2asp.asp.control import deferred_signals
from foon2asp.asp.facts import facts
from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject
from foon2asp.foon.problem import Problem
from foon2asp.foon.safejson import loads as safe_loads
from foon2asp.methods.planner import GROUNDINGS, BatchRunner, Parts
from foon2asp.tree.results import BatchReport
from foon2asp.tree.serialize import tree_json

#: --grounding: "auto" picks whole or per-goal with :func:`choose_grounding`
GROUNDING_CHOICES = ("auto", *GROUNDINGS)
#: auto: per-goal when the median relevant part is below this share of the viable units ...
AUTO_PART_SHARE = 0.10
#: ... or when there are more viable units than this (the whole grounding's memory)
AUTO_MAX_WHOLE = 50_000
#: ... judged on this many goals, spread over the list
AUTO_SAMPLE = 50


def choose_grounding(problem: Problem, goals: list[int], parts: Parts | None = None) -> tuple[str, str]:
    """``(grounding, reason)`` for ``--grounding auto``.

    ``per-goal`` when the FOON has more than :data:`AUTO_MAX_WHOLE` viable
    units (one grounding of everything costs minutes and gigabytes there), or
    when the median relevant part of a sample of the goals
    (:meth:`Parts.relevant`) is under :data:`AUTO_PART_SHARE` of the viable
    units (each small grounding is then cheap, and one big one would be
    searched for every goal); ``whole`` otherwise (the parts overlap most of
    the FOON, so grounding each of them again would repeat the same work).
    """
    parts = parts if parts is not None else Parts(problem)
    viable = len(parts.viable)
    if viable > AUTO_MAX_WHOLE:
        return "per-goal", f"{viable:,} viable units (more than {AUTO_MAX_WHOLE:,})"
    if not goals:
        return "whole", "no goals"
    step = max(1, len(goals) // AUTO_SAMPLE)
    sample = goals[::step][:AUTO_SAMPLE]
    median = statistics.median(len(parts.relevant(g)[0]) for g in sample)
    share = median / max(1, viable)
    if share < AUTO_PART_SHARE:
        return "per-goal", f"median relevant part {median:g} of {viable:,} viable units ({share:.1%}, under 10 %)"
    return "whole", f"median relevant part {median:g} of {viable:,} viable units ({share:.1%}, 10 % or more)"


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
            name: BatchRunner(name, spec.problem, spec.options, spec.grounding, spec.shortcuts, parts)
            for name in spec.methods
        }

    def run(self, goal: int, method: str) -> str:
        """The result of ``method`` for ``goal`` as one JSON line (with newline)."""
        tree = judge(self.spec.problem, self.runners[method](goal))  # "valid", as compare gives it
        record = tree_json(self.spec.problem, tree)
        record["requested_method"] = method
        return json.dumps(record, ensure_ascii=False) + "\n"

    def run_many(self, tasks: list[tuple[int, str]]) -> list[tuple[int, str, str]]:
        return [(goal, method, self.run(goal, method)) for goal, method in tasks]


# --- the worker of a process pool (built by the pool's initializer) ---

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


def _init_worker(spec: BatchSpec) -> None:
    global _WORKER
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # an interrupt is the parent's to handle
    _exit_with_parent()
    _WORKER = Worker(spec)


def _run_in_worker(tasks: list[tuple[int, str]]) -> list[tuple[int, str, str]]:
    assert _WORKER is not None, "worker not initialised"
    return _WORKER.run_many(tasks)


# --- the output file ---


def _goal_key(problem: Problem, record: dict) -> int | None:
    goal = record.get("goal")
    if not isinstance(goal, dict) or not isinstance(goal.get("label"), str):
        return None
    obj = FoonObject.make(goal["label"], goal.get("states") or (), goal.get("ingredients") or (), goal.get("container"))
    return problem.foon.object_ids.get(obj)


def read_results(path: str | Path, repair: bool = False) -> list[dict]:
    """The records of a results file.

    A last line without its newline or not parseable (a write cut short) is
    dropped -- and cut off the file when ``repair`` is set; a bad line
    elsewhere is an :class:`InputError` naming file and line.
    """
    path = Path(path)
    if not path.exists():
        return []
    data = path.read_bytes()
    pieces = data.split(b"\n")
    # the piece after the last newline is empty unless the last write was cut short
    complete = pieces[:-1]
    records: list[dict] = []
    good_end = 0
    for lineno, raw in enumerate(complete, 1):
        try:
            record = safe_loads(raw.decode("utf-8"), str(path), checked=True) if raw.strip() else None
            if record is not None and not isinstance(record, dict):
                raise ValueError("not an object")
        except (ValueError, UnicodeDecodeError, InputError):
            if lineno == len(complete) and not pieces[-1]:
                break  # a damaged last line: dropped like a cut one
            raise InputError("not a JSON result line (remove or fix it to resume)", str(path), lineno) from None
        if record is not None and HEADER_KEY not in record:
            records.append(record)
        good_end += len(raw) + 1
    if repair and good_end < len(data):
        with open(path, "r+b") as fh:
            fh.truncate(good_end)
            fh.flush()
            os.fsync(fh.fileno())
    return records


HEADER_KEY = "foon2asp_results"
HEADER_VERSION = 1

#: configuration keys that may differ on --resume (they do not change the answers)
RESUMABLE_KEYS = ("methods",)


def configuration(spec: BatchSpec) -> dict:
    """What produced a results file: the answers depend on these (see the module docstring)."""
    o = spec.options
    return {
        "methods": list(spec.methods),
        "objective": list(o.objective),
        "constraints": [[name, hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]] for name, text in o.programs],
        "encodings": list(o.encodings),
        "utensil_rule": spec.problem.utensil_rule,
        "time_limit": o.time_limit,
        "opt_strategy": o.opt_strategy,
        "threads": o.threads,
        "clingo_args": list(o.clingo_args),
        "max_depth": o.max_depth,
        "human_steps": o.human_steps,
        "models": o.models,
        "all_optimal": o.all_optimal,
        "heuristic": o.heuristic,
        "canonical": o.canonical,
        "input_sha256": hashlib.sha256(facts(spec.problem).encode("utf-8")).hexdigest(),
    }


def header_line(config: dict) -> str:
    """The first line of a results file."""
    return json.dumps({HEADER_KEY: HEADER_VERSION, "config": config}, ensure_ascii=False) + "\n"


def read_header(path: str | Path) -> dict | None:
    """The configuration recorded in the header line of a results file (None: no header)."""
    try:
        with open(path, "rb") as fh:
            first = fh.readline()
    except OSError:
        return None
    try:
        value = json.loads(first.decode("utf-8"))
    except (ValueError, UnicodeDecodeError):
        return None
    if isinstance(value, dict) and HEADER_KEY in value and isinstance(value.get("config"), dict):
        return value["config"]
    return None


def config_differences(old: dict, new: dict) -> list[str]:
    """The keys whose values differ (the ones in RESUMABLE_KEYS aside)."""
    keys = sorted(set(old) | set(new))
    return [k for k in keys if k not in RESUMABLE_KEYS and old.get(k) != new.get(k)]


#: with sync on, the longest time between two syncs of the results file while lines are written
SYNC_INTERVAL_S = 0.25


class ResultFile:
    """Append-only result lines, each written whole, synced to disk in groups (at most
    ``sync_interval`` seconds apart, and on close); an exclusive lock (``flock``) while
    open, so a second writer is refused.  ``sync_interval=0`` syncs every line."""

    def __init__(self, path: str | Path, sync: bool = True, sync_interval: float = SYNC_INTERVAL_S):
        self.path = Path(path)
        self.sync = sync
        self.sync_interval = sync_interval
        self._synced = time.monotonic()
        self._dirty = False
        try:
            if self.path.parent and not self.path.parent.exists():
                self.path.parent.mkdir(parents=True, exist_ok=True)
            self.fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        except OSError as exc:
            raise InputError(f"cannot open the results file: {exc.strerror or exc}", str(self.path)) from None
        if fcntl is None:  # pragma: no cover - not POSIX: no lock
            return
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(self.fd)
            raise InputError(
                "results file is in use by another running batch (it holds the lock)", str(self.path)
            ) from None

    def append(self, line: str) -> None:
        data = line.encode("utf-8")
        view = memoryview(data)
        with deferred_signals():  # an interrupt waits until the line is whole
            while view:
                written = os.write(self.fd, view)
                view = view[written:]
            if self.sync:
                self._dirty = True
                if time.monotonic() - self._synced >= self.sync_interval:
                    self.flush()

    def flush(self) -> None:
        """Sync the lines written so far to disk (with sync on)."""
        if self.sync and self._dirty:
            os.fsync(self.fd)
            self._dirty = False
            self._synced = time.monotonic()

    def close(self) -> None:
        try:
            with deferred_signals():
                self.flush()
        finally:
            os.close(self.fd)

    def __enter__(self) -> ResultFile:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


# --- running ---


def pending_tasks(
    problem: Problem, goals: list[int], method_names: list[str], previous: list[dict]
) -> tuple[list[tuple[int, str]], int]:
    """The (goal, method) pairs not yet in ``previous``, and how many were skipped."""
    have = set()
    for record in previous:
        g = _goal_key(problem, record)
        if g is not None:
            have.add((g, record.get("requested_method", record.get("method"))))
    todo: list[tuple[int, str]] = []
    skipped = 0
    seen: set[tuple[int, str]] = set()
    for g in goals:
        for m in method_names:
            if (g, m) in seen:
                continue
            seen.add((g, m))
            if (g, m) in have:
                skipped += 1
            else:
                todo.append((g, m))
    return todo, skipped


def _chunks(tasks: list[tuple[int, str]], size: int) -> Iterator[list[tuple[int, str]]]:
    for i in range(0, len(tasks), size):
        yield tasks[i : i + size]


def execute(
    spec: BatchSpec,
    tasks: list[tuple[int, str]],
    workers: int = 1,
    chunk: int = 1,
) -> Iterator[tuple[int, str, str]]:
    """Run ``tasks``; yield ``(goal, method, json_line)`` as results finish.

    With ``workers > 1`` a process pool runs them; when the caller stops (an
    interrupt, an error) the pool's workers are terminated at once.
    """
    if workers <= 1:
        worker = Worker(spec)
        for goal, method in tasks:
            yield goal, method, worker.run(goal, method)
        return
    if not tasks:
        return
    context = multiprocessing.get_context("spawn")
    pool = context.Pool(workers, initializer=_init_worker, initargs=(spec,))
    try:
        for results in pool.imap_unordered(_run_in_worker, _chunks(tasks, max(1, chunk))):
            yield from results
        pool.close()
    finally:
        pool.terminate()
        pool.join()


def _progress(total: int, enabled: bool | None):

    disable = not sys.stderr.isatty() if enabled is None else not enabled
    return tqdm(total=total, unit="result", desc="batch", file=sys.stderr, disable=disable, smoothing=0.05)


def run_batch(
    spec: BatchSpec,
    goals: list[int],
    output: str | Path | None,
    resume: bool = False,
    workers: int = 1,
    progress: bool | None = None,
    sync: bool = True,
    executor: Callable[[BatchSpec, list[tuple[int, str]]], Iterable[tuple[int, str, str]]] | None = None,
    chunk: int = 1,
) -> BatchReport:
    """Solve every (goal, method) pair of ``goals`` x ``spec.methods``; append results to ``output``.

    Without ``resume`` an existing, non-empty ``output`` is an error (nothing
    is overwritten).  ``executor`` replaces the local runner (the Dask path).
    """
    for name in spec.methods:
        methods_mod.get(name)  # unknown names fail before any work
    reason = ""
    if spec.grounding == "auto":
        grounding, reason = choose_grounding(spec.problem, goals)
        spec = replace(spec, grounding=grounding)
    elif spec.grounding not in GROUNDINGS:
        raise InputError(f"unknown grounding {spec.grounding!r} (have {', '.join(GROUNDING_CHOICES)})")
    previous: list[dict] = []
    out = None
    if output is not None:
        path = Path(output)
        if path.is_dir():
            raise InputError("results file is a directory", str(path))
        if path.exists() and path.stat().st_size > 0 and not resume:
            raise InputError("results file exists; use --resume to continue it or choose another --output", str(path))
        out = ResultFile(output, sync)  # locked from here on
    try:
        if out is not None:
            config = configuration(spec)
            if resume:
                old = read_header(out.path)
                if old is not None:
                    differ = config_differences(old, config)
                    if differ:
                        raise InputError(
                            "results file was made with another configuration (differs in: "
                            f"{', '.join(differ)}); choose another --output or the same options",
                            str(out.path),
                        )
                previous = read_results(out.path, repair=True)
            if out.path.stat().st_size == 0:
                out.append(header_line(config))
        todo, skipped = pending_tasks(spec.problem, goals, spec.methods, previous)
        t0 = time.perf_counter()
        new_records: list[dict] = []
        bar = _progress(len(todo), progress)
        results: Iterable[tuple[int, str, str]] = ()
        try:
            if executor is not None:
                results = executor(spec, todo)
            else:
                results = execute(spec, todo, workers, chunk)
            for _goal, _method, line in results:
                if out is not None:
                    out.append(line)
                new_records.append(json.loads(line))
                bar.update(1)
        finally:
            close = getattr(results, "close", None)
            if close is not None:
                close()  # stops a pool at once
            bar.close()
    finally:
        if out is not None:
            out.close()
    elapsed = time.perf_counter() - t0
    wanted = {(g, m) for g in goals for m in spec.methods}
    kept = [r for r in previous if (_goal_key(spec.problem, r), r.get("requested_method", r.get("method"))) in wanted]
    return BatchReport(
        len(new_records),
        skipped,
        elapsed,
        kept + new_records,
        workers,
        str(output) if output else None,
        spec.grounding,
        reason,
    )


# --- the summary ---


def summarize(records: list[dict]) -> list[dict]:
    """One row per method: counts per status and tree-size statistics (units of trees found)."""
    by_method: dict[str, list[dict]] = {}
    for r in records:
        by_method.setdefault(r.get("requested_method", r.get("method", "?")), []).append(r)
    rows = []
    for method, recs in by_method.items():
        statuses: dict[str, int] = {}
        for r in recs:
            statuses[r.get("status", "?")] = statuses.get(r.get("status", "?"), 0) + 1
        sizes = [len(r.get("units", [])) for r in recs if r.get("status") in ("optimal", "ranked", "feasible", "found")]
        valid = [r.get("valid") for r in recs if r.get("status") in ("optimal", "ranked", "feasible", "found")]
        times = [float(r.get("time_s", 0.0)) for r in recs]
        rows.append(
            {
                "method": method,
                "results": len(recs),
                "statuses": dict(sorted(statuses.items())),
                "trees": len(sizes),
                # trees the independent validator accepts (None: records written without "valid")
                "valid": sum(1 for v in valid if v) if all(v is not None for v in valid) else None,
                "units_min": min(sizes) if sizes else None,
                "units_median": statistics.median(sizes) if sizes else None,
                "units_mean": round(statistics.fmean(sizes), 2) if sizes else None,
                "units_max": max(sizes) if sizes else None,
                "time_total_s": round(sum(times), 3),
                "time_median_ms": round(1000 * statistics.median(times), 3) if times else None,
            }
        )
    return rows
