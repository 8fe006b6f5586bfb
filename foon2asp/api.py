"""The Python API: load a FOON with its kitchen, then ask it for task trees.

>>> import foon2asp
>>> kb = foon2asp.load("demo")
>>> t = kb.solve("tomato salad")
>>> t.status, t.cost["units"]
('optimal', 1)

Every command of the ``foon2asp`` command line is a thin layer over these
calls: :func:`load` reads the data, :class:`KnowledgeBase` answers
(:meth:`~KnowledgeBase.solve`, :meth:`~KnowledgeBase.check`,
:meth:`~KnowledgeBase.compare`, :meth:`~KnowledgeBase.reachable`,
:meth:`~KnowledgeBase.missing`, :meth:`~KnowledgeBase.query`,
:meth:`~KnowledgeBase.batch`), and the answers render themselves in every
format of :mod:`foon2asp.report`.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from foon2asp import methods, report
from foon2asp.analysis import check as check_mod
from foon2asp.analysis import compare as compare_mod
from foon2asp.analysis import queries
from foon2asp.asp.constraints import ConstraintSpec, unknown_names
from foon2asp.asp.multishot.driver import alternatives
from foon2asp.asp.options import OBJECTIVES, AspOptions
from foon2asp.batch import cluster
from foon2asp.batch import run as batch_run
from foon2asp.batch.pool import BatchSpec
from foon2asp.errors import InputError
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.demo import demo_dir
from foon2asp.foon.loaders import FILE_NAMES, Dataset
from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.problem import Problem
from foon2asp.foon.treefiles import TreeFile, TreeUnit
from foon2asp.methods.planner import solve_goals
from foon2asp.report import draw
from foon2asp.tree.results import BatchReport, MealRow, MissingResult, QueryResult, Report, Row
from foon2asp.tree.serialize import tree_foon, tree_json, tree_text
from foon2asp.tree.tasktree import TaskTree

#: a goal as the API takes it: a label, an object's text, ``"#ID"``, an object id or a FoonObject
GoalLike = str | int | FoonObject


def _objective(value: str | Sequence[str]) -> tuple[str, ...]:
    parts = [p.strip() for p in value.split(",")] if isinstance(value, str) else [str(p).strip() for p in value]
    parts = [p for p in parts if p]
    for p in parts:
        if p not in OBJECTIVES:
            raise InputError(f"unknown objective {p!r} (have {', '.join(OBJECTIVES)})")
    return tuple(parts) or ("units",)


@dataclass
class Constraints:
    """User constraints, as the ``--forbid-motion`` ... ``--rule`` options give them."""

    forbid_motions: Sequence[str] = ()
    forbid_objects: Sequence[str] = ()
    require_motions: Sequence[str] = ()
    require_objects: Sequence[str] = ()
    max_units: int | None = None
    #: ASP rule texts over the vocabulary (docs/vocabulary.md)
    rules: Sequence[str] = ()
    #: ASP files with such rules
    files: Sequence[str] = ()

    def spec(self) -> ConstraintSpec:
        return ConstraintSpec(
            tuple(str(f) for f in self.files),
            tuple(self.rules),
            tuple(self.forbid_motions),
            tuple(self.forbid_objects),
            tuple(self.require_motions),
            tuple(self.require_objects),
            self.max_units,
        )


class Tree:
    """A task tree for one goal by one method, with its status and measures.

    ``units`` are the tree's functional units in executable order (each
    required input is a kitchen item or made by an earlier unit).
    """

    def __init__(self, kb: KnowledgeBase, raw: TaskTree) -> None:
        self.kb = kb
        #: the internal record (object and unit ids)
        self.raw = raw

    @property
    def goal(self) -> FoonObject:
        return self.kb.problem.objects[self.raw.goal]

    @property
    def goal_id(self) -> int:
        return self.raw.goal

    @property
    def goals(self) -> list[FoonObject]:
        """Every goal of the tree: one, or the dishes of a meal (``together=True``)."""
        return [self.kb.problem.objects[g] for g in self.raw.meal]

    @property
    def method(self) -> str:
        return self.raw.method

    @property
    def status(self) -> str:
        """``optimal`` | ``feasible`` | ``unreachable`` | ``unknown`` (ASP), ``found`` | ``not-found`` (search)."""
        return self.raw.status

    @property
    def cost(self) -> dict:
        """``units``, ``success``, ``inputs``, ``depth`` (empty when there is no tree)."""
        return self.raw.cost

    @property
    def units(self) -> list[Unit]:
        return [self.kb.problem.units[u] for u in self.raw.units]

    @property
    def unit_ids(self) -> list[int]:
        return list(self.raw.units)

    @property
    def time_s(self) -> float:
        return self.raw.time_s

    @property
    def has_tree(self) -> bool:
        return self.raw.has_tree

    @property
    def valid(self) -> bool | None:
        """Validity by the independent validator, where it was judged (compare, batch); else None."""
        value = self.raw.extra.get("valid")
        return None if value is None else bool(value)

    @property
    def alternatives(self) -> list[Tree]:
        """The further trees found with this one (``models`` / ``all_optimal``), best first."""
        return [Tree(self.kb, t) for t in alternatives(self.raw)[1:]]

    def to_dict(self) -> dict:
        """Exactly one element of ``solve --format json``."""
        return tree_json(self.kb.problem, self.raw)

    def to_text(self) -> str:
        return tree_text(self.kb.problem, self.raw)

    def to_foon(self) -> str:
        """The tree as FOON text (``solve --format foon``)."""
        return tree_foon(self.kb.problem, self.raw)

    def render(self, fmt: str) -> str:
        """The tree in any text format of ``solve --format`` (:mod:`foon2asp.report`)."""
        return report.render("trees", fmt, self.kb.problem, [self.raw])

    def draw(self, path: str | Path) -> Path:
        """Draw the tree into ``path``; the format follows the extension (.svg, .png, .pdf, .dot)."""
        return draw.draw_tree(self.kb.problem, self.raw, path)

    def _repr_svg_(self) -> str:
        """The drawing, for Jupyter."""
        return draw.tree_svg(self.kb.problem, self.raw)

    def __repr__(self) -> str:
        return f"<Tree {self.goal} {self.method} {self.status} {self.cost}>"


@dataclass
class CheckReport:
    """What ``check`` says about one tree: valid or not, the first problem, the optimum."""

    kb: KnowledgeBase
    raw: Report

    @property
    def valid(self) -> bool:
        return self.raw.valid

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
    def cost(self) -> dict:
        return self.raw.cost

    @property
    def optimum(self) -> Tree | None:
        return Tree(self.kb, self.raw.optimum) if self.raw.optimum is not None else None

    def to_dict(self) -> dict:
        return report.check.report_json(self.kb.problem, self.raw)

    def to_text(self) -> str:
        return report.check.report_text(self.kb.problem, self.raw)


@dataclass
class Comparison:
    """One row per goal: the tree of every method, each judged by the validator."""

    kb: KnowledgeBase
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

    kb: KnowledgeBase
    raw: MissingResult

    @property
    def status(self) -> str:
        return self.raw.status

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
class KnowledgeBase:
    """A FOON with its kitchen, goals, motion success rates and utensils, ready to answer."""

    data: Dataset
    problem: Problem
    #: one-line warnings about the input (skipped units, motions without a rate, ...)
    warnings: list[str] = field(default_factory=list)

    # -- what is there ------------------------------------------------------

    @property
    def goals(self) -> list[FoonObject]:
        """The entries of the goals file, in file order."""
        return [obj for obj, _ in self.data.goals]

    def objects(self, label: str | None = None) -> list[FoonObject]:
        """Every FOON object with ``label`` (all objects when None), in id order."""
        if label is None:
            return list(self.problem.objects)
        return self.problem.foon.by_label(label)

    def find_objects(self, query: str | None = None, only: str | None = None) -> list[int]:
        """Ids of the objects ``query`` names (``#ID``, an object's text, a label, else labels
        containing it as words; all when None); ``only``: ``produced``, ``kitchen`` or ``derivable``."""
        return goals_mod.find_objects(self.problem, query, only)

    def object_info(self, goal: GoalLike) -> dict:
        """``{"id", "text", "label", "states", "ingredients", "container", "in_kitchen", "producers"}``
        (``producers``: how many units make it); a list of these is a goals file."""
        return goals_mod.object_info(self.problem, self.object_id(goal))

    def object_id(self, goal: GoalLike) -> int:
        """The object id of a goal given as a label, an object's text, ``#ID``, an id or an object."""
        if isinstance(goal, FoonObject):
            return goals_mod.goal_id(self.problem, goal)
        if isinstance(goal, int):
            if not 0 <= goal < len(self.problem.objects):
                raise InputError(f"no object #{goal}")
            return goal
        return goals_mod.resolve_goal(self.data, self.problem, goal)

    def goal_ids(self, goals: GoalLike | Iterable[GoalLike] | None) -> list[int]:
        """Object ids for ``goals``: one goal, several, ``"all"`` (the goals file) or ``"all-objects"``."""
        if goals is None:
            return goals_mod.default_goals(self.data, self.problem)
        if goals == "all":
            return goals_mod.resolve(self.data, self.problem, (), "all")
        if goals == "all-objects":
            return goals_mod.all_objects(self.problem)
        if isinstance(goals, str | int | FoonObject):
            return [self.object_id(goals)]
        return [self.object_id(g) for g in goals]

    # -- options ------------------------------------------------------------

    def options(
        self,
        objective: str | Sequence[str] = "units",
        time_limit: float | None = None,
        constraints: Constraints | None = None,
        max_depth: int | None = None,
        human_steps: int | None = None,
        models: int = 1,
        all_optimal: bool = False,
        opt_strategy: str | None = None,
        threads: int | None = None,
    ) -> AspOptions:
        """The solver options every answer uses (defaults: see :mod:`foon2asp.asp.options`)."""
        spec = (constraints or Constraints()).spec()
        self.warnings.extend(unknown_names(self.problem, spec))
        ranked = _objective(objective)
        if human_steps is not None and "success" not in ranked:
            raise InputError(
                "human steps only change the tree when 'success' is an objective (a person's step succeeds"
                f" for sure); use --objective success or {','.join(ranked)},success"
            )
        settings: dict = {}
        if threads is not None:
            settings["threads"] = threads
        if opt_strategy is not None:
            settings["opt_strategy"] = opt_strategy
        return AspOptions(
            objective=_objective(objective),
            time_limit=time_limit,
            programs=spec.programs(),
            max_depth=max_depth,
            human_steps=human_steps,
            models=models,
            all_optimal=all_optimal,
            **settings,
        )

    # -- answers ------------------------------------------------------------

    def solve_iter(
        self, goal_ids: Sequence[int | tuple[int, ...]], method: str = "asp", options: AspOptions | None = None
    ) -> Iterator[Tree]:
        """Trees for ``goal_ids`` one after another (the path every command takes); an
        element that is a tuple of ids is a meal: one tree that makes all of them."""
        options = options or AspOptions()
        kind = methods.get(method).kind
        if kind != "asp" and options.programs:
            raise InputError(f"constraints apply to ASP methods only; {method!r} is a search baseline")
        for raw in solve_goals(self.problem, goal_ids, method, options):
            yield Tree(self, raw)

    def solve(
        self,
        goals: GoalLike | Sequence[GoalLike] | None = None,
        *,
        objective: str | Sequence[str] = "units",
        method: str = "asp",
        time_limit: float | None = None,
        forbid_motions: Sequence[str] = (),
        forbid_objects: Sequence[str] = (),
        require_motions: Sequence[str] = (),
        require_objects: Sequence[str] = (),
        max_units: int | None = None,
        rules: Sequence[str] = (),
        constraint_files: Sequence[str] = (),
        max_depth: int | None = None,
        human_steps: int | None = None,
        models: int = 1,
        all_optimal: bool = False,
        opt_strategy: str | None = None,
        threads: int | None = None,
        together: bool = False,
    ) -> Tree | list[Tree]:
        """The best task tree for a goal (a :class:`Tree`), or for each of several goals (a list).

        ``together=True``: one tree that makes every goal (a meal; units shared
        between dishes count once), proven optimal like a single goal's.

        ``goals``: a label, an object's text, ``"#ID"``, an object, a list of
        these, or ``"all"`` / ``"all-objects"`` (a list).  ``objective``:
        ``units`` (default), ``success``, ``inputs``, ``depth`` or a
        lexicographic list.  The constraint keywords match the CLI flags.
        """
        constraints = Constraints(
            forbid_motions, forbid_objects, require_motions, require_objects, max_units, rules, constraint_files
        )
        options = self.options(
            objective, time_limit, constraints, max_depth, human_steps, models, all_optimal, opt_strategy, threads
        )
        ids = self.goal_ids(goals)
        if together:
            return next(self.solve_iter([tuple(dict.fromkeys(ids))], method, options))
        trees = list(self.solve_iter(ids, method, options))
        single = isinstance(goals, str | int | FoonObject) and goals not in ("all", "all-objects")
        return trees[0] if single else trees

    def check(
        self,
        tree: Tree | str | Path,
        goal: GoalLike | Sequence[GoalLike] | None = None,
        optimum: bool = True,
        goals: Sequence[GoalLike] | str | Path | None = None,
    ) -> CheckReport | list[CheckReport]:
        """Judge a tree: a :class:`Tree`, or a file (FOON text in either dialect, FOON JSON,
        foon2asp JSON, or a plan as Fast Downward writes it for ``export pddl``).

        A :class:`Tree`, or a file holding one tree, gives one report; a file holding several
        gives a list, one per tree (:meth:`check_all`: always a list).
        ``goal``: the goal (several: a meal). Otherwise the goal of a tree in a file is
        the one of ``goals`` (a goals file or a list) the tree makes, else the one the
        file names (a JSON result, or the ``# task tree for ...`` line ``solve --format
        foon`` writes), else the tree's only product no unit of it needs.
        """
        if isinstance(tree, Tree):
            if goal is not None and not isinstance(goal, str | int | FoonObject):
                raise InputError("check a Tree against one goal (its own by default)")
            units = [TreeUnit(self.problem.units[u], i, None) for i, u in enumerate(tree.unit_ids, 1)]
            tf = TreeFile("<tree>", units, tree.goal, tree.method)
            raw = check_mod.check_tree(self.problem, tf, tree.goal_id if goal is None else self.object_id(goal))
            raw.goal_source = "the tree's goal" if goal is None else "given"
            if optimum:
                raw.optimum = next(iter(solve_goals(self.problem, [raw.goal], "asp", AspOptions())))
            return CheckReport(self, raw)

        def name(g: GoalLike) -> str:
            return f"#{self.object_id(g)}" if isinstance(g, int | FoonObject) else g

        goal_list = [] if goal is None else [goal] if isinstance(goal, str | int | FoonObject) else list(goal)
        labels = tuple(name(g) for g in goal_list) or None
        among = None
        if isinstance(goals, str | Path):
            among = goals_mod.goals_from_file(self.problem, str(goals))
        elif goals is not None:
            among = [self.object_id(g) for g in goals]
        reports = check_mod.check_file(self.data, self.problem, tree, labels, optimum, among)
        found = [CheckReport(self, r) for r in reports]
        return found[0] if len(found) == 1 else found

    def check_all(
        self,
        tree: Tree | str | Path,
        goal: GoalLike | Sequence[GoalLike] | None = None,
        optimum: bool = True,
        goals: Sequence[GoalLike] | str | Path | None = None,
    ) -> list[CheckReport]:
        """:meth:`check` as a list, whatever the file holds (one report per tree)."""
        found = self.check(tree, goal, optimum, goals)
        return found if isinstance(found, list) else [found]

    def compare(
        self,
        goals: GoalLike | Sequence[GoalLike] | None = "all",
        methods: Sequence[str] = compare_mod.DEFAULT_METHODS,
        *,
        objective: str | Sequence[str] = "units",
        time_limit: float | None = None,
        constraints: Constraints | None = None,
        opt_strategy: str | None = None,
        threads: int | None = None,
    ) -> Comparison:
        """Every method on every goal, each tree judged valid or not, beside the proven optimum."""
        options = self.options(objective, time_limit, constraints, opt_strategy=opt_strategy, threads=threads)
        parts = self.compare_iter(self.goal_ids(goals), methods, options)
        return Comparison(self, [row for part in parts for row in part.raw])

    def compare_iter(
        self, goal_ids: Sequence[int], methods: Sequence[str] = compare_mod.DEFAULT_METHODS, options=None
    ) -> Iterator[Comparison]:
        """:meth:`compare` goal by goal: a one-row :class:`Comparison` as soon as each goal is done."""
        for row in compare_mod.compare_iter(self.problem, list(goal_ids), list(methods), options):
            yield Comparison(self, [row])

    def compare_meal(
        self,
        goals: Sequence[GoalLike],
        method: str = "asp",
        *,
        objective: str | Sequence[str] = "units",
        time_limit: float | None = None,
        constraints: Constraints | None = None,
        opt_strategy: str | None = None,
        threads: int | None = None,
    ) -> MealRow:
        """The meal's optimal tree (all ``goals`` at once) beside each goal's own optimum."""
        options = self.options(objective, time_limit, constraints, opt_strategy=opt_strategy, threads=threads)
        return compare_mod.compare_meal(self.problem, self.goal_ids(goals), method, options)

    def reachable(self, goals: GoalLike | Sequence[GoalLike] | None = "all") -> dict[FoonObject, bool]:
        """For each goal: can it be made from the kitchen at all (one solve for all)?"""
        answers = queries.reachable(self.problem, self.goal_ids(goals))
        return {self.problem.objects[o]: ok for o, ok in answers.items()}

    def missing(
        self,
        goal: GoalLike | Sequence[GoalLike],
        *,
        time_limit: float | None = None,
        constraints: Constraints | None = None,
        objective: str | Sequence[str] = "units",
        opt_strategy: str | None = None,
        threads: int = 1,
    ) -> Missing:
        """The fewest objects to add to the kitchen so ``goal`` can be made (proven minimal), then
        the best tree by ``objective`` (``units``, ``success``, ``inputs`` or a lexicographic list).

        Several goals: the fewest objects for the whole meal (one tree making all of them).
        """
        programs = (constraints or Constraints()).spec().programs()
        ranked = _objective(objective)
        target: int | tuple[int, ...]
        if isinstance(goal, str | int | FoonObject):
            target = self.object_id(goal)
        else:
            target = tuple(dict.fromkeys(self.object_id(g) for g in goal))
        answer = queries.missing(self.problem, target, programs, time_limit, ranked, opt_strategy, threads)
        return Missing(self, answer)

    def query(
        self,
        program: str,
        *,
        goal: GoalLike | None = None,
        encodings: Sequence[str] = (),
        models: int = 1,
        time_limit: float | None = None,
        name: str = "<program>",
        goal_nodes: GoalLike | Sequence[GoalLike] | None = None,
    ) -> QueryResult:
        """Run an ASP ``program`` (text) with the facts; shown atoms come back with ids decoded.

        ``goal_nodes`` (default: the goals file's entries) become ``goal_node/2`` facts;
        ``encodings`` are loaded with the ones they need (``reachable`` needs ``tree``).
        With a ``#show`` of its own in ``program`` only what it shows is returned;
        ``warnings`` names atoms the program uses that no rule or fact defines.
        """
        if goal_nodes is None:
            path = self.data.paths.get("goals")
            nodes = [goals_mod.goal_id(self.problem, obj, path, line) for obj, line in self.data.goals]
        else:
            nodes = self.goal_ids(goal_nodes)
        gid = None if goal is None else self.object_id(goal)
        return queries.query(self.problem, (name, program), nodes, gid, encodings, models, time_limit)

    def batch(
        self,
        goals: GoalLike | Sequence[GoalLike] | None = "all-objects",
        output: str | Path | None = None,
        *,
        methods: Sequence[str] = ("asp",),
        workers: int = 1,
        resume: bool = False,
        objective: str | Sequence[str] = "units",
        time_limit: float | None = None,
        constraints: Constraints | None = None,
        opt_strategy: str | None = None,
        threads: int | None = None,
        grounding: str = "auto",
        shortcuts: bool = True,
        progress: bool | None = False,
        fsync: bool = True,
        scheduler: str | None = None,
    ) -> BatchReport:
        """Many goals x methods into a resumable JSON-lines file (``output``; None keeps results in memory).

        ``grounding``: ``"whole"``, ``"per-goal"`` or ``"auto"`` (chosen from the FOON and the goals by
        :func:`foon2asp.batch.run.choose_grounding`; the report's ``grounding`` and ``grounding_reason`` say which).
        """
        options = self.options(objective, time_limit, constraints, opt_strategy=opt_strategy, threads=threads)
        spec = BatchSpec(self.problem, list(dict.fromkeys(methods)), options, grounding, shortcuts)
        executor = None
        if scheduler:
            executor = cluster.executor(scheduler)
        return batch_run.run_batch(spec, self.goal_ids(goals), output, resume, workers, progress, fsync, executor)


