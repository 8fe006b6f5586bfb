"""The answers of :class:`foon2asp.api.KnowledgeBase`: trees and their schedules, check reports,
comparisons, missing items, reachability, batch runs, consolidations and verdicts on files; each
renders itself in the formats of :mod:`foon2asp.report`.

Each answer wraps one internal record (``raw``, of object and unit ids) once; its attributes
(:class:`Raw`) read that record's fields in the FOON of the knowledge base that gave it."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any, ClassVar, Generic, Protocol, TypeVar, cast

from foon2asp import report
from foon2asp.analysis import compare as compare_mod
from foon2asp.api.request import Options, schedule_request
from foon2asp.asp.multishot.driver import alternatives
from foon2asp.asp.options import AspOptions
from foon2asp.batch.results_file import record_trees, summarize
from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.problem import Problem
from foon2asp.report import draw, gantt
from foon2asp.schedule import DEFAULT_ENCODING, ScheduleSpec, schedule
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.result import seconds, seconds_text
from foon2asp.tree.serialize import json_list, tree_foon, tree_json, tree_text
from foon2asp.tree.tasktree import TaskTree

T = TypeVar("T")


class Source(Protocol):
    """What an answer asks of the knowledge base that gave it (:class:`foon2asp.api.KnowledgeBase`)."""

    problem: Problem

    def options(self, options: Options | AspOptions | None = None, **settings: Any) -> AspOptions: ...

    def solving_problem(self, solver: AspOptions) -> Problem: ...

    def judging_problem(self, solver: AspOptions | Options | None, goals: Iterable[int] = ()) -> Problem: ...


class Raw(Generic[T]):
    """An answer's read-only attribute: the field ``path`` of its ``raw`` record (dotted: nested;
    default: the attribute's name), passed through ``read(answer, value)`` when given."""

    def __init__(self, doc: str = "", path: str = "", read: Callable[[Any, Any], T] | None = None) -> None:
        self.__doc__, self.path, self.read = doc, path, read

    def __set_name__(self, owner: type, name: str) -> None:
        self.path = self.path or name

    def __get__(self, answer: Any, owner: type | None = None) -> T:
        if answer is None:
            return cast(T, self)
        value = answer.raw
        for name in self.path.split("."):
            value = getattr(value, name)
        return value if self.read is None else self.read(answer, value)

    def __set__(self, answer: Any, value: Any) -> None:
        raise AttributeError(f"{self.path!r} is read-only")


def object_of(answer: Any, oid: int) -> FoonObject:
    return answer.kb.problem.objects[oid]


def objects_of(answer: Any, ids: Iterable[int]) -> list[FoonObject]:
    return [answer.kb.problem.objects[o] for o in ids]


def units_of(answer: Any, ids: Iterable[int]) -> list[Unit]:
    return [answer.kb.problem.units[u] for u in ids]


def tree_of(answer: Any, raw: TaskTree) -> Tree:
    return Tree(answer.kb, raw)


def as_list(answer: Any, items: Iterable) -> list:
    return list(items)


@dataclass(eq=False)
class Answer:
    """An answer: its internal record ``raw``, read in the FOON of ``kb``."""

    kb: Source
    raw: Any
    #: the kind of answer :meth:`render` renders (:func:`foon2asp.report.render`; "": none)
    kind: ClassVar[str] = ""
    #: :meth:`render` renders the record as its command renders a list of one
    one: ClassVar[bool] = False
    #: the writers of :meth:`to_dict` and :meth:`to_text`: (problem, raw) -> JSON value, text
    json_of: ClassVar[Callable[[Problem, Any], dict] | None] = None
    text_of: ClassVar[Callable[[Problem, Any], str] | None] = None

    def render(self, fmt: str = "text") -> str:
        """The answer in a text format of its command's ``--format``."""
        if not self.kind:
            raise AttributeError(f"{type(self).__name__} has no render(); use to_dict() or to_text()")
        return report.render(self.kind, fmt, self.kb.problem, [self.raw] if self.one else self.raw)

    def to_dict(self) -> dict:
        """Exactly one element of its command's ``--format json``."""
        return self._written(type(self).json_of, "to_dict")

    def to_text(self) -> str:
        return self._written(type(self).text_of, "to_text")

    def _written(self, writer: Callable[[Problem, Any], Any] | None, name: str) -> Any:
        if writer is None:
            raise AttributeError(f"{type(self).__name__} has no {name}(); use render(fmt)")
        return writer(self.kb.problem, self.raw)


