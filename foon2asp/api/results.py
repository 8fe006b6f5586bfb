"""The answers of :class:`foon2asp.api.KnowledgeBase`: trees and their schedules, check reports,
comparisons, missing items and reachability; each renders itself in the formats of :mod:`foon2asp.report`."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Generic, Protocol, TypeVar, Unpack, cast

from foon2asp import report
from foon2asp.analysis import compare as compare_mod
from foon2asp.api.options import Options, Settings
from foon2asp.api.schedules import make_spec
from foon2asp.asp.multishot.driver import alternatives
from foon2asp.asp.options import AspOptions
from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.problem import Problem
from foon2asp.report import draw, gantt
from foon2asp.schedule import DEFAULT_ENCODING, ScheduleResult, ScheduleSpec
from foon2asp.schedule import check as schedule_check
from foon2asp.schedule import schedule as schedule_tree
from foon2asp.schedule.result import seconds, seconds_text
from foon2asp.tree.results import MissingResult, Report, Row
from foon2asp.tree.serialize import tree_foon, tree_json, tree_text
from foon2asp.tree.tasktree import TaskTree

T = TypeVar("T")


class Source(Protocol):
    """What an answer asks of the knowledge base that gave it (:class:`foon2asp.api.KnowledgeBase`)."""

    problem: Problem

    def options(self, options: Options | None = None, **settings: Unpack[Settings]) -> AspOptions: ...

    def solving_problem(self, solver: AspOptions) -> Problem: ...

    def judging_problem(self, solver: AspOptions | Options | None, goals: Iterable[int] = ()) -> Problem: ...


class Raw(Generic[T]):
    """An answer's attribute that is the attribute ``name`` (default: the same name) of its ``raw`` record."""

    def __init__(self, doc: str = "", name: str = "") -> None:
        self.__doc__, self.name = doc, name

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = self.name or name

    def __get__(self, answer: Any, owner: type | None = None) -> T:
        return cast(T, self) if answer is None else getattr(answer.raw, self.name)

    def __set__(self, answer: Any, value: Any) -> None:
        raise AttributeError(f"{self.name!r} is read-only")


