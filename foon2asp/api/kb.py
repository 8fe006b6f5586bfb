"""The knowledge base: a FOON with its kitchen, goals, motion success rates and utensils, ready to answer.

Every answer takes a request as ``options=`` (:class:`foon2asp.api.Options`) and/or as its
keywords (:meth:`foon2asp.api.Options.of`).  Goals, goals files, tree files and substitutes are
read as ``load``'s level, normalisation and synonyms compare objects (``projection``)."""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import Any

from foon2asp import methods
from foon2asp.analysis import check as check_mod
from foon2asp.analysis import compare as compare_mod
from foon2asp.analysis import queries
from foon2asp.api import results
from foon2asp.api.request import Options, jobs, one_goal, schedule_request, workers_count
from foon2asp.api.schedules import ScheduleVerdict, check_schedule_file
from foon2asp.asp.constraints import unknown_names
from foon2asp.asp.facts import facts as facts_text
from foon2asp.asp.options import AspOptions
from foon2asp.asp.substitute_facts import report as report_substitutions
from foon2asp.asp.substitute_facts import substitute_facts
from foon2asp.batch.pool import BatchSpec, dask_executor
from foon2asp.batch.results_file import run_batch
from foon2asp.errors import InputError
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.loaders import Dataset, read_goals
from foon2asp.foon.matching import Projection
from foon2asp.foon.model import FoonObject
from foon2asp.foon.motioncost import MotionCosts, motion_key, unit_weights, unscaled
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import Substitute, candidates, substituted_kitchen, with_substitutes
from foon2asp.foon.treefiles import TreeFile, TreeUnit, read_trees
from foon2asp.methods.runner import solve_goals
from foon2asp.outcomes import MealRow, QueryResult
from foon2asp.schedule import DEFAULT_ENCODING, ScheduleSpec
from foon2asp.tree.tasktree import meal_of
from foon2asp.tree.validate import bounds_proof

#: a goal as the API takes it: a label, an object's text, ``"#ID"``, an object id or a FoonObject
GoalLike = str | int | FoonObject
#: one goal, several, or None (the goals file's)
Goals = GoalLike | Sequence[GoalLike] | None
#: goal ids to answer one by one; a tuple of ids is a meal (one tree making all of them)
Jobs = Sequence[int | tuple[int, ...]]
#: a request, or the solver options :meth:`KnowledgeBase.options` made of one
Request = Options | AspOptions | None