class Tree(Answer):
    """A task tree for one goal by one method, with its status and measures; ``units`` in executable order."""

    kind, one = "trees", True
    json_of, text_of = tree_json, tree_text
    method = Raw[str]()
    goal = Raw[FoonObject](read=object_of)
    goal_id = Raw[int](path="goal")
    goals = Raw[list[FoonObject]]("Every goal of the tree: one, or the dishes of a meal.", "meal", objects_of)
    units = Raw[list[Unit]](read=units_of)
    unit_ids = Raw[list[int]](path="units", read=as_list)
    status = Raw[str]("``optimal`` | ``feasible`` | ``unreachable`` | ``unknown`` (ASP), ``found`` | ``not-found``.")
    cost = Raw[dict]("``units``, ``success``, ``inputs``, ``depth`` (empty when there is no tree).")
    bound = Raw[dict | None]("The best proven lower bound per objective level, in the units of :attr:`cost`.")
    gap = Raw[float | None]("The relative gap to :attr:`bound` on the first objective: 0 when proven.")
    proven_by = Raw[str | None]("What proved the answer: ``clingo``, ``fixpoint`` or ``only-tree``; else None.")
    time_s = Raw[float]()
    has_tree = Raw[bool]()

    note = Raw[str | None]("What the solver says about the answer, if anything.")
    substitutions = Raw[list[dict] | None]("With substitutes: the ones the tree uses.")
    valid = Raw[bool | None]("The validator's verdict where it was judged (compare, batch, :meth:`judge`).")

    @property
    def alternatives(self) -> list[Tree]:
        """The further trees found with this one (``models`` / ``all_optimal``), best first."""
        return self.with_alternatives[1:]

    @property
    def with_alternatives(self) -> list[Tree]:
        """This tree, then :attr:`alternatives`."""
        return [self if t is self.raw else Tree(self.kb, t) for t in alternatives(self.raw)]

    def schedule(
        self, spec: ScheduleSpec | None = None, *, options: Options | AspOptions | None = None, **settings: Any
    ) -> Schedule:
        """This tree's units scheduled with the proven-minimal makespan (the agents and ``joint``
        as in :meth:`KnowledgeBase.schedule`; ``joint``: this tree's own schedule is ``fixed``)."""
        request = schedule_request(spec, settings)
        solver = self.kb.options(options, **settings)
        return next(schedule_trees([self], solver, **request))

    def judge(self) -> Tree:
        """Judge the tree with the independent validator (sets :attr:`valid`); returns the tree."""
        compare_mod.judge(self.kb.problem, self.raw)
        return self

    def to_foon(self) -> str:
        """The tree as FOON text (``solve --format foon``)."""
        return tree_foon(self.kb.problem, self.raw)

    def draw(self, path: str | Path) -> Path:
        """Draw the tree into ``path``; the format follows the extension (.svg, .png, .pdf, .dot)."""
        return draw.draw_tree(self.kb.problem, self.raw, path)

    def _repr_svg_(self) -> str:
        return draw.tree_svg(self.kb.problem, self.raw)

    def __repr__(self) -> str:
        return f"<Tree {self.goal} {self.method} {self.status} {self.cost}>"