#: what is lost when a file is not beside the FOON
_WITHOUT = {
    "goals": "no goals file: name goals with --goal or --goals FILE",
    "motion": "every motion gets success rate 0.5",
    "utensils": "no object is treated as a utensil",
}


def _beside(foon: Path, given: dict, warnings: list[str]) -> dict:
    """``given`` with the files not given taken from beside ``foon``; warnings for absent optional ones."""
    out = dict(given)
    for key, value in given.items():
        if value is not None:
            continue
        candidate = foon.parent / FILE_NAMES[key]
        if candidate.is_file():
            out[key] = str(candidate)
        elif key == "kitchen":
            raise InputError(
                f"no {FILE_NAMES[key]} beside the FOON file (looked for {candidate});"
                " give --kitchen FILE or --data DIR (--data demo for the demo data)"
            )
        else:
            warnings.append(f"no {FILE_NAMES[key]} beside {foon}: {_WITHOUT[key]}")
    return out


def load(
    path: str | Path | None = None,
    *,
    foon: str | Path | Sequence[str | Path] | None = None,
    kitchen: str | Path | None = None,
    goals: str | Path | None = None,
    motion: str | Path | None = None,
    utensils: str | Path | None = None,
    utensil_rule: str = "starter",
    strict: bool = False,
) -> KnowledgeBase:
    """Read a data folder (``FOON.txt``, ``kitchen.json``, ``goal_nodes.json``,
    ``motion.txt``, ``utensils.txt``) or ``"demo"``; keyword files override its files.

    With ``foon`` and no folder, the other files are read from beside the
    (first) FOON file when there; a missing ``kitchen.json`` is an error, a
    missing goals, motion or utensils file a warning saying what that means.
    """
    if path == "demo":
        path = demo_dir()
    if path is None and foon is None:
        raise InputError("no data given: load(DIR), load('demo') or load(foon=FILE, kitchen=FILE, ...)")
    foon_paths: str | list | None = (
        [str(f) for f in foon] if isinstance(foon, list | tuple) else (None if foon is None else str(foon))
    )
    beside: list[str] = []
    if path is None and foon_paths:
        first = Path(foon_paths[0] if isinstance(foon_paths, list) else foon_paths)
        found = _beside(first, {"kitchen": kitchen, "goals": goals, "motion": motion, "utensils": utensils}, beside)
        kitchen, goals, motion, utensils = found["kitchen"], found["goals"], found["motion"], found["utensils"]
    data = Dataset.load(
        path, foon=foon_paths, kitchen=kitchen, goals=goals, motion=motion, utensils=utensils, strict=strict
    )
    problem = Problem.from_dataset(data, utensil_rule)
    warnings = list(data.foon.warnings) + list(data.warnings) + beside
    unknown = problem.unknown_motions()
    if data.motion and unknown:
        warnings.append(
            f"{len(unknown)} motion(s) not in {data.paths.get('motion')} get success rate 0.5: {', '.join(unknown[:5])}"
        )
    return KnowledgeBase(data, problem, warnings)
