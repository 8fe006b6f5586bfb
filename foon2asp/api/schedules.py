"""Schedules through the library: a goal's task tree on robot arms and people, and schedule files checked.

:meth:`foon2asp.api.KnowledgeBase.schedule` and :meth:`foon2asp.api.Tree.schedule` return a
:class:`Schedule` (``foon2asp schedule``); :func:`check_schedule_file` judges a file of
``schedule --format json`` with :mod:`foon2asp.schedule.check` (``foon2asp check``).  The
agents, durations, capabilities and resources are one :class:`~foon2asp.schedule.ScheduleSpec`
(:func:`make_spec`: a spec, or the ``--agents`` text and the three files).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Unpack

from foon2asp import report
from foon2asp.api.options import Options, Settings
from foon2asp.asp.options import AspOptions
from foon2asp.batch.schedules import schedules_path
from foon2asp.errors import InputError
from foon2asp.foon import safejson
from foon2asp.foon.model import FoonObject
from foon2asp.foon.problem import Problem
from foon2asp.report import gantt
from foon2asp.schedule import DEFAULT_ENCODING, ScheduleResult, ScheduleSpec, parse_agents
from foon2asp.schedule import check as check_mod
from foon2asp.schedule import schedule as schedule_tree
from foon2asp.schedule.encode import ENCODINGS
from foon2asp.schedule.result import seconds, seconds_text
from foon2asp.tree.tasktree import TaskTree

if TYPE_CHECKING:
    from foon2asp.api.kb import GoalLike, KnowledgeBase
    from foon2asp.api.results import Tree

#: the statuses of a schedule (``optimal``: makespan proven minimal; ``feasible``: a time limit ended the search)
SCHEDULE_STATUSES = ("optimal", "feasible", "unschedulable", "unreachable", "unknown")

#: the schedule encodings (:mod:`foon2asp.schedule.encode`) and the default one
SCHEDULE_ENCODINGS = ENCODINGS
DEFAULT_SCHEDULE_ENCODING = DEFAULT_ENCODING

__all__ = [
    "schedules_path",
    "DEFAULT_SCHEDULE_ENCODING",
    "SCHEDULE_ENCODINGS",
    "SCHEDULE_STATUSES",
    "ScheduleSpec",
    "parse_agents",
]


def make_spec(
    spec: ScheduleSpec | None = None,
    agents: str | Mapping[str, int] | None = None,
    durations: str | Path | None = None,
    capabilities: str | Path | None = None,
    resources: str | Path | None = None,
) -> ScheduleSpec:
    """``spec``, or the spec of ``agents`` (``"arm=2,human=1"`` or ``{"arm": 2, "human": 1}``; default
    ``robot=1``) and the durations, capabilities and resources files (each optional)."""
    files = (durations, capabilities, resources)
    if spec is not None:
        if agents is not None or any(f is not None for f in files):
            raise InputError("give a ScheduleSpec or agents/durations/capabilities/resources, not both")
        return spec
    if isinstance(agents, Mapping):
        agents = ",".join(f"{kind}={n}" for kind, n in agents.items())
    return ScheduleSpec.from_files(agents, *files)


class Schedule:
    """The schedule of one goal's tree: who does which unit when, the makespan, its bounds and baseline."""

    def __init__(self, kb: KnowledgeBase, raw: ScheduleResult, spec: ScheduleSpec) -> None:
        self.kb = kb
        #: the internal record (unit ids, times in milliseconds)
        self.raw = raw
        self.spec = spec

    @property
    def status(self) -> str:
        """``optimal`` | ``feasible`` | ``unschedulable`` | ``unreachable`` | ``unknown`` (no tree in time)."""
        return self.raw.status

    @property
    def makespan(self) -> float | None:
        """Seconds (None without a schedule)."""
        return seconds(self.raw.makespan)

    @property
    def agents(self) -> list[str]:
        return list(self.raw.agents)

    @property
    def entries(self) -> list[dict]:
        """``{"unit", "agent", "start", "end"}`` per unit, by start time (the JSON's ``schedule``)."""
        return self.to_dict()["schedule"]

    @property
    def tree(self) -> Tree:
        """The scheduled tree (``joint``: the one chosen with the schedule)."""
        from foon2asp.api.results import Tree

        return Tree(self.kb, self.raw.tree)

    @property
    def fixed(self) -> Schedule | None:
        """Joint scheduling: the schedule of the given tree alone (None otherwise)."""
        return None if self.raw.fixed is None else Schedule(self.kb, self.raw.fixed, self.spec)

    def check(self) -> str | None:
        """The first violation the independent checker finds (None: a valid schedule)."""
        return check_mod.check_schedule(self.raw.problem, self.to_dict(), self.spec)

    def to_dict(self) -> dict:
        """Exactly one element of ``schedule --format json``."""
        return self.raw.to_dict()

    def to_text(self) -> str:
        """The headline (status, makespan, baseline, bounds) and one timeline per agent."""
        return self.raw.to_text()

    def render(self, fmt: str) -> str | bytes:
        """The Gantt chart in a format of :mod:`foon2asp.report` kind ``schedule`` (svg, png, pdf, dot, html)."""
        if report.get("schedule", fmt).binary:
            return report.render_bytes("schedule", fmt, [self.to_dict()])
        return report.render("schedule", fmt, [self.to_dict()])

    def draw(self, path: str | Path) -> Path:
        """Draw the Gantt chart into ``path``; the format follows the extension (.svg, .png, .pdf, .dot)."""
        return gantt.draw_gantt(self.to_dict(), path)

    def _repr_svg_(self) -> str:
        """The Gantt chart, for Jupyter."""
        return gantt.gantt_svg(self.to_dict())

    def __repr__(self) -> str:
        return f"<Schedule {self.tree.goal} {self.status} makespan={seconds_text(self.raw.makespan)} s>"


