"""Batch solving: goals x methods, one JSON line per result, resumable.

Every finished result is appended to the output file at once as one complete
JSON line (the ``solve --format json`` shape of one tree plus
``"requested_method"``, the registry name it was asked for): the line is built
in full, written with one ``os.write`` on an append-only descriptor and
``fsync``-ed, so a batch killed at any moment leaves only whole lines (at
worst a last line cut short by a crash of the machine, which ``--resume``
drops).  ``--resume`` skips every (goal, method) pair already in the file.

Runners are built once per process (:class:`foon2asp.fastpath.BatchRunner`);
``workers > 1`` runs goals in a process pool whose initializer builds each
worker's runners once.  :mod:`foon2asp.dask_runner` runs the same tasks on a
Dask cluster.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import statistics
import sys
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from pathlib import Path

from tqdm import tqdm

from foon2asp import methods as methods_mod
from foon2asp.analysis.compare import judge
from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject
from foon2asp.foon.problem import Problem
from foon2asp.methods.planner import BatchRunner, Parts
from foon2asp.tree.serialize import tree_json


@dataclass
class BatchSpec:
    """Everything a process needs to build its runners (picklable)."""

    problem: Problem
    methods: list[str]
    options: AspOptions = field(default_factory=AspOptions)
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


def _init_worker(spec: BatchSpec) -> None:
    global _WORKER
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
            record = json.loads(raw.decode("utf-8")) if raw.strip() else None
            if record is not None and not isinstance(record, dict):
                raise ValueError("not an object")
        except (ValueError, UnicodeDecodeError):
            if lineno == len(complete) and not pieces[-1]:
                break  # a damaged last line: dropped like a cut one
            raise InputError("not a JSON result line (remove or fix it to resume)", str(path), lineno) from None
        if record is not None:
            records.append(record)
        good_end += len(raw) + 1
    if repair and good_end < len(data):
        with open(path, "r+b") as fh:
            fh.truncate(good_end)
            fh.flush()
            os.fsync(fh.fileno())
    return records


class ResultFile:
    """Append-only result lines, each written whole and synced to disk."""

    def __init__(self, path: str | Path, sync: bool = True):
        self.path = Path(path)
        self.sync = sync
        if self.path.parent and not self.path.parent.exists():
            self.path.parent.mkdir(parents=True, exist_ok=True)
        self.fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)

    def append(self, line: str) -> None:
        data = line.encode("utf-8")
        view = memoryview(data)
        while view:
            written = os.write(self.fd, view)
            view = view[written:]
        if self.sync:
            os.fsync(self.fd)

    def close(self) -> None:
        os.close(self.fd)

    def __enter__(self) -> ResultFile:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


# --- running ---


@dataclass
class BatchReport:
    """What a batch did: counts, times and all records of the requested pairs."""

    done: int
    skipped: int
    elapsed_s: float
    records: list[dict]
    workers: int
    output: str | None


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
    """Run ``tasks``; yield ``(goal, method, json_line)`` as results finish."""
    if workers <= 1:
        worker = Worker(spec)
        for goal, method in tasks:
            yield goal, method, worker.run(goal, method)
        return

    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(workers, mp_context=context, initializer=_init_worker, initargs=(spec,)) as pool:
        queue = iter(_chunks(tasks, max(1, chunk)))
        running = set()
        # keep a bounded window of chunks in flight so an interrupt loses little
        for part in queue:
            running.add(pool.submit(_run_in_worker, part))
            if len(running) >= 4 * workers:
                break
        while running:
            finished, running = wait(running, return_when=FIRST_COMPLETED)
            for future in finished:
                yield from future.result()
                nxt = next(queue, None)
                if nxt is not None:
                    running.add(pool.submit(_run_in_worker, nxt))


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
    previous: list[dict] = []
    if output is not None:
        path = Path(output)
        if path.exists() and path.stat().st_size > 0 and not resume:
            raise InputError("results file exists; use --resume to continue it or choose another --output", str(path))
        if resume:
            previous = read_results(path, repair=True)
    todo, skipped = pending_tasks(spec.problem, goals, spec.methods, previous)
    t0 = time.perf_counter()
    new_records: list[dict] = []
    out = ResultFile(output, sync) if output is not None else None
    bar = _progress(len(todo), progress)
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
        bar.close()
        if out is not None:
            out.close()
    elapsed = time.perf_counter() - t0
    wanted = {(g, m) for g in goals for m in spec.methods}
    kept = [r for r in previous if (_goal_key(spec.problem, r), r.get("requested_method", r.get("method"))) in wanted]
    return BatchReport(len(new_records), skipped, elapsed, kept + new_records, workers, str(output) if output else None)


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
