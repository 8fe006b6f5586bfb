"""Schedules of a batch's trees (``batch --schedule``): one schedule per goal, written as one JSON list."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

from foon2asp.analysis.check import unit_index
from foon2asp.asp.options import AspOptions
from foon2asp.batch.results import goal_key
from foon2asp.errors import InputError
from foon2asp.foon.foonjson import parse_json
from foon2asp.foon.problem import Problem
from foon2asp.schedule import DEFAULT_ENCODING, ScheduleResult, ScheduleSpec, schedule
from foon2asp.tree.results import WITH_TREE
from foon2asp.tree.tasktree import TaskTree, executable_order, measures


def schedules_path(output: str | Path) -> Path:
    """Where the schedules of the results file ``output`` go: beside it, ``.schedules.json``."""
    return Path(output).with_suffix(".schedules.json")


def record_tree(problem: Problem, record: dict) -> TaskTree | None:
    """The task tree of a result record, its units found in the FOON by motion, inputs and
    outputs (None: its goal is not an object of this FOON; no tree: status unreachable or unknown)."""
    goal = goal_key(problem, record)
    if goal is None:
        return None
    status = str(record.get("status", "unknown"))
    if status not in WITH_TREE or not record.get("units"):
        status = "unreachable" if status in ("unreachable", "not-found") else "unknown"
        return TaskTree(goal=goal, method=str(record.get("method", "?")), status=status)
    ids = unit_index(problem)
    units = []
    for unit in parse_json(json.dumps(record["units"]), "results").units:
        uid = ids.get(unit.key())
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


def schedule_records(
    problem: Problem,
    records: list[dict],
    spec: ScheduleSpec,
    options: AspOptions,
    method: str | None = None,
    joint: bool = False,
    encoding: str = DEFAULT_ENCODING,
    view: Callable[[tuple[int, ...]], Problem] | None = None,
) -> list[ScheduleResult]:
    """One schedule per goal of ``records`` (those of ``method``; default: the first method in
    them); ``view``: the problem a tree of these goals is scheduled on (with substitutes)."""
    if method is None:
        method = next((str(r.get("requested_method", r.get("method"))) for r in records), None)
    out: dict[int, ScheduleResult] = {}
    for r in records:
        if str(r.get("requested_method", r.get("method"))) != method:
            continue
        tree = record_tree(problem, r)
        if tree is None or tree.goal in out:
            continue
        on = problem if view is None else view(tree.meal)
        out[tree.goal] = schedule(on, tree, spec, options, joint, options.time_limit, encoding)
    return list(out.values())