def schedules_json(schedules: list[Schedule]) -> str:
    """``schedule --format json``: a JSON list, one schedule per line."""
    if not schedules:
        return "[]\n"
    return "[\n" + ",\n".join(json.dumps(s.to_dict()) for s in schedules) + "\n]\n"


def schedule_raw(
    kb: KnowledgeBase,
    tree: TaskTree,
    spec: ScheduleSpec,
    solver: AspOptions,
    joint: bool = False,
    encoding: str = DEFAULT_ENCODING,
    time_limit: float | None = None,
    progress: Callable[[dict], None] | None = None,
) -> Schedule:
    """:func:`foon2asp.schedule.schedule` of one tree, as a :class:`Schedule`; with substitutes,
    on the problem the tree is judged on (what a substitute stands in for is in the kitchen).
    ``progress``: as :func:`foon2asp.schedule.schedule` takes it."""
    problem = kb.judging_problem(solver, tree.meal)
    found = schedule_tree(problem, tree, spec, solver, joint, time_limit, encoding, progress=progress)
    return Schedule(kb, found, spec)


class Scheduling:
    """The part of :class:`foon2asp.api.KnowledgeBase` that schedules trees and checks schedule files."""

    if TYPE_CHECKING:  # what the knowledge base gives its parts

        def options(self, options: Options | None = None, **settings: Unpack[Settings]) -> AspOptions: ...

        def goal_ids(self, goals: Any) -> list[int]: ...

        def solve_iter(self, goal_ids: Any, method: str = "asp", options: Any = None) -> Iterator[Tree]: ...

        def judging_problem(self, solver: Any, goals: Any = ()) -> Problem: ...

    def schedule(
        self,
        goals: GoalLike | Sequence[GoalLike] | None = None,
        spec: ScheduleSpec | None = None,
        *,
        agents: str | dict[str, int] | None = None,
        durations: str | Path | None = None,
        capabilities: str | Path | None = None,
        resources: str | Path | None = None,
        joint: bool = False,
        together: bool = False,
        encoding: str = DEFAULT_ENCODING,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> Schedule | list[Schedule]:
        """The schedule with the proven-minimal makespan of each goal's best tree (by ``objective``;
        ``joint``: tree and schedule chosen together) on ``spec``'s agents, or on ``agents``
        (``"arm=2,human=1"``, default one robot) with the ``durations``, ``capabilities`` and
        ``resources`` files.  One goal gives a :class:`Schedule`, several a list (as :meth:`solve`);
        ``together=True``: one schedule of one tree that makes every goal (a meal)."""
        solver = self.options(options, **settings)
        chosen = make_spec(spec, agents, durations, capabilities, resources)
        ids = self.goal_ids(goals)
        jobs: list[int | tuple[int, ...]] = [tuple(dict.fromkeys(ids))] if together else list(ids)
        found = list(self.schedule_iter(jobs, chosen, solver, joint=joint, encoding=encoding))
        single = together or (isinstance(goals, str | int | FoonObject) and goals not in ("all", "all-objects"))
        return found[0] if single else found

    def schedule_iter(
        self,
        goal_ids: Sequence[int | tuple[int, ...]],
        spec: ScheduleSpec | None = None,
        options: Options | AspOptions | None = None,
        *,
        joint: bool = False,
        encoding: str = DEFAULT_ENCODING,
        progress: Callable[[dict], None] | None = None,
    ) -> Iterator[Schedule]:
        """:meth:`schedule` goal after goal (the path ``foon2asp schedule`` takes); an element
        that is a tuple of ids is a meal: one tree, and its schedule, for all of them.
        ``progress``: called as each goal's schedules improve, with what
        :func:`foon2asp.schedule.schedule` reports and ``goal``, the goal's label."""
        solver = options if isinstance(options, AspOptions) else self.options(options)
        chosen = spec or ScheduleSpec()
        for tree in self.solve_iter(goal_ids, "asp", solver):
            report = None
            if progress is not None:
                label = " + ".join(g.label for g in tree.goals)

                def report(info: dict, label: str = label) -> None:
                    progress({**info, "goal": label})

            yield schedule_raw(tree.kb, tree.raw, chosen, solver, joint, encoding, progress=report)

    def check_schedules(
        self, path: str | Path, spec: ScheduleSpec | None = None, options: Options | None = None
    ) -> list[ScheduleVerdict]:
        """Judge each schedule of a ``schedule --format json`` file on ``spec``'s agents (default one
        robot, every unit 1 s): the first violation of precedence, one unit per agent at a time,
        capabilities, durations, resources or the tree's validity, per schedule; with the
        substitutes of ``options`` what they stand in for is in the kitchen."""
        return check_schedule_file(self, path, spec or ScheduleSpec(), options)


# ---------------------------------------------------------------- schedule files


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
        return {
            "file": self.path,
            "goal": self.goal,
            "status": self.status,
            "valid": self.valid,
            "problem": self.problem,
            "makespan": self.makespan,
        }

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
        _, doc = safejson.load(path, "schedule file")
    except InputError:
        return None
    items = doc if isinstance(doc, list) else [doc]
    if items and all(isinstance(r, dict) and "schedule" in r and "agents" in r for r in items):
        return items
    return None


def is_schedule_file(path: str | Path) -> bool:
    """Does ``path`` hold schedules (``schedule --format json``), rather than task trees?"""
    return _records(path) is not None


def _goal_label(record: dict) -> str:
    goals = record.get("goals") if "goals" in record else [record.get("goal")]
    return " + ".join(str(g.get("label", "?")) if isinstance(g, dict) else "?" for g in goals or [])


def _goal_ids(kb: Any, record: dict) -> list[int]:
    """The object ids of the goals a record names (those of the FOON)."""
    goals = record.get("goals") if "goals" in record else [record.get("goal")]
    ids = kb.problem.foon.object_ids
    out = []
    for g in goals if isinstance(goals, list) else []:
        if isinstance(g, dict) and isinstance(g.get("label"), str):
            obj = FoonObject.make(g["label"], g.get("states") or (), g.get("ingredients") or (), g.get("container"))
            if obj in ids:
                out.append(ids[obj])
    return out


def check_schedule_file(
    kb: Any, path: str | Path, spec: ScheduleSpec, options: Options | None = None
) -> list[ScheduleVerdict]:
    """Judge every schedule of a ``schedule --format json`` file against ``spec`` and the FOON of
    ``kb`` (with the substitutes of ``options``, as :meth:`KnowledgeBase.check` judges trees)."""
    records = _records(path)
    if records is None:
        raise InputError("not a schedule file (the JSON of 'schedule --format json')", str(path))
    out = []
    for r in records:
        status = str(r.get("status"))
        if status in ("unschedulable", "unreachable", "unknown"):
            out.append(ScheduleVerdict(_goal_label(r), None, None, str(path), status))
            continue
        found = check_mod.check_schedule(kb.judging_problem(options, _goal_ids(kb, r)), r, spec)
        made = r.get("makespan")
        number = made if isinstance(made, int | float) and not isinstance(made, bool) else None
        out.append(ScheduleVerdict(_goal_label(r), found, number, str(path), status))
    return out


def verdicts_json(verdicts: list[ScheduleVerdict]) -> str:
    return json.dumps([v.to_dict() for v in verdicts], indent=2) + "\n"
