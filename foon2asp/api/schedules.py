"""Schedule files (``schedule --format json``): told from tree files, and each schedule in them checked."""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from foon2asp.errors import InputError
from foon2asp.foon import reading
from foon2asp.foon.problem import Problem
from foon2asp.outcomes import record_object
from foon2asp.schedule import ScheduleSpec
from foon2asp.schedule import checker as check_mod


@dataclass
class ScheduleVerdict:
    """What the checker says about one schedule of a file."""

    #: the goal's label (several joined by " + " for a meal)
    goal: str
    #: the first violation in words; None: valid (or no schedule to judge)
    problem: str | None
    makespan: float | None
    path: str
    #: the record's status: ``unschedulable``, ``unreachable`` and ``unknown`` hold no schedule to judge
    status: str = "optimal"

    @property
    def valid(self) -> bool:
        return self.problem is None

    def to_dict(self) -> dict:
        return {"file": self.path} | {k: getattr(self, k) for k in ("goal", "status", "valid", "problem", "makespan")}

    def to_text(self) -> str:
        if self.problem is not None:
            return f"{self.path}: {self.goal}: INVALID schedule: {self.problem}\n"
        if self.makespan is None:
            return f"{self.path}: {self.goal}: no schedule to check ({self.status})\n"
        return f"{self.path}: {self.goal}: valid schedule ({self.status}), makespan {self.makespan:g} s\n"


def _records(path: str | Path) -> list | None:
    """The schedule records of a JSON file (a list of them or one), None when it holds no schedules."""
    if Path(path).suffix.lower() != ".json" or not Path(path).is_file():
        return None
    try:
        _, doc = reading.load(path, "schedule")
    except InputError:
        return None
    items = doc if isinstance(doc, list) else [doc]
    if items and all(isinstance(r, dict) and "schedule" in r and "agents" in r for r in items):
        return items
    return None


def is_schedule_file(path: str | Path) -> bool:
    """Does ``path`` hold schedules (``schedule --format json``), rather than task trees?"""
    return _records(path) is not None


def _record_goals(problem: Problem, record: dict) -> tuple[str, list[int]]:
    """The labels of the goals a record names (joined by " + ") and the ids of those in the FOON."""
    goals = record.get("goals") if "goals" in record else [record.get("goal")]
    goals = goals if isinstance(goals, list) else []
    label = " + ".join(str(g.get("label", "?")) if isinstance(g, dict) else "?" for g in goals)
    ids = problem.foon.object_ids
    return label, [ids[obj] for obj in map(record_object, goals) if obj is not None and obj in ids]


def check_schedule_file(
    problem: Problem, view: Callable[[list[int]], Problem], path: str | Path, spec: ScheduleSpec
) -> list[ScheduleVerdict]:
    """Judge every schedule of a ``schedule --format json`` file against ``spec`` and the FOON of
    ``problem``; ``view``: the problem a record's goals are judged on (with substitutes, as
    :meth:`foon2asp.api.KnowledgeBase.check` judges trees)."""
    records = _records(path)
    if records is None:
        raise InputError("not a schedule file (the JSON of 'schedule --format json')", str(path))
    out = []
    for r in records:
        status = str(r.get("status"))
        label, goals = _record_goals(problem, r)
        if status in ("unschedulable", "unreachable", "unknown"):
            out.append(ScheduleVerdict(label, None, None, str(path), status))
            continue
        made = r.get("makespan")
        number = made if isinstance(made, int | float) and not isinstance(made, bool) else None
        out.append(ScheduleVerdict(label, check_mod.check_schedule(view(goals), r, spec), number, str(path), status))
    return out


def verdicts_json(verdicts: list[ScheduleVerdict]) -> str:
    return json.dumps([v.to_dict() for v in verdicts], indent=2) + "\n"