@dataclass(eq=False)
class Schedule(Answer):
    """The schedule of one goal's tree: who does which unit when, the makespan, its bounds and baseline."""

    json_of, text_of = (lambda _, raw: raw.to_dict()), (lambda _, raw: raw.to_text())
    spec: ScheduleSpec = field(default_factory=ScheduleSpec)
    status = Raw[str]("``optimal`` | ``feasible`` | ``unschedulable`` | ``unreachable`` | ``unknown`` (no tree).")
    makespan = Raw[float | None]("Seconds (None without a schedule).", read=lambda _, ms: seconds(ms))
    agents = Raw[list[str]](read=as_list)
    tree = Raw[Tree]("The scheduled tree (``joint``: the one chosen with the schedule).", read=tree_of)

    @property
    def entries(self) -> list[dict]:
        """``{"unit", "agent", "start", "end"}`` per unit, by start time (the JSON's ``schedule``)."""
        return self.to_dict()["schedule"]

    @property
    def fixed(self) -> Schedule | None:
        """Joint scheduling: the schedule of the given tree alone (None otherwise)."""
        return None if self.raw.fixed is None else Schedule(self.kb, self.raw.fixed, self.spec)

    def check(self) -> str | None:
        """The first violation the independent checker finds (None: a valid schedule)."""
        return check_schedule(self.raw.problem, self.to_dict(), self.spec)

    def render(self, fmt: str = "text") -> str | bytes:  # type: ignore[override]
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
    return json_list([s.to_dict() for s in schedules]) + "\n"


def _with_goal(progress: Callable[[dict], None], label: str, info: dict) -> None:
    progress({**info, "goal": label})


def schedule_trees(
    trees: Iterable[Tree],
    solver: AspOptions,
    spec: ScheduleSpec,
    joint: bool = False,
    encoding: str = DEFAULT_ENCODING,
    progress: Callable[[dict], None] | None = None,
) -> Iterator[Schedule]:
    """:func:`foon2asp.schedule.schedule` of each tree, on the problem it is judged on;
    ``progress``: called with what that reports and ``goal``, the tree's goals' labels."""
    for tree in trees:
        told = None if progress is None else partial(_with_goal, progress, " + ".join(g.label for g in tree.goals))
        problem = tree.kb.judging_problem(solver, tree.raw.meal)
        found = schedule(problem, tree.raw, spec, solver, joint, None, encoding, progress=told)
        yield Schedule(tree.kb, found, spec)


class CheckReport(Answer):
    """What ``check`` says about one tree: valid or not, the first problem, the optimum."""

    kind, one = "check", True
    json_of, text_of = report.verdicts.report_json, report.verdicts.report_text
    valid = Raw[bool]()
    substitutions = Raw[list[dict] | None]("With substitutes: the ones a valid tree uses (None without substitutes).")
    cost = Raw[dict]()
    goal = Raw[FoonObject](read=object_of)
    warnings = Raw[list[str]](
        "What reading the tree's file skipped or merged (one line each).", "tree.warnings", as_list
    )

    @property
    def problem(self) -> str | None:
        """The first problem in words (None for a valid tree)."""
        return self.raw.finding.message if self.raw.finding else None

    @property
    def cycle(self) -> list[tuple[FoonObject, Unit]]:
        """For circular support: (object, unit making it) pairs; each unit needs the next object."""
        p = self.kb.problem
        return [(p.objects[o], p.units[u]) for o, u in self.raw.finding.cycle] if self.raw.finding else []

    @property
    def order(self) -> list[Unit]:
        """The units that can fire, in an executable order."""
        v = self.raw.validation
        return units_of(self, v.order) if v is not None else []

    optimum = Raw[Tree | None](read=lambda a, t: None if t is None else Tree(a.kb, t))
    proof = Raw[dict | None](
        "The proof the tree claims, checked again without the solver: ``{proven_by, verified, problem}`` (None: none)."
    )