@dataclass
class KnowledgeBase:
    """A FOON with its kitchen, goals, motion success rates and utensils, ready to answer."""

    data: Dataset
    problem: Problem
    #: one-line warnings about the input (skipped units, motions without a rate, files not found, ...)
    warnings: tuple[str, ...] = ()
    #: how objects are compared (``load``'s ``level``, ``normalize``, ``synonyms``; foon2asp.foon.matching)
    projection: Projection = field(default_factory=Projection)
    #: the problems answers are found and judged on, made so far
    _views: dict = field(default_factory=dict, init=False, repr=False)

    @property
    def goals(self) -> list[FoonObject]:
        """The entries of the goals file, in file order."""
        return [obj for obj, _ in self.data.goals]

    def objects(self, label: str | None = None) -> list[FoonObject]:
        """Every FOON object with ``label`` (all objects when None), in id order."""
        return list(self.problem.objects) if label is None else self.problem.foon.by_label(label)

    def find_objects(
        self, query: str | None = None, only: str | None = None, options: Options | None = None
    ) -> list[int]:
        """Ids of the objects ``query`` names; ``only``: ``produced``, ``kitchen`` or ``derivable``."""
        table = self.substitutes(options)
        problem = with_substitutes(self.problem, table) if only == "derivable" and table else self.problem
        return goals_mod.find_objects(problem, query, only)

    def object_info(self, goal: GoalLike) -> dict:
        """One object as a goals file lists it (``{"id", "text", "label", ..., "producers"}``), with
        ``"joined"``: the texts of the objects it stands for when the comparison joined several."""
        oid = self.object_id(goal)
        info = goals_mod.object_info(self.problem, oid)
        texts = self.projection.sources.get(self.problem.objects[oid], [])
        if len(texts) > 1:
            info["joined"] = list(texts)
        return info

    def object_id(self, goal: GoalLike) -> int:
        """The object id of a goal given as a label, an object's text, ``#ID``, an id or an object."""
        if isinstance(goal, FoonObject):
            return goals_mod.goal_id(self.problem, self.projection.object(goal))
        if isinstance(goal, int):
            if not 0 <= goal < len(self.problem.objects):
                raise InputError(f"no object #{goal}")
            return goal
        text = goal.strip()
        if not self.projection.identity and not text.startswith("#"):
            parsed = goals_mod.parse_object_text(text)
            if parsed is not None:
                found = self.problem.foon.object_ids.get(self.projection.object(parsed))
                if found is not None:
                    return found
            if parsed is None or parsed == FoonObject(parsed.label):  # a label, spelled as the comparison does
                goal = self.projection.label(text)
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

    def select_goals(self, goal: Sequence[str] = (), goals: str | Path | None = None) -> list[int]:
        """The goals a request names: each of ``goal`` in order, then ``goals`` (a goals file,
        ``"all"`` or ``"all-objects"``); neither: the goals file's entries, else an error."""
        name = None if goals is None else str(goals)
        if self.projection.identity:
            return goals_mod.resolve(self.data, self.problem, tuple(goal), name)
        named = [self.object_id(g) for g in goal]
        if name is None and named:
            return named
        if name in (None, "all", "all-objects"):
            return named + goals_mod.resolve(self.data, self.problem, (), name)
        seen = self.projection.object
        from_file = [goals_mod.goal_id(self.problem, seen(o), name, n) for o, n in read_goals(name)]
        if not from_file:
            raise InputError("the goals file lists no goal", name)
        return named + from_file

    def file_goals(self) -> list[int]:
        """The ids of the goals file's entries (none without a goals file)."""
        path = self.data.paths.get("goals")
        return [goals_mod.goal_id(self.problem, obj, path, line) for obj, line in self.data.goals]

    def facts(
        self, goal_nodes: Iterable[int] | None = None, goals: Iterable[int] = (), options: Options | None = None
    ) -> str:
        """The FOON, kitchen and goals as ASP facts: ``goal_node/2`` for ``goal_nodes`` (default: the
        goals file's), ``goal/1`` for ``goals``, with substitutes ``substitute/3`` (docs/vocabulary.md)."""
        nodes = self.file_goals() if goal_nodes is None else list(goal_nodes)
        text = facts_text(self.problem, goal_nodes=nodes) + "".join(f"goal({g}).\n" for g in goals)
        return text + self._substitute_facts(options)

    @property
    def joined(self) -> dict[str, list[str]]:
        """The spellings joined by ``normalize``/``synonyms``: first spelling -> every spelling."""
        return {first: list(every) for first, every in self.projection.texts_joined.items()}

    def project_tree(self, tree: TreeFile) -> TreeFile:
        """A tree read from a file, its units and goal as this knowledge base's level sees them."""
        seen = self.projection
        if seen.identity:
            return tree
        units = [TreeUnit(seen.unit(tu.unit), tu.step, tu.line) for tu in tree.units]
        return replace(tree, units=units, goal=None if tree.goal is None else seen.object(tree.goal))

    def substitutes(self, options: Options | None) -> tuple[Substitute, ...]:
        """The substitutes of a request, spelled as this knowledge base spells labels."""
        if options is None or options.substitutes is None:
            return ()
        return self.projection.substitutes(options.substitute_table())

    def _substitute_facts(self, options: Options | None) -> str:
        table = self.substitutes(options)
        if not table:
            return ""
        return substitute_facts(self.problem, table, limit=options.max_substitutions if options else None)

    def options_and_warnings(self, options: Request = None, **settings: Any) -> tuple[AspOptions, list[str]]:
        """The solver options of a request (:meth:`options`) and the warnings about its names."""
        if isinstance(options, AspOptions):
            if settings:
                raise TypeError(f"settings {', '.join(settings)} apply to Options, not to solver options")
            return options, []
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

    def options(self, options: Request = None, **settings: Any) -> AspOptions:
        """The solver options of a request: names checked, programs read, motion costs as weights
        (solver options given already: themselves)."""
        return self.options_and_warnings(options, **settings)[0]

    def solving_problem(self, solver: AspOptions) -> Problem:
        """The problem answers with ``solver`` are found on (with its motion costs: measures include ``cost``)."""
        weights = solver.motion_costs
        if weights is None:
            return self.problem
        key = frozenset(weights.items())
        if key not in self._views:
            problem = self._views[key] = copy.copy(self.problem)  # what it caches does not depend on the costs
            problem.motion_costs = MotionCosts({motion_key(m): unscaled(w) for m, w in weights.items()})
        return self._views[key]

    def judging_problem(self, solver: AspOptions | Options | None, goals: Iterable[int] = ()) -> Problem:
        """The problem a tree is judged on: :meth:`solving_problem`, where with substitutes every
        object one can stand in for (but ``goals``) is a kitchen item."""
        if not isinstance(solver, AspOptions):
            solver = AspOptions(substitutes=self.substitutes(solver))
        problem, table = self.solving_problem(solver), solver.substitutes
        if not table:
            return problem
        key = (None if solver.motion_costs is None else frozenset(solver.motion_costs.items()), table)
        if key not in self._views:
            self._views[key] = ([c.needed for c in candidates(problem, table)], {})
        needed, made = self._views[key]
        skip = frozenset(goals).intersection(needed)
        if skip not in made:
            made[skip] = substituted_kitchen(problem, [n for n in needed if n not in skip])
        return made[skip]

    def solve_iter(self, goal_ids: Jobs, method: str = "asp", options: Request = None) -> Iterator[results.Tree]:
        """Trees for ``goal_ids`` one after another (a tuple of ids: a meal)."""
        given = options.grounding if isinstance(options, Options) else "auto"
        grounding = "whole" if given == "auto" else given  # auto: one grounding for the goals asked
        solver = self.options(options)
        if methods.get(method).kind != "asp" and solver.programs:
            raise InputError(f"constraints apply to ASP methods only; {method!r} is a search baseline")
        for raw in solve_goals(self.solving_problem(solver), goal_ids, method, solver, grounding):
            yield results.Tree(self, raw)

    def solve(
        self, goals: Goals = None, *, method: str = "asp", together: bool = False, **settings: Any
    ) -> results.Tree | list[results.Tree]:
        """The best task tree for a goal, or a list for several (also ``"all"``, ``"all-objects"``);
        ``together``: one tree that makes every goal (a meal; shared units count once)."""
        given = settings.pop("options", None)
        request = self.options(given, **settings) if isinstance(given, AspOptions) else Options.of(given, **settings)
        trees = list(self.solve_iter(jobs(self.goal_ids(goals), together), method, request))
        return trees[0] if together or one_goal(goals) else trees

    def check(
        self,
        tree: results.Tree | str | Path,
        goal: Goals = None,
        optimum: bool = True,
        goals: Sequence[GoalLike] | str | Path | None = None,
        *,
        strict: bool = False,
        **settings: Any,
    ) -> results.CheckReport | list[results.CheckReport]:
        """Judge a :class:`Tree`, or each tree of a file (a list when it holds several; docs/api.md)."""
        solver = self.options(**settings)
        view = partial(self.judging_problem, solver)
        if isinstance(tree, results.Tree):
            if goal is not None and not isinstance(goal, str | int | FoonObject):
                raise InputError("check a Tree against one goal (its own by default)")
            units = [TreeUnit(self.problem.units[u], i, None) for i, u in enumerate(tree.unit_ids, 1)]
            gid = tree.goal_id if goal is None else self.object_id(goal)
            claim = TreeFile("<tree>", units, tree.goal, tree.method, proven_by=tree.raw.proven_by)
            claim.landmarks, claim.landmark_sets = tree.raw.landmarks, tree.raw.landmark_sets or []
            claim.landmark_cases, claim.derivation_level = tree.raw.landmark_cases, tree.raw.derivation_level
            raw = check_mod.check_tree(view((gid,)), claim, gid)
            raw.goal_source = "the tree's goal" if goal is None else "given"
            reports = [raw]
        else:
            reports = self._check_file(view, tree, goal, goals, strict)
        for r in reports if solver.substitutes else []:
            used = [u for u in dict.fromkeys(r.ids) if u is not None]
            r.substitutions = report_substitutions(self.problem, r.meal, used, solver.substitutes) if r.valid else []
        if optimum and reports:  # a Tree's own goal, a file's trees by meal (one goal: a meal of one)
            key = (lambda r: r.goal) if isinstance(tree, results.Tree) else (lambda r: r.meal)
            meals = list(dict.fromkeys(key(r) for r in reports))
            best = dict(zip(meals, (t.raw for t in self.solve_iter(meals, "asp", solver))))
            for r in reports:
                r.optimum = opt = best[key(r)]
                if opt.proven_by == "bounds":  # its witness, checked without the solver
                    marks, sets = opt.landmarks or [], opt.landmark_sets or []
                    first = solver.objective[0] if solver.objective[0] in ("success", "inputs") else "units"
                    cases, level = opt.landmark_cases, opt.derivation_level
                    why = bounds_proof(view(opt.meal), opt.goal, opt.units, marks, sets, first, cases, level)
                    r.optimum_proof = {"proven_by": "bounds", "verified": why is None, "problem": why}
        found = [results.CheckReport(self, r) for r in reports]
        return found[0] if len(found) == 1 else found

    def _check_file(self, view: Callable, path: str | Path, goal: Goals, goals: Any, strict: bool) -> list:
        """The reports on every tree of a tree file, each judged on ``view(its goals)``."""
        named = [] if goal is None else [goal] if isinstance(goal, str | int | FoonObject) else list(goal)
        same = self.projection.identity
        labels = tuple(g if isinstance(g, str) and same else f"#{self.object_id(g)}" for g in named) or None
        among = None
        if isinstance(goals, str | Path):
            among = self.select_goals((), goals)
        elif goals is not None:
            among = [self.object_id(g) for g in goals]
        files = [self.project_tree(t) for t in read_trees(path, self.problem, strict)]
        reports = check_mod.check_trees(self.data, view(()), files, labels, among)
        for i, r in enumerate(reports):  # a goal a substitute stands in for is judged without it
            judged_on = view(r.meal)
            if judged_on is not view(()):
                reports[i] = check_mod.check_tree(judged_on, r.tree, r.goals or r.goal)
                reports[i].goal_source = r.goal_source
        return reports

    def check_all(self, *args: Any, **kwargs: Any) -> list[results.CheckReport]:
        """:meth:`check` (the same arguments) as a list, whatever the file holds."""
        found = self.check(*args, **kwargs)
        return found if isinstance(found, list) else [found]

    def compare(
        self, goals: Goals = "all", methods: Sequence[str] = compare_mod.DEFAULT_METHODS, **settings: Any
    ) -> results.Comparison:
        """Every method on every goal, each tree judged valid or not, beside the proven optimum."""
        solver = self.options(**settings)
        parts = self.compare_iter(self.goal_ids(goals), methods, solver)
        return results.Comparison(self, [row for part in parts for row in part.raw])

    def compare_iter(
        self, goal_ids: Sequence[int], methods: Sequence[str] = compare_mod.DEFAULT_METHODS, options: Request = None
    ) -> Iterator[results.Comparison]:
        """:meth:`compare` goal by goal: a one-row :class:`Comparison` as soon as each goal is done."""
        solver = self.options(options)
        for row in compare_mod.compare_iter(self.solving_problem(solver), list(goal_ids), list(methods), solver):
            yield results.Comparison(self, [row])

    def compare_meal(self, goals: Sequence[GoalLike], method: str = "asp", **settings: Any) -> MealRow:
        """The meal's optimal tree (all ``goals`` at once) beside each goal's own optimum."""
        solver = self.options(**settings)
        return compare_mod.compare_meal(self.solving_problem(solver), self.goal_ids(goals), method, solver)

    def reachability(self, goals: Goals = "all", *, options: Options | None = None) -> results.Reachability:
        """For each goal: can it be made from the kitchen at all (with substitutes: when they may stand in)?"""
        ids = self.goal_ids(goals)
        base = self.judging_problem(options)
        answers = queries.reachable(base, ids)
        for goal in ids:  # a goal a substitute stands in for is not had by substituting it
            judged_on = self.judging_problem(options, (goal,))
            if judged_on is not base:
                answers[goal] = queries.reachable(judged_on, [goal])[goal]
        return results.Reachability(self, answers)

    def reachable(self, goals: Goals = "all", *, options: Options | None = None) -> dict[FoonObject, bool]:
        """:meth:`reachability` as ``{object: reachable}``."""
        return self.reachability(goals, options=options).answers

    def missing(self, goal: GoalLike | Sequence[GoalLike], **settings: Any) -> results.Missing:
        """The fewest objects to add to the kitchen so ``goal`` (several: the meal) can be made, then the best tree."""
        solver = self.options(**settings)
        target: int | tuple[int, ...]
        if isinstance(goal, str | int | FoonObject):
            target = self.object_id(goal)
        else:
            target = tuple(dict.fromkeys(self.object_id(g) for g in goal))
        meal = meal_of(target)
        problem = judged_on = self.solving_problem(solver)
        if solver.substitutes:  # the fewest substitutes when nothing need be added
            lenient = with_substitutes(problem, solver.substitutes)
            judged_on = lenient if all(g in lenient.derivable for g in meal) else self.judging_problem(solver, meal)
        answer = queries.missing(judged_on, target, solver)
        if solver.substitutes:
            bought = substituted_kitchen(problem, answer.missing)  # the kitchen with what is added
            answer.substitutions = report_substitutions(bought, meal, answer.units, solver.substitutes)
        return results.Missing(self, answer)

    def query(
        self,
        program: str,
        *,
        goal: GoalLike | None = None,
        encodings: Sequence[str] = (),
        name: str = "<program>",
        goal_nodes: Goals = None,
        **settings: Any,
    ) -> QueryResult:
        """Run an ASP ``program`` (text) with the facts (:meth:`facts`) and ``encodings``; shown atoms come back decoded."""
        request = Options.of(settings.pop("options", None), **settings)
        nodes = self.file_goals() if goal_nodes is None else self.goal_ids(goal_nodes)
        gid = None if goal is None else self.object_id(goal)
        program += self._substitute_facts(request)
        return queries.query(self.problem, (name, program), nodes, gid, encodings, request.models, request.time_limit)

    def batch(
        self,
        goals: Goals = "all-objects",
        output: str | Path | None = None,
        *,
        methods: Sequence[str] = ("asp",),
        workers: int | str = 1,
        resume: bool = False,
        progress: bool | None = False,
        fsync: bool = True,
        scheduler: str | None = None,
        **settings: Any,
    ) -> results.BatchRun:
        """Many goals x methods into a resumable JSON-lines file (``output``; None: in memory; docs/batch.md)."""
        request = Options.of(settings.pop("options", None), **settings)
        solver = self.options(request)
        spec = BatchSpec(
            self.solving_problem(solver), list(dict.fromkeys(methods)), solver, request.grounding, request.shortcuts
        )
        executor = dask_executor(scheduler) if scheduler else None
        count = workers_count(workers)
        outcome = run_batch(spec, self.goal_ids(goals), output, resume, count, progress, fsync, executor)
        return results.BatchRun(self, outcome)

    def schedule(
        self, goals: Goals = None, spec: ScheduleSpec | None = None, *, together: bool = False, **settings: Any
    ) -> results.Schedule | list[results.Schedule]:
        """The schedule with the proven-minimal makespan of each goal's best tree (docs/api.md)."""
        request = schedule_request(spec, settings)
        goal_ids = jobs(self.goal_ids(goals), together)
        found = list(self.schedule_iter(goal_ids, options=self.options(**settings), **request))
        return found[0] if together or one_goal(goals) else found

    def schedule_iter(
        self,
        goal_ids: Jobs,
        spec: ScheduleSpec | None = None,
        options: Request = None,
        *,
        joint: bool = False,
        encoding: str = DEFAULT_ENCODING,
        progress: Callable[[dict], None] | None = None,
    ) -> Iterator[results.Schedule]:
        """:meth:`schedule` goal after goal (docs/api.md)."""
        solver = self.options(options)
        trees = self.solve_iter(goal_ids, "asp", solver)
        yield from results.schedule_trees(trees, solver, spec or ScheduleSpec(), joint, encoding, progress)

    def check_schedules(
        self, path: str | Path, spec: ScheduleSpec | None = None, options: Options | None = None
    ) -> list[ScheduleVerdict]:
        """Judge each schedule of a ``schedule --format json`` file on ``spec``'s agents (default one robot)."""
        return check_schedule_file(self.problem, partial(self.judging_problem, options), path, spec or ScheduleSpec())