class Tree:
    """A task tree for one goal by one method, with its status and measures; ``units`` in
    executable order."""

    method = Raw[str]()
    goal_id = Raw[int](name="goal")
    status = Raw[str]("``optimal`` | ``feasible`` | ``unreachable`` | ``unknown`` (ASP), ``found`` | ``not-found``.")
    cost = Raw[dict]("``units``, ``success``, ``inputs``, ``depth`` (empty when there is no tree).")
    bound = Raw[dict | None](
        "The best proven lower bound per objective level, in the units of :attr:`cost` (None for the search baselines)."
    )
    gap = Raw[float | None]("The relative gap to :attr:`bound` on the first objective: 0 when proven.")
    proven_by = Raw[str | None](
        "What proved the answer: ``clingo``, ``fixpoint`` or ``only-tree``; None when not proven and for the search baselines."
    )
    time_s = Raw[float]()
    has_tree = Raw[bool]()

    def __init__(self, kb: Source, raw: TaskTree) -> None:
        self.kb = kb
        #: the internal record (object and unit ids)
        self.raw = raw

    @property
    def goal(self) -> FoonObject:
        return self.kb.problem.objects[self.raw.goal]

    @property
    def goals(self) -> list[FoonObject]:
        """Every goal of the tree: one, or the dishes of a meal."""
        return [self.kb.problem.objects[g] for g in self.raw.meal]

    @property
    def units(self) -> list[Unit]:
        return [self.kb.problem.units[u] for u in self.raw.units]

    @property
    def unit_ids(self) -> list[int]:
        return list(self.raw.units)

    @property
    def valid(self) -> bool | None:
        """The independent validator's verdict where it was judged (compare, batch, :meth:`judge`); else None."""
        value = self.raw.extra.get("valid")
        return None if value is None else bool(value)

    @property
    def note(self) -> str | None:
        """What the solver says about the answer (e.g. a budget that ended a search), if anything."""
        return self.raw.extra.get("note")

    @property
    def substitutions(self) -> list[dict] | None:
        """With substitutes: the ones the tree uses, ``[{"needed", "used"}]`` (else None)."""
        return self.raw.extra.get("substitutions")

    @property
    def alternatives(self) -> list[Tree]:
        """The further trees found with this one (``models`` / ``all_optimal``), best first."""
        return self.with_alternatives[1:]

    @property
    def with_alternatives(self) -> list[Tree]:
        """This tree, then :attr:`alternatives`."""
        return [self if t is self.raw else Tree(self.kb, t) for t in alternatives(self.raw)]

    def schedule(
        self,
        spec: ScheduleSpec | None = None,
        *,
        agents: str | dict[str, int] | None = None,
        durations: str | Path | None = None,
        capabilities: str | Path | None = None,
        resources: str | Path | None = None,
        joint: bool = False,
        encoding: str = DEFAULT_ENCODING,
        options: Options | AspOptions | None = None,
        **settings: Unpack[Settings],
    ) -> Schedule:
        """This tree's units scheduled with the proven-minimal makespan (the agents as in
        :meth:`KnowledgeBase.schedule`); ``joint``: the tree chosen again with the schedule, this
        one's own schedule kept as the result's ``fixed``."""
        solver = options if isinstance(options, AspOptions) else self.kb.options(options, **settings)
        chosen = make_spec(spec, agents, durations, capabilities, resources)
        return next(schedule_trees([self], chosen, solver, joint, encoding))

    def judge(self) -> Tree:
        """Judge the tree with the independent validator (sets :attr:`valid`); returns the tree."""
        compare_mod.judge(self.kb.problem, self.raw)
        return self

    def to_dict(self) -> dict:
        """Exactly one element of ``solve --format json``."""
        return tree_json(self.kb.problem, self.raw)

    def to_text(self) -> str:
        return tree_text(self.kb.problem, self.raw)

    def to_foon(self) -> str:
        """The tree as FOON text (``solve --format foon``)."""
        return tree_foon(self.kb.problem, self.raw)

    def render(self, fmt: str) -> str:
        """The tree in a text format of ``solve --format``."""
        return report.render("trees", fmt, self.kb.problem, [self.raw])

    def draw(self, path: str | Path) -> Path:
        """Draw the tree into ``path``; the format follows the extension (.svg, .png, .pdf, .dot)."""
        return draw.draw_tree(self.kb.problem, self.raw, path)

    def _repr_svg_(self) -> str:
        return draw.tree_svg(self.kb.problem, self.raw)

    def __repr__(self) -> str:
        return f"<Tree {self.goal} {self.method} {self.status} {self.cost}>"


class Schedule:
    """The schedule of one goal's tree: who does which unit when, the makespan, its bounds and baseline."""

    status = Raw[str](
        "``optimal`` | ``feasible`` | ``unschedulable`` | ``unreachable`` | ``unknown`` (no tree in time)."
    )

    def __init__(self, kb: Source, raw: ScheduleResult, spec: ScheduleSpec) -> None:
        self.kb = kb
        #: the internal record (unit ids, times in milliseconds)
        self.raw = raw
        self.spec = spec

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
        return Tree(self.kb, self.raw.tree)

    @property
    def fixed(self) -> Schedule | None:
        """Joint scheduling: the schedule of the given tree alone (None otherwise)."""
        return None if self.raw.fixed is None else Schedule(self.kb, self.raw.fixed, self.spec)

    def check(self) -> str | None:
        """The first violation the independent checker finds (None: a valid schedule)."""
        return schedule_check.check_schedule(self.raw.problem, self.to_dict(), self.spec)

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
        return gantt.gantt_svg(self.to_dict())

    def __repr__(self) -> str:
        return f"<Schedule {self.tree.goal} {self.status} makespan={seconds_text(self.raw.makespan)} s>"


def schedules_json(schedules: list[Schedule]) -> str:
    """``schedule --format json``: a JSON list, one schedule per line."""
    if not schedules:
        return "[]\n"
    return "[\n" + ",\n".join(json.dumps(s.to_dict()) for s in schedules) + "\n]\n"