class Comparison(Answer):
    """One row per goal (``raw``: the rows): the tree of every method, each judged by the validator."""

    kind = "compare"

    @property
    def rows(self) -> list[tuple[FoonObject, dict[str, Tree]]]:
        return [(object_of(self, r.goal), {m: Tree(self.kb, t) for m, t in r.trees.items()}) for r in self.raw]

    @property
    def trees(self) -> list[Tree]:
        return [Tree(self.kb, t) for r in self.raw for t in r.trees.values()]


class Missing(Answer):
    """The fewest objects to add to the kitchen so a goal can be made, and the tree then."""

    kind, one = "missing", True
    json_of, text_of = report.query_answers.missing_json, report.query_answers.missing_text
    status = Raw[str]()
    missing = Raw[list[FoonObject]](read=objects_of)

    @property
    def tree(self) -> Tree | None:
        r = self.raw
        if not r.has_tree:
            return None
        return Tree(self.kb, TaskTree(r.goal, "missing", r.status, list(r.units), dict(r.cost), r.time_s))


class Reachability(Answer):
    """For each goal: can it be made from the kitchen at all (``raw``: object id -> reachable, in the order asked)."""

    kind = "reachable"

    @property
    def answers(self) -> dict[FoonObject, bool]:
        return {object_of(self, o): ok for o, ok in self.raw.items()}


@dataclass(eq=False)
class BatchRun(Answer):
    """What a batch did: counts, times, the grounding and every record of the requested pairs."""

    #: :meth:`schedule`'s schedules, one per goal (empty until it runs)
    schedules: list[Schedule] = field(default_factory=list)
    done = Raw[int]("Results computed now.")
    skipped = Raw[int]("Results already in the file (``resume``).")
    elapsed_s = Raw[float]()
    records = Raw[list[dict]]("The JSON lines of the requested (goal, method) pairs, old and new.")
    workers = Raw[int]()
    output = Raw[str | None]()
    grounding = Raw[str]("``whole`` or ``per-goal``: the grounding used.")
    grounding_reason = Raw[str]('Why ``grounding="auto"`` chose it (empty otherwise).')

    def schedule(
        self,
        spec: ScheduleSpec | None = None,
        *,
        method: str | None = None,
        output: str | Path | None = None,
        **settings: Any,
    ) -> list[Schedule]:
        """Schedule the tree of every goal of the run (of ``method``; default the first asked for)
        as :meth:`Tree.schedule` does; ``output``: also write them there as ``schedule --format json``."""
        request = schedule_request(spec, settings)
        solver = self.kb.options(**settings)
        found = record_trees(self.kb.solving_problem(solver), self.raw.records, method)
        self.schedules = list(schedule_trees([Tree(self.kb, t) for t in found], solver, **request))
        if output is not None:
            write_file(output, schedules_json(self.schedules))
        return self.schedules

    def summary(self) -> list[dict]:
        """One row per method: results per status, trees, valid trees, tree sizes and times."""
        return summarize(self.raw.records)

    def render(self, fmt: str = "text") -> str:
        """The summary ``batch`` prints, in a format of ``batch --summary``."""
        # the HTML page draws the schedules, and the FOON for kitchen items and cycles
        extra = [[s.to_dict() for s in self.schedules], self.kb.problem] if fmt == "html" else []
        return report.render("summary", fmt, self.summary(), self.raw, *extra)


def writable_dir(path: str | Path) -> Path:
    """``path`` as a directory, created with its parents (an error names the path)."""
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create the output directory: {exc.strerror or exc}", str(out)) from None
    if not out.is_dir():
        raise InputError("output path is not a directory", str(out))
    return out


def write_file(path: str | Path, text: str | bytes) -> None:
    """Write ``text`` to ``path``, creating its directory (an error names the path)."""
    out = Path(path)
    if out.parent != Path("."):
        writable_dir(out.parent)
    try:
        if isinstance(text, bytes):
            out.write_bytes(text)
        else:
            out.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot write the output file: {exc.strerror or exc}", str(out)) from None
