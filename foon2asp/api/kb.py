"""The knowledge base: a FOON with its kitchen, goals, motion success rates and utensils, ready to answer.

Every answer takes a request as ``options=`` (:class:`foon2asp.api.Options`) and/or as keywords
(:class:`foon2asp.api.options.Settings`)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import Any, Unpack

from foon2asp import methods
from foon2asp.analysis import check as check_mod
from foon2asp.analysis import compare as compare_mod
from foon2asp.analysis import queries
from foon2asp.api import matching
from foon2asp.api.batches import BatchRun, workers_count
from foon2asp.api.matching import GoalLike
from foon2asp.api.options import Options, Settings
from foon2asp.api.results import CheckReport, Comparison, Missing, Reachability, Schedule, Tree, schedule_trees
from foon2asp.api.schedules import ScheduleVerdict, check_schedule_file, make_spec
from foon2asp.asp.constraints import unknown_names
from foon2asp.asp.facts import facts as facts_text
from foon2asp.asp.options import AspOptions
from foon2asp.asp.substitutes import report as report_substitutions
from foon2asp.batch import cluster
from foon2asp.batch import run as batch_run
from foon2asp.batch.pool import BatchSpec
from foon2asp.errors import InputError
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.loaders import Dataset
from foon2asp.foon.matching import Projection
from foon2asp.foon.model import FoonObject
from foon2asp.foon.motioncost import unit_weights
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import Substitute
from foon2asp.foon.treefiles import TreeFile, TreeUnit
from foon2asp.methods.runner import solve_goals
from foon2asp.schedule import DEFAULT_ENCODING, ScheduleSpec
from foon2asp.tree.results import MealRow, QueryResult


@dataclass
class KnowledgeBase:
    """A FOON with its kitchen, goals, motion success rates and utensils, ready to answer."""

    data: Dataset
    problem: Problem
    #: one-line warnings about the input (skipped units, motions without a rate, files not found, ...)
    warnings: tuple[str, ...] = ()
    #: how objects are compared (``load``'s ``level``, ``normalize``, ``synonyms``; foon2asp.foon.matching)
    projection: Projection = field(default_factory=Projection)
    #: motion-cost weights -> (the problem with them, substitutes -> the problems trees are judged on)
    _views: dict = field(default_factory=dict, init=False, repr=False)

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

    def find_objects(
        self, query: str | None = None, only: str | None = None, options: Options | None = None
    ) -> list[int]:
        """Ids of the objects ``query`` names (``#ID``, an object's text, a label, else labels
        containing it as words; all when None); ``only``: ``produced``, ``kitchen`` or ``derivable``
        (with ``options.substitutes``: derivable when substitutes may stand in for kitchen items)."""
        return matching.find_objects(self.problem, self.projection, query, only, options)

    def object_info(self, goal: GoalLike) -> dict:
        """``{"id", "text", "label", "states", "ingredients", "container", "in_kitchen", "producers"}``
        (a list of these is a goals file); ``"joined"``: the texts of the objects it stands for
        when the comparison joined several."""
        return matching.object_info(self.problem, self.projection, self.object_id(goal))

    def object_id(self, goal: GoalLike) -> int:
        """The object id of a goal given as a label, an object's text, ``#ID``, an id or an object."""
        return matching.object_id(self.data, self.problem, self.projection, goal)

    def goal_ids(self, goals: GoalLike | Iterable[GoalLike] | None) -> list[int]:
        """Object ids for ``goals``: one goal, several, ``"all"`` (the goals file) or ``"all-objects"``."""
        return matching.goal_ids(self.data, self.problem, self.projection, goals)

    def select_goals(self, goal: Sequence[str] = (), goals: str | Path | None = None) -> list[int]:
        """The goals a request names: each of ``goal`` in order, then ``goals`` (a goals file,
        ``"all"`` or ``"all-objects"``); neither: the goals file's entries, else an error."""
        return matching.select_goals(self.data, self.problem, self.projection, goal, goals)

    def file_goals(self) -> list[int]:
        """The ids of the goals file's entries (none without a goals file)."""
        path = self.data.paths.get("goals")
        return [goals_mod.goal_id(self.problem, obj, path, line) for obj, line in self.data.goals]

    def facts(
        self, goal_nodes: Iterable[int] | None = None, goals: Iterable[int] = (), options: Options | None = None
    ) -> str:
        """The FOON, kitchen and goals as ASP facts: ``goal_node/2`` for ``goal_nodes`` (default:
        the goals file's entries), ``goal/1`` for each of ``goals``, and with ``options.substitutes``
        ``substitute(N,K,C)`` (docs/vocabulary.md)."""
        nodes = self.file_goals() if goal_nodes is None else list(goal_nodes)
        text = facts_text(self.problem, goal_nodes=nodes) + "".join(f"goal({g}).\n" for g in goals)
        return text + matching.substitute_facts(self.problem, self.projection, options)

    @property
    def joined(self) -> dict[str, list[str]]:
        """The spellings joined by ``normalize``/``synonyms``: first spelling -> every spelling."""
        return matching.joined(self.projection)

    def substitutes(self, options: Options | None) -> tuple[Substitute, ...]:
        """The substitutes of a request, spelled as this knowledge base spells labels."""
        return matching.substitutes(self.projection, options)

    def solving_problem(self, solver: AspOptions) -> Problem:
        """The problem answers with ``solver`` are found on: with its motion costs, every tree's
        measures include ``cost``."""
        return self._costed(solver.motion_costs)[0]

    def judging_problem(self, solver: AspOptions | Options | None, goals: Iterable[int] = ()) -> Problem:
        """The problem a tree is judged on: :meth:`solving_problem`, where with substitutes every
        object one can stand in for (but ``goals``) is a kitchen item."""
        if isinstance(solver, AspOptions):
            problem, views = self._costed(solver.motion_costs)
            return matching.judging_problem(problem, views, solver.substitutes, goals)
        problem, views = self._costed(None)
        return matching.judging_problem(problem, views, self.substitutes(solver), goals)

    def _costed(self, weights: dict[str, int] | None) -> tuple[Problem, dict]:
        """The problem with the motion costs ``weights``, and the problems judged on made of it so far."""
        key = None if weights is None else frozenset(weights.items())
        if key not in self._views:
            self._views[key] = (self.problem if weights is None else matching.costed(self.problem, weights), {})
        return self._views[key]

    def project_tree(self, tree: TreeFile) -> TreeFile:
        """A tree read from a file, its units and goal as this knowledge base's level sees them."""
        return matching.project_tree(self.projection, tree)

    def options_and_warnings(
        self, options: Options | None = None, **settings: Unpack[Settings]
    ) -> tuple[AspOptions, list[str]]:
        """The solver options of a request (:meth:`options`) and the warnings about it: constraint
        names no motion or label matches, the motions the motion-cost table lacks (each costs 1)."""
        request = Options.of(options, **settings)
        warnings = unknown_names(self.problem, request.constraints)
        solver = request.solver()
        if solver.substitutes:  # spelled as the FOON's labels are at this level
            solver = replace(solver, substitutes=self.projection.substitutes(solver.substitutes))
        table = request.motion_table()
        if table is None:
            return solver, warnings
        weights, warning = unit_weights(table, [u.motion for u in self.problem.units])
        return replace(solver, motion_costs=weights), warnings + ([] if warning is None else [warning])

    def options(self, options: Options | None = None, **settings: Unpack[Settings]) -> AspOptions:
        """The solver options of a request (defaults: :mod:`foon2asp.asp.options`): names checked,
        constraint programs read, the motion-cost table as integer weights (hundredths)."""
        return self.options_and_warnings(options, **settings)[0]

    def _solver(self, options: Options | AspOptions | None) -> AspOptions:
        return options if isinstance(options, AspOptions) else self.options(options)

    # -- answers ------------------------------------------------------------

    def solve_iter(
        self,
        goal_ids: Sequence[int | tuple[int, ...]],
        method: str = "asp",
        options: Options | AspOptions | None = None,
    ) -> Iterator[Tree]:
        """Trees for ``goal_ids`` one after another; a tuple of ids is a meal (one tree making
        all of them).  ``options``: a request, or the solver options :meth:`options` made of one."""
        solver = self._solver(options)
        if methods.get(method).kind != "asp" and solver.programs:
            raise InputError(f"constraints apply to ASP methods only; {method!r} is a search baseline")
        for raw in solve_goals(self.solving_problem(solver), goal_ids, method, solver):
            yield Tree(self, raw)

    def solve(
        self,
        goals: GoalLike | Sequence[GoalLike] | None = None,
        *,
        method: str = "asp",
        together: bool = False,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> Tree | list[Tree]:
        """The best task tree for a goal (a :class:`Tree`), or for each of several goals (a list;
        also for ``"all"`` / ``"all-objects"``).  ``together=True``: one tree that makes every goal
        (a meal; units shared between dishes count once), proven optimal like a single goal's."""
        solver = self.options(options, **settings)
        trees = list(self.solve_iter(matching.jobs(self.goal_ids(goals), together), method, solver))
        return trees[0] if together or _one(goals) else trees

    def check(
        self,
        tree: Tree | str | Path,
        goal: GoalLike | Sequence[GoalLike] | None = None,
        optimum: bool = True,
        goals: Sequence[GoalLike] | str | Path | None = None,
        *,
        strict: bool = False,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> CheckReport | list[CheckReport]:
        """Judge a :class:`Tree`, or each tree of a file (any tree format, or a plan of ``export
        pddl``): one report, or a list when the file holds several.  ``goal``: the goal (several: a
        meal); else the one of ``goals`` the tree makes, else the one the file names, else the
        tree's only product no unit needs.  ``optimum``: also solve the optimum with the request."""
        solver = self.options(options, **settings)
        if isinstance(tree, Tree):
            if goal is not None and not isinstance(goal, str | int | FoonObject):
                raise InputError("check a Tree against one goal (its own by default)")
            units = [TreeUnit(self.problem.units[u], i, None) for i, u in enumerate(tree.unit_ids, 1)]
            tf = TreeFile("<tree>", units, tree.goal, tree.method)
            gid = tree.goal_id if goal is None else self.object_id(goal)
            raw = check_mod.check_tree(self.judging_problem(solver, (gid,)), tf, gid)
            raw.goal_source = "the tree's goal" if goal is None else "given"
            reports = [raw]
        else:
            view = partial(self.judging_problem, solver)
            reports = matching.check_file(self.data, self.problem, self.projection, view, tree, goal, goals, strict)
        for r in reports if solver.substitutes else []:
            used = [u for u in dict.fromkeys(r.ids) if u is not None]
            r.substitutions = report_substitutions(self.problem, r.meal, used, solver.substitutes) if r.valid else []
        if optimum and reports:
            # a Tree's own goal, a file's trees by meal (one goal: a meal of one)
            key = (lambda r: r.goal) if isinstance(tree, Tree) else (lambda r: r.meal)
            meals = list(dict.fromkeys(key(r) for r in reports))
            best = dict(zip(meals, (t.raw for t in self.solve_iter(meals, "asp", solver))))
            for r in reports:
                r.optimum = best[key(r)]
        found = [CheckReport(self, r) for r in reports]
        return found[0] if len(found) == 1 else found

    def check_all(self, *args: Any, **kwargs: Any) -> list[CheckReport]:
        """:meth:`check` (the same arguments) as a list, whatever the file holds."""
        found = self.check(*args, **kwargs)
        return found if isinstance(found, list) else [found]

    def compare(
        self,
        goals: GoalLike | Sequence[GoalLike] | None = "all",
        methods: Sequence[str] = compare_mod.DEFAULT_METHODS,
        *,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> Comparison:
        """Every method on every goal, each tree judged valid or not, beside the proven optimum."""
        solver = self.options(options, **settings)
        parts = self.compare_iter(self.goal_ids(goals), methods, solver)
        return Comparison(self, [row for part in parts for row in part.raw])

    def compare_iter(
        self,
        goal_ids: Sequence[int],
        methods: Sequence[str] = compare_mod.DEFAULT_METHODS,
        options: Options | AspOptions | None = None,
    ) -> Iterator[Comparison]:
        """:meth:`compare` goal by goal: a one-row :class:`Comparison` as soon as each goal is done."""
        solver = self._solver(options)
        for row in compare_mod.compare_iter(self.solving_problem(solver), list(goal_ids), list(methods), solver):
            yield Comparison(self, [row])

    def compare_meal(
        self,
        goals: Sequence[GoalLike],
        method: str = "asp",
        *,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> MealRow:
        """The meal's optimal tree (all ``goals`` at once) beside each goal's own optimum."""
        solver = self.options(options, **settings)
        return compare_mod.compare_meal(self.solving_problem(solver), self.goal_ids(goals), method, solver)

    def reachability(
        self, goals: GoalLike | Sequence[GoalLike] | None = "all", *, options: Options | None = None
    ) -> Reachability:
        """For each goal: can it be made from the kitchen at all (one solve for all)?  With
        ``options.substitutes``: when substitutes may stand in for missing kitchen items."""
        return Reachability(self, matching.reachable(partial(self.judging_problem, options), self.goal_ids(goals)))

    def reachable(
        self, goals: GoalLike | Sequence[GoalLike] | None = "all", *, options: Options | None = None
    ) -> dict[FoonObject, bool]:
        """:meth:`reachability` as ``{object: reachable}``."""
        return self.reachability(goals, options=options).answers

    def missing(
        self,
        goal: GoalLike | Sequence[GoalLike],
        *,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> Missing:
        """The fewest objects to add to the kitchen so ``goal`` can be made (proven minimal), then
        the best tree by the objective; several goals: the fewest for the whole meal."""
        solver = self.options(options, **settings)
        target: int | tuple[int, ...]
        if isinstance(goal, str | int | FoonObject):
            target = self.object_id(goal)
        else:
            target = tuple(dict.fromkeys(self.object_id(g) for g in goal))
        view = partial(self.judging_problem, solver)
        return Missing(self, matching.missing(self.solving_problem(solver), view, target, solver))

    def query(
        self,
        program: str,
        *,
        goal: GoalLike | None = None,
        encodings: Sequence[str] = (),
        name: str = "<program>",
        goal_nodes: GoalLike | Sequence[GoalLike] | None = None,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> QueryResult:
        """Run an ASP ``program`` (text) with the facts (``goal_node/2`` for ``goal_nodes``, default
        the goals file's entries) and ``encodings``; shown atoms come back with ids decoded."""
        request = Options.of(options, **settings)
        nodes = self.file_goals() if goal_nodes is None else self.goal_ids(goal_nodes)
        gid = None if goal is None else self.object_id(goal)
        program += matching.substitute_facts(self.problem, self.projection, request)
        return queries.query(self.problem, (name, program), nodes, gid, encodings, request.models, request.time_limit)

    def batch(
        self,
        goals: GoalLike | Sequence[GoalLike] | None = "all-objects",
        output: str | Path | None = None,
        *,
        methods: Sequence[str] = ("asp",),
        workers: int | str = 1,
        resume: bool = False,
        progress: bool | None = False,
        fsync: bool = True,
        scheduler: str | None = None,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> BatchRun:
        """Many goals x methods into a resumable JSON-lines file (``output``; None keeps results in
        memory).  ``workers``: processes, or ``"auto"`` (this process, then a pool on every usable
        core once the batch has run 5 s; a script using a pool needs the ``__main__`` guard)."""
        request = Options.of(options, **settings)
        solver = self.options(request)
        problem = self.solving_problem(solver)
        spec = BatchSpec(problem, list(dict.fromkeys(methods)), solver, request.grounding, request.shortcuts)
        executor = cluster.executor(scheduler) if scheduler else None
        count = workers_count(workers)
        outcome = batch_run.run_batch(spec, self.goal_ids(goals), output, resume, count, progress, fsync, executor)
        return BatchRun(self, outcome)

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
        """The schedule with the proven-minimal makespan of each goal's best tree (``joint``: tree
        and schedule chosen together) on ``spec``'s agents, or on ``agents`` (``"arm=2,human=1"``,
        default one robot) with the ``durations``, ``capabilities`` and ``resources`` files.  One
        goal gives a :class:`Schedule`, several a list; ``together=True``: one schedule of a meal."""
        solver = self.options(options, **settings)
        chosen = make_spec(spec, agents, durations, capabilities, resources)
        jobs = matching.jobs(self.goal_ids(goals), together)
        found = list(self.schedule_iter(jobs, chosen, solver, joint=joint, encoding=encoding))
        return found[0] if together or _one(goals) else found

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
        """:meth:`schedule` goal after goal; a tuple of ids is a meal.  ``progress``: called as each
        goal's schedules improve, with what :func:`foon2asp.schedule.schedule` reports and ``goal``."""
        solver = self._solver(options)
        trees = self.solve_iter(goal_ids, "asp", solver)
        yield from schedule_trees(trees, spec or ScheduleSpec(), solver, joint, encoding, progress)

    def check_schedules(
        self, path: str | Path, spec: ScheduleSpec | None = None, options: Options | None = None
    ) -> list[ScheduleVerdict]:
        """Judge each schedule of a ``schedule --format json`` file on ``spec``'s agents (default one
        robot, every unit 1 s): the first violation per schedule (precedence, one unit per agent at a
        time, capabilities, durations, resources, the tree's validity)."""
        return check_schedule_file(self.problem, partial(self.judging_problem, options), path, spec or ScheduleSpec())


def _one(goals: object) -> bool:
    """Does ``goals`` name one goal (the answer is one value, not a list)?"""
    return isinstance(goals, str | int | FoonObject) and goals not in ("all", "all-objects")
