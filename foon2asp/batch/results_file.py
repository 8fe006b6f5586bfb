"""A batch's results file (one JSON line per result, a header, resumable), the run that fills it
and the task trees its records hold (scheduled by ``batch --schedule``).

What survives a kill or a crash, and what ``--resume`` refuses: docs/batch.md, "The results file".
"""

from __future__ import annotations

import gc
import hashlib
import json
import os
import statistics
import sys
import time
from collections import Counter
from dataclasses import replace
from pathlib import Path

from tqdm import tqdm

try:
    import fcntl
except ModuleNotFoundError:  # pragma: no cover - not POSIX
    fcntl = None  # type: ignore[assignment]

from foon2asp import methods as methods_mod
from foon2asp.asp.facts import facts
from foon2asp.asp.interrupts import deferred_signals
from foon2asp.batch.pool import AUTO, BatchSpec, Execution, Executor, refuse_while_starting
from foon2asp.errors import InputError
from foon2asp.foon.foonjson import read_json
from foon2asp.foon.problem import Problem
from foon2asp.foon.reading import loads as safe_loads
from foon2asp.methods.parts import GROUNDING_CHOICES, GROUNDINGS, choose_grounding
from foon2asp.outcomes import BatchReport, record_object
from foon2asp.tree.tasktree import WITH_TREE, TaskTree, executable_order, measures


def goal_key(problem: Problem, record: dict) -> int | None:
    """The object id of the goal a result record names (None: not a goal of this FOON)."""
    obj = record_object(record.get("goal"))
    return None if obj is None else problem.foon.object_ids.get(obj)


def read_results(path: str | Path, repair: bool = False) -> list[dict]:
    """The records of a results file: a cut or damaged last line is dropped (and cut off the file
    with ``repair``), a bad line elsewhere is an :class:`InputError` naming file and line."""
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


def _digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def configuration(spec: BatchSpec) -> dict:
    """What produced a results file: the answers depend on these."""
    o = spec.options
    config = {
        "methods": list(spec.methods),
        "objective": list(o.objective),
        "constraints": [[name, _digest(text)] for name, text in o.programs],
        "encodings": [],  # kept for results files written before every encoding was shipped
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
        **({"gap": o.gap} if o.gap else {}),
        "input_sha256": hashlib.sha256(facts(spec.problem).encode("utf-8")).hexdigest(),
    }
    if o.motion_costs is not None:
        config["motion_costs"] = _digest(json.dumps(o.motion_costs, sort_keys=True))
    if o.substitutes:  # the substitutes and the kitchen items they may use (not all are in the facts)
        table = sorted([s.needed, s.used, s.cost] for s in o.substitutes)
        kitchen = sorted(obj.text for obj in spec.problem.kitchen_items)
        config["substitutes"] = _digest(json.dumps([table, kitchen]))
        config["max_substitutions"] = o.max_substitutions
    return config


def read_header(path: str | Path) -> dict | None:
    """The configuration recorded in the header line of a results file (None: no header)."""
    try:
        with open(path, "rb") as fh:
            value = json.loads(fh.readline().decode("utf-8"))
    except (OSError, ValueError, UnicodeDecodeError):
        return None
    config = value.get("config") if isinstance(value, dict) and HEADER_KEY in value else None
    return config if isinstance(config, dict) else None


#: with sync on, the longest time between two syncs of the results file while lines are written
SYNC_INTERVAL_S = 0.25


class ResultFile:
    """Append-only result lines, each written whole, synced to disk in groups (at most
    :data:`SYNC_INTERVAL_S` apart, and on close); an exclusive lock (``flock``) while open, so a
    second writer is refused."""

    def __init__(self, path: str | Path, sync: bool = True):
        self.path = Path(path)
        self.sync = sync
        self._synced = time.monotonic()
        self._dirty = False
        try:
            if not self.path.parent.exists():
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
        view = memoryview(line.encode("utf-8"))
        with deferred_signals():  # an interrupt waits until the line is whole
            while view:
                written = os.write(self.fd, view)
                view = view[written:]
            if self.sync:
                self._dirty = True
                if time.monotonic() - self._synced >= SYNC_INTERVAL_S:
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


def record_key(problem: Problem, record: dict) -> tuple[int | None, str | None]:
    """The (goal, method) pair a result record answers."""
    return goal_key(problem, record), record.get("requested_method", record.get("method"))


def pending_tasks(
    problem: Problem, goals: list[int], method_names: list[str], previous: list[dict]
) -> tuple[list[tuple[int, str]], int]:
    """The (goal, method) pairs not yet in ``previous``, and how many were skipped."""
    have = {record_key(problem, r) for r in previous}
    pairs = list(dict.fromkeys((g, m) for g in goals for m in method_names))
    todo = [pair for pair in pairs if pair not in have]
    return todo, len(pairs) - len(todo)


def open_results(output: str | Path, config: dict, resume: bool, sync: bool) -> tuple[ResultFile, list[dict]]:
    """The results file ``output`` opened and locked for a batch of configuration ``config``, and
    the records already in it (with ``resume``; without it a non-empty file is refused, with it
    another configuration)."""
    path = Path(output)
    if path.is_dir():
        raise InputError("results file is a directory", str(path))
    if path.exists() and path.stat().st_size > 0 and not resume:
        raise InputError("results file exists; use --resume to continue it or choose another --output", str(path))
    out = ResultFile(path, sync)  # locked from here on
    try:
        previous: list[dict] = []
        if resume:
            old = read_header(path) or config
            differ = [
                k for k in sorted(set(old) | set(config)) if k not in RESUMABLE_KEYS and old.get(k) != config.get(k)
            ]
            if differ:
                raise InputError(
                    "results file was made with another configuration (differs in: "
                    f"{', '.join(differ)}); choose another --output or the same options",
                    str(path),
                )
            previous = read_results(path, repair=True)
        if path.stat().st_size == 0:
            out.append(json.dumps({HEADER_KEY: HEADER_VERSION, "config": config}, ensure_ascii=False) + "\n")
    except BaseException:
        out.close()
        raise
    return out, previous


