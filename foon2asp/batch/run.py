"""Batch solving: goals x methods, one JSON line per result, resumable.

The results file is :mod:`foon2asp.batch.results`'s, the worker pool :mod:`foon2asp.batch.pool`'s.
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Callable, Iterable
from dataclasses import replace
from pathlib import Path

from tqdm import tqdm

from foon2asp import methods as methods_mod
from foon2asp.batch.pool import AUTO, BatchSpec, Execution, refuse_while_starting
from foon2asp.batch.results import configuration, open_results, pending_tasks, record_key
from foon2asp.errors import InputError
from foon2asp.methods.parts import GROUNDING_CHOICES, GROUNDINGS, choose_grounding
from foon2asp.tree.results import BatchReport


def run_batch(
    spec: BatchSpec,
    goals: list[int],
    output: str | Path | None,
    resume: bool = False,
    workers: int = 1,
    progress: bool | None = None,
    sync: bool = True,
    executor: Callable[[BatchSpec, list[tuple[int, str]]], Iterable[tuple[int, str, str]]] | None = None,
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
        new_records: list[dict] = []
        disable = not sys.stderr.isatty() if progress is None else not progress
        bar = tqdm(total=len(todo), unit="result", desc="batch", file=sys.stderr, disable=disable, smoothing=0.05)
        results: Iterable[tuple[int, str, str]] = ()
        used = 1 if workers == AUTO else workers  # the processes that ran tasks (the pool's, once it started)
        try:
            results = executor(spec, todo) if executor is not None else Execution(spec, todo, workers)
            for _goal, _method, line in results:
                if out is not None:
                    out.append(line)
                new_records.append(json.loads(line))
                bar.update(1)
            used = getattr(results, "workers", used)
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
    kept = [r for r in previous if record_key(spec.problem, r) in wanted]
    output = str(output) if output else None
    return BatchReport(len(new_records), skipped, elapsed, kept + new_records, used, output, spec.grounding, reason)
