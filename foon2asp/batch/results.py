"""The results file of a batch: one JSON line per result, a header, resumable.

:class:`ResultFile` appends each finished result as one whole line with one ``os.write``
(signals wait until it is written), syncs in groups (at most :data:`SYNC_INTERVAL_S`
apart) and holds an exclusive lock while open; the first line is a header with the
:func:`configuration` that produced the file, and ``--resume`` with another one is refused
(:func:`config_differences`).  :func:`read_results` drops a last line cut short,
:func:`pending_tasks` says which (goal, method) pairs are still to do and :func:`summarize`
counts per method.  What survives a kill or a crash: docs/batch.md, "The results file".
"""

from __future__ import annotations

import hashlib
import json
import os
import statistics
import time
from pathlib import Path

try:
    import fcntl
except ModuleNotFoundError:  # pragma: no cover - not POSIX
    fcntl = None  # type: ignore[assignment]

from foon2asp.asp.facts import facts
from foon2asp.asp.interrupts import deferred_signals
from foon2asp.batch.pool import BatchSpec
from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject
from foon2asp.foon.problem import Problem
from foon2asp.foon.reading import loads as safe_loads


def goal_key(problem: Problem, record: dict) -> int | None:
    """The object id of the goal a result record names (None: not a goal of this FOON)."""
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


#: statuses of records with a tree
WITH_TREE = ("optimal", "ranked", "feasible", "found")

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
        **({"gap": o.gap} if o.gap else {}),
        "input_sha256": hashlib.sha256(facts(spec.problem).encode("utf-8")).hexdigest(),
        **(
            {"motion_costs": hashlib.sha256(json.dumps(o.motion_costs, sort_keys=True).encode()).hexdigest()[:16]}
            if o.motion_costs is not None
            else {}
        ),
        **(_substitutes_config(spec) if o.substitutes else {}),
    }


def _substitutes_config(spec: BatchSpec) -> dict:
    """The substitutes and the kitchen items they may use (not all are in the facts), hashed."""
    o = spec.options
    table = sorted([s.needed, s.used, s.cost] for s in o.substitutes)
    kitchen = sorted(obj.text for obj in spec.problem.kitchen_items)
    digest = hashlib.sha256(json.dumps([table, kitchen]).encode("utf-8")).hexdigest()[:16]
    return {"substitutes": digest, "max_substitutions": o.max_substitutions}


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


def pending_tasks(
    problem: Problem, goals: list[int], method_names: list[str], previous: list[dict]
) -> tuple[list[tuple[int, str]], int]:
    """The (goal, method) pairs not yet in ``previous``, and how many were skipped."""
    have = set()
    for record in previous:
        g = goal_key(problem, record)
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