def summarize(records: list[dict]) -> list[dict]:
    """One row per method: counts per status and tree-size statistics (units of trees found)."""
    by_method: dict[str, list[dict]] = {}
    for r in records:
        by_method.setdefault(r.get("requested_method", r.get("method", "?")), []).append(r)
    rows = []
    for method, recs in by_method.items():
        statuses = Counter(r.get("status", "?") for r in recs)
        trees = [r for r in recs if r.get("status") in WITH_TREE]
        sizes = [len(r.get("units", [])) for r in trees]
        valid = [r.get("valid") for r in trees]
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


def run_batch(
    spec: BatchSpec,
    goals: list[int],
    output: str | Path | None,
    resume: bool = False,
    workers: int = 1,
    progress: bool | None = None,
    sync: bool = True,
    executor: Executor | None = None,
) -> BatchReport:
    """Solve every (goal, method) pair of ``goals`` x ``spec.methods`` and append the results to
    ``output`` (an existing, non-empty one only with ``resume``); ``workers`` as
    :class:`~foon2asp.batch.pool.Execution` takes them, ``executor`` replaces the pool (Dask)."""
    refuse_while_starting()  # a worker running the main script again must not start its batch
    for name in spec.methods:
        methods_mod.get(name)  # unknown names fail before any work
    reason = ""
    if spec.options.substitutes:  # the goal runner grounds the whole FOON with substitutes
        spec = replace(spec, grounding="whole")
        reason = "with substitutes, a goal's part would leave out the kitchen items that stand in"
    elif spec.grounding == "auto":
        grounding, reason = choose_grounding(spec.problem, goals)
        spec = replace(spec, grounding=grounding)
    elif spec.grounding not in GROUNDINGS:
        raise InputError(f"unknown grounding {spec.grounding!r} (have {', '.join(GROUNDING_CHOICES)})")
    out, previous = (None, []) if output is None else open_results(output, configuration(spec), resume, sync)
    try:
        todo, skipped = pending_tasks(spec.problem, goals, spec.methods, previous)
        t0 = time.perf_counter()
        lines: list[str] = []
        disable = not sys.stderr.isatty() if progress is None else not progress
        bar = tqdm(total=len(todo), unit="result", desc="batch", file=sys.stderr, disable=disable, smoothing=0.05)
        results = executor(spec, todo) if executor is not None else Execution(spec, todo, workers)
        try:
            for line in results:
                if out is not None:
                    out.append(line)
                lines.append(line)  # parsed at the end: records kept meanwhile slow the collector down
                bar.update(1)
        finally:
            results.close()  # stops a pool at once
            bar.close()
        # the processes that ran tasks (the pool's, once it started)
        used = getattr(results, "workers", 1 if workers == AUTO else workers)
    finally:
        if out is not None:
            out.close()
    elapsed = time.perf_counter() - t0
    new_records = parse_records(lines)
    wanted = {(g, m) for g in goals for m in spec.methods}
    kept = [r for r in previous if record_key(spec.problem, r) in wanted]
    output = str(output) if output else None
    return BatchReport(len(new_records), skipped, elapsed, kept + new_records, used, output, spec.grounding, reason)


def parse_records(lines: list[str]) -> list[dict]:
    """The records of result lines, parsed with the cycle collector paused (they hold no cycles)."""
    was_on = gc.isenabled()
    gc.disable()
    try:
        return [json.loads(line) for line in lines]
    finally:
        if was_on:
            gc.enable()


def schedules_path(output: str | Path) -> Path:
    """Where the schedules of the results file ``output`` go: beside it, ``.schedules.json``."""
    return Path(output).with_suffix(".schedules.json")


def record_tree(problem: Problem, record: dict) -> TaskTree | None:
    """The task tree of a result record, its units found in the FOON by motion, inputs and
    outputs (None: its goal is not an object of this FOON; no tree: status unreachable or
    unknown)."""
    goal = goal_key(problem, record)
    if goal is None:
        return None
    status = str(record.get("status", "unknown"))
    if status not in WITH_TREE or not record.get("units"):
        status = "unreachable" if status in ("unreachable", "not-found") else "unknown"
        return TaskTree(goal=goal, method=str(record.get("method", "?")), status=status)
    units = []
    for unit in read_json(record["units"], "results").units:
        uid = problem.foon.unit_id(unit)
        if uid is None:
            raise InputError(f"a unit ({unit.motion}) of the tree for {problem.objects[goal]} is not in the FOON")
        units.append(uid)
    return TaskTree(
        goal=goal,
        method=str(record.get("method", "?")),
        status="optimal" if status == "ranked" else status,
        units=executable_order(problem, units),
        cost=measures(problem, goal, units),
    )


def record_trees(problem: Problem, records: list[dict], method: str | None = None) -> list[TaskTree]:
    """The task tree of each goal of ``records``, from its first record of ``method`` (default: the
    first method in them)."""
    if method is None:
        method = next((str(r.get("requested_method", r.get("method"))) for r in records), None)
    out: dict[int, TaskTree] = {}
    for r in records:
        if str(r.get("requested_method", r.get("method"))) != method or goal_key(problem, r) in out:
            continue
        tree = record_tree(problem, r)
        if tree is not None:
            out[tree.goal] = tree
    return list(out.values())
