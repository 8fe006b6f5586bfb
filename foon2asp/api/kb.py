"""The knowledge base: a FOON with its kitchen, goals, motion success rates and utensils, ready to answer.

Every answer takes the request's settings as ``options=`` (:class:`foon2asp.api.Options`) and/or
as keywords (:class:`foon2asp.api.options.Settings`); goals are named as :data:`GoalLike`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import Unpack

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
    #: one-line warnings about the input (skipped units, motions without a rate, unknown names, ...)
    warnings: list[str] = field(default_factory=list)
    #: how objects are compared (``load``'s ``level``, ``normalize``, ``synonyms``; foon2asp.foon.matching)
    projection: Projection = field(default_factory=Projection)
    #: substitutes -> (the objects they stand in for, the problems trees are judged on)
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
        (``producers``: how many units make it); a list of these is a goals file.  With ``"joined"``
        the texts of the objects it stands for when the comparison (level, normalize, synonyms)
        joined several."""
        return matching.object_info(self.problem, self.projection, self.object_id(goal))

    def object_id(self, goal: GoalLike) -> int:
        """The object id of a goal given as a label, an object's text, ``#ID``, an id or an object."""
        return matching.object_id(self.data, self.problem, self.projection, goal)

    def goal_ids(self, goals: GoalLike | Iterable[GoalLike] | None) -> list[int]:
        """Object ids for ``goals``: one goal, several, ``"all"`` (the goals file) or ``"all-objects"``."""
        return matching.goal_ids(self.data, self.problem, self.projection, goals)

    def select_goals(self, goal: Sequence[str] = (), goals: str | Path | None = None) -> list[int]:
        """The goals a request names: each of ``goal`` (labels, texts or ``#ID``) in order, then
        ``goals``: a goals file, ``"all"`` (the goals file's entries) or ``"all-objects"``; neither:
        the goals file's entries.  Naming nothing at all is an error."""
        return matching.select_goals(self.data, self.problem, self.projection, goal, goals)

    def file_goals(self) -> list[int]:
        """The ids of the goals file's entries (none without a goals file)."""
        path = self.data.paths.get("goals")
        return [goals_mod.goal_id(self.problem, obj, path, line) for obj, line in self.data.goals]

    def facts(
        self, goal_nodes: Iterable[int] | None = None, goals: Iterable[int] = (), options: Options | None = None
    ) -> str:
        """The FOON, kitchen and goals as ASP facts: ``goal_node/2`` for ``goal_nodes`` (default:
        the goals file's entries), ``goal/1`` for each of ``goals`` (docs/vocabulary.md); with
        ``options.substitutes`` also ``substitute(N,K,C)`` (docs/vocabulary.md)."""
        nodes = self.file_goals() if goal_nodes is None else list(goal_nodes)
        text = facts_text(self.problem, goal_nodes=nodes) + "".join(f"goal({g}).\n" for g in goals)
        return text + matching.substitute_facts(self.problem, self.projection, options)

    @property
    def joined(self) -> dict[str, list[str]]:
        """The spellings joined by ``normalize``/``synonyms``: first spelling -> every spelling
        (first first); only texts spelled more than one way."""
        return matching.joined(self.projection)

    def substitutes(self, options: Options | None) -> tuple[Substitute, ...]:
        """The substitutes of a request, spelled as this knowledge base spells labels."""
        return matching.substitutes(self.projection, options)

    def judging_problem(self, solver: AspOptions | Options | None, goals: Iterable[int] = ()) -> Problem:
        """The problem a tree is judged on: with substitutes, every object one can stand in
        for (but ``goals``) is a kitchen item (foon2asp.asp.substitutes.validate_with)."""
        table = solver.substitutes if isinstance(solver, AspOptions) else self.substitutes(solver)
        return matching.judging_problem(self.problem, self._views, table, goals)

    def project_tree(self, tree: TreeFile) -> TreeFile:
        """A tree read from a file, its units and goal as this knowledge base's level sees them."""
        return matching.project_tree(self.projection, tree)

    def options(self, options: Options | None = None, **settings: Unpack[Settings]) -> AspOptions:
        """The solver options an answer uses (defaults: see :mod:`foon2asp.asp.options`): names
        checked, constraint programs read; constraint names no motion or label matches are warned about.

        The request's motion-cost table becomes the solver's integer weights (hundredths) and the
        problem's table (:attr:`Problem.motion_costs`: every tree's measures then include ``cost``);
        the motions of the FOON the table lacks (each costs 1) are named in one warning."""
        request = Options.of(options, **settings)
        self.warnings.extend(unknown_names(self.problem, request.constraints))
        solver = request.solver()
        if solver.substitutes:  # spelled as the FOON's labels are at this level
            solver = replace(solver, substitutes=self.projection.substitutes(solver.substitutes))
        table = request.motion_table()
        self.problem.motion_costs = table
        if table is None:
            return solver
        weights, warning = unit_weights(table, [u.motion for u in self.problem.units])
        if warning is not None:
            self.warnings.append(warning)
        return replace(solver, motion_costs=weights)

    # -- answers ------------------------------------------------------------

    def solve_iter(
        self,
        goal_ids: Sequence[int | tuple[int, ...]],
        method: str = "asp",
        options: Options | AspOptions | None = None,
    ) -> Iterator[Tree]:
        """Trees for ``goal_ids`` one after another (the path every command takes); an
        element that is a tuple of ids is a meal: one tree that makes all of them.
        ``options``: a request, or the solver options :meth:`options` made of one."""
        solver = options if isinstance(options, AspOptions) else self.options(options)
        kind = methods.get(method).kind
        if kind != "asp" and solver.programs:
            raise InputError(f"constraints apply to ASP methods only; {method!r} is a search baseline")
        for raw in solve_goals(self.problem, goal_ids, method, solver):
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
        """The best task tree for a goal (a :class:`Tree`), or for each of several goals (a list).

        ``together=True``: one tree that makes every goal (a meal; units shared
        between dishes count once), proven optimal like a single goal's.

        ``goals``: a label, an object's text, ``"#ID"``, an object, a list of
        these, or ``"all"`` / ``"all-objects"`` (a list).  ``objective``:
        ``units`` (default), ``success``, ``inputs``, ``depth`` or a
        lexicographic list.  The constraint keywords match the CLI flags.
        """
        solver = self.options(options, **settings)
        ids = self.goal_ids(goals)
        if together:
            return next(self.solve_iter([tuple(dict.fromkeys(ids))], method, solver))
        trees = list(self.solve_iter(ids, method, solver))
        single = isinstance(goals, str | int | FoonObject) and goals not in ("all", "all-objects")
        return trees[0] if single else trees

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
        """Judge a tree: a :class:`Tree`, or a file (FOON text in either dialect, FOON JSON,
        foon2asp JSON, the unit-list JSON of generated trees, or a plan as Fast Downward writes
        it for ``export pddl``).

        A :class:`Tree`, or a file holding one tree, gives one report; a file holding several
        gives a list, one per tree (:meth:`check_all`: always a list).
        ``goal``: the goal (several: a meal). Otherwise the goal of a tree in a file is
        the one of ``goals`` (a goals file or a list) the tree makes, else the one the
        file names (a JSON result, or the ``# task tree for ...`` line ``solve --format
        foon`` writes), else the tree's only product no unit of it needs.
        With ``optimum`` the ASP optimum is solved with ``options`` for each goal (a meal's for a meal).
        Units of a unit list that are skipped or merged are warned about (:attr:`warnings`; an
        error with ``strict``).  A tree file judged without a FOON: :func:`foon2asp.api.check_tree`.
        """
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
            self.warnings.extend(dict.fromkeys(w for r in reports for w in r.tree.warnings))
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

    def check_all(
        self,
        tree: Tree | str | Path,
        goal: GoalLike | Sequence[GoalLike] | None = None,
        optimum: bool = True,
        goals: Sequence[GoalLike] | str | Path | None = None,
        *,
        strict: bool = False,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> list[CheckReport]:
        """:meth:`check` as a list, whatever the file holds (one report per tree)."""
        found = self.check(tree, goal, optimum, goals, strict=strict, options=options, **settings)
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
        solver = options if isinstance(options, AspOptions) else self.options(options)
        for row in compare_mod.compare_iter(self.problem, list(goal_ids), list(methods), solver):
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
        return compare_mod.compare_meal(self.problem, self.goal_ids(goals), method, solver)

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
        the best tree by ``objective`` (``units``, ``success``, ``inputs`` or a lexicographic list).

        Several goals: the fewest objects for the whole meal (one tree making all of them).
        """
        solver = self.options(options, **settings)
        target: int | tuple[int, ...]
        if isinstance(goal, str | int | FoonObject):
            target = self.object_id(goal)
        else:
            target = tuple(dict.fromkeys(self.object_id(g) for g in goal))
        return Missing(self, matching.missing(self.problem, partial(self.judging_problem, solver), target, solver))

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
        """Run an ASP ``program`` (text) with the facts; shown atoms come back with ids decoded.

        ``goal_nodes`` (default: the goals file's entries) become ``goal_node/2`` facts;
        ``encodings`` are loaded with the ones they need (``reachable`` needs ``tree``).
        ``models`` (0: all) and ``time_limit`` come from ``options`` or the keywords.
        With a ``#show`` of its own in ``program`` only what it shows is returned;
        ``warnings`` names atoms the program uses that no rule or fact defines.
        With ``substitutes`` the facts include ``substitute(N,K,C)`` (and ``max_substitutions(M)``).
        """
        request = Options.of(options, **settings)
        nodes = self.file_goals() if goal_nodes is None else self.goal_ids(goal_nodes)
        gid = None if goal is None else self.object_id(goal)
        # substitute/3 with substitutes (encodings: "substitutes")
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
        """Many goals x methods into a resumable JSON-lines file (``output``; None keeps results in memory).

        ``grounding``: ``"whole"``, ``"per-goal"`` or ``"auto"`` (chosen from the FOON and the goals by
        :func:`foon2asp.methods.parts.choose_grounding`; the run's ``grounding`` and ``grounding_reason`` say which).
        ``workers``: processes, or ``"auto"`` (this process, then a pool on every usable core once the batch has
        run 5 s; the run's ``workers`` says how many ran; a script using a pool needs the usual
        ``if __name__ == "__main__":`` guard).
        """
        request = Options.of(options, **settings)
        solver = self.options(request)
        spec = BatchSpec(self.problem, list(dict.fromkeys(methods)), solver, request.grounding, request.shortcuts)
        executor = None
        if scheduler:
            executor = cluster.executor(scheduler)
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
        trees = self.solve_iter(goal_ids, "asp", solver)
        yield from schedule_trees(trees, spec or ScheduleSpec(), solver, joint, encoding, progress)

    def check_schedules(
        self, path: str | Path, spec: ScheduleSpec | None = None, options: Options | None = None
    ) -> list[ScheduleVerdict]:
        """Judge each schedule of a ``schedule --format json`` file on ``spec``'s agents (default one
        robot, every unit 1 s): the first violation of precedence, one unit per agent at a time,
        capabilities, durations, resources or the tree's validity, per schedule; with the
        substitutes of ``options`` what they stand in for is in the kitchen."""
        return check_schedule_file(self.problem, partial(self.judging_problem, options), path, spec or ScheduleSpec())