def schedule_trees(
    trees: Iterable[Tree],
    spec: ScheduleSpec,
    solver: AspOptions,
    joint: bool = False,
    encoding: str = DEFAULT_ENCODING,
    progress: Callable[[dict], None] | None = None,
) -> Iterator[Schedule]:
    """:func:`foon2asp.schedule.schedule` of each tree, on the problem it is judged on;
    ``progress``: called with what that reports and ``goal``, the tree's goals' labels."""
    for tree in trees:
        told = None
        if progress is not None:
            label = " + ".join(g.label for g in tree.goals)

            def told(info: dict, label: str = label) -> None:
                progress({**info, "goal": label})

        problem = tree.kb.judging_problem(solver, tree.raw.meal)
        found = schedule_tree(problem, tree.raw, spec, solver, joint, None, encoding, progress=told)
        yield Schedule(tree.kb, found, spec)


@dataclass
class CheckReport:
    """What ``check`` says about one tree: valid or not, the first problem, the optimum."""

    kb: Source
    raw: Report
    valid = Raw[bool]()
    substitutions = Raw[list[dict] | None]("With substitutes: the ones a valid tree uses (None without substitutes).")
    cost = Raw[dict]()

    @property
    def goal(self) -> FoonObject:
        return self.kb.problem.objects[self.raw.goal]

    @property
    def problem(self) -> str | None:
        """The first problem in words (None for a valid tree)."""
        return self.raw.finding.message if self.raw.finding else None

    @property
    def cycle(self) -> list[tuple[FoonObject, Unit]]:
        """For circular support: (object, unit making it) pairs; each unit needs the next object."""
        if not self.raw.finding:
            return []
        p = self.kb.problem
        return [(p.objects[o], p.units[u]) for o, u in self.raw.finding.cycle]

    @property
    def order(self) -> list[Unit]:
        """The units that can fire, in an executable order."""
        v = self.raw.validation
        return [self.kb.problem.units[u] for u in v.order] if v is not None else []

    @property
    def optimum(self) -> Tree | None:
        return Tree(self.kb, self.raw.optimum) if self.raw.optimum is not None else None

    @property
    def warnings(self) -> list[str]:
        """What reading the tree's file skipped or merged (one line each)."""
        return list(self.raw.tree.warnings)

    def to_dict(self) -> dict:
        return report.check.report_json(self.kb.problem, self.raw)

    def to_text(self) -> str:
        return report.check.report_text(self.kb.problem, self.raw)


@dataclass
class Comparison:
    """One row per goal: the tree of every method, each judged by the validator."""

    kb: Source
    raw: list[Row]

    @property
    def rows(self) -> list[tuple[FoonObject, dict[str, Tree]]]:
        return [(self.kb.problem.objects[r.goal], {m: Tree(self.kb, t) for m, t in r.trees.items()}) for r in self.raw]

    @property
    def trees(self) -> list[Tree]:
        return [Tree(self.kb, t) for r in self.raw for t in r.trees.values()]

    def render(self, fmt: str = "text") -> str:
        return report.render("compare", fmt, self.kb.problem, self.raw)


@dataclass
class Missing:
    """The fewest objects to add to the kitchen so a goal can be made, and the tree then."""

    kb: Source
    raw: MissingResult
    status = Raw[str]()

    @property
    def missing(self) -> list[FoonObject]:
        return [self.kb.problem.objects[o] for o in self.raw.missing]

    @property
    def tree(self) -> Tree | None:
        r = self.raw
        if not r.has_tree:
            return None
        return Tree(self.kb, TaskTree(r.goal, "missing", r.status, list(r.units), dict(r.cost), r.time_s))

    def to_dict(self) -> dict:
        return report.queries.missing_json(self.kb.problem, self.raw)

    def to_text(self) -> str:
        return report.queries.missing_text(self.kb.problem, self.raw)


@dataclass
class Reachability:
    """For each goal: can it be made from the kitchen at all."""

    kb: Source
    #: object id -> reachable, in the order asked
    raw: dict[int, bool]

    @property
    def answers(self) -> dict[FoonObject, bool]:
        return {self.kb.problem.objects[o]: ok for o, ok in self.raw.items()}

    def render(self, fmt: str = "text") -> str:
        """The answers in a format of ``reachable --format``."""
        return report.render("reachable", fmt, self.kb.problem, self.raw)
