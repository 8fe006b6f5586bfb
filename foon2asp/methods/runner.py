"""The goal runner: the one path from goals to trees, for every registered method.

:class:`GoalRunner` answers goal after goal for one method of
:mod:`foon2asp.methods.registry`; :func:`solve_goals` is the entry point that
``solve``, ``compare``, ``check``, ``batch`` and the library take, and
:func:`runner` the runner of one method for a caller that asks goal by goal.  A
search baseline is built once on the whole problem and asked goal by goal; an
ASP method is solved around the solver, in one of two groundings, with shortcuts
and pruning:

* ``whole`` -- one grounding for all goals (:class:`~foon2asp.asp.session.Session`,
  the goal switched as an external), restricted to the *viable* units (units
  that fire in the kitchen's least fixpoint).  No other unit can ever be a
  candidate of a tree, so the answers do not change.
* ``per-goal`` -- a small grounding per goal holding only the goal's
  *relevant part*: the viable producers of the goal, of their required
  inputs, and so on (the encoding's ``candidate/1`` units), with the kitchen
  items among their inputs.  The cost of a query then depends on the size of
  the goal's part, not of the FOON; use it for very large FOONs.
* shortcuts (both groundings, on by default) that answer without the solver when
  the answer is forced:

  - the goal is not derivable from the kitchen: ``unreachable``;
  - every object of the relevant part has exactly one viable producer: the
    whole part is the only tree (each of its units is needed and together
    they fire), so it is the optimum of every objective that only adds
    non-negative weights per used unit (:data:`MONOTONE`, weighed by
    :data:`foon2asp.tree.weights.UNIT_WEIGHTS`).

  - the lower bound of :mod:`foon2asp.methods.bounds` meets its upper bound:
    the *bounds tree* (a valid tree built without the solver) is optimal
    (``"shortcut": "bounds"``);
  - otherwise the branch and bound of :mod:`foon2asp.methods.exact` finds the
    optimum and the canonical tree on the goal's part
    (``"shortcut": "branch-and-bound"``), unless it runs out of nodes
    (:attr:`GoalRunner.search_nodes`);
  - otherwise MaxSAT (:mod:`foon2asp.maxsat.trees`) proves the optimum on the goal's
    part (dominated units left out) and walks on to the smallest optimal tree
    (``"shortcut": "maxsat"``); cut short by the time limit or the gap,
    the answer is the bounds tree, ``feasible``, with the lower bound MaxSAT proved;
  - depth first, then one of those objectives (nothing else asked): MaxSAT among the
    trees within the goal's level (:func:`foon2asp.methods.proofs.by_maxsat_depth`)
    instead of the rounds of the depth driver.

  Shortcuts are taken only for plain optimisation (no user programs, extra
  encodings, depth bounds, human steps, alternatives or greedy heuristics);
  anything else goes to the solver.  They are exact also when the caller
  restricts the units (``options.units``, as :func:`solve_goals` does), as
  long as the goal's relevant part lies inside them.
* pruning: a goal with choice that neither the bounds, the branch and bound nor
  MaxSAT decide (:attr:`GoalRunner.maxsat` off) is solved on its part without the units no optimal tree uses, the
  landmark units required (:meth:`~foon2asp.methods.bounds.Bounds.keep`), on a
  small grounding.

*The canonical tree* (the same from every path: solve, compare, check,
batch with any grounding, workers or shortcuts, the library): for the
objectives the bounds handle, the bounds tree whenever it is optimal -- found
by the shortcut, or by the solver proving an optimum of the same cost --
else the lexicographically smallest optimal tree
(:mod:`foon2asp.asp.canonical`).
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Iterator
from dataclasses import replace
from functools import cached_property

from foon2asp.asp.dominance import Dominators
from foon2asp.asp.objectives import ranked
from foon2asp.asp.options import AspOptions
from foon2asp.asp.session import Session
from foon2asp.asp.substitutes import prepare as with_substitutes
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem, walk_back
from foon2asp.methods import proofs
from foon2asp.methods.bounds import Bounds, weights
from foon2asp.methods.bounds import supports as bounds_supports
from foon2asp.methods.exact import NODE_LIMIT, canonical_tree, hopeless
from foon2asp.methods.registry import Runner, check_substitutes, effective_options, get
from foon2asp.tree.gap import settle
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, meal_of, measures
from foon2asp.tree.weights import UNIT_WEIGHTS

GROUNDINGS = ("whole", "per-goal")

#: FOONs with more viable units than this build a goal's bounds on its part first (Parts.bounds_for)
PART_BOUNDS_MIN = 20_000
#: ... when the part is less than 1/PART_BOUNDS_SHARE of them
PART_BOUNDS_SHARE = 4

#: objectives whose cost is a sum of non-negative weights of the used units (the cost
#: term the solver reports for a tree, ``asp_cost``, is :func:`foon2asp.tree.weights.total`)
MONOTONE = frozenset(UNIT_WEIGHTS)


class Parts:
    """Viable units and per-goal relevant parts of one problem (computed once)."""

    def __init__(self, problem: Problem):
        self.problem = problem
        #: units that fire in the kitchen's least fixpoint
        self.viable: frozenset[int] = problem.viable_units
        #: object -> its viable producers
        self.producers: dict[int, list[int]] = problem.viable_producers
        self._bounds: dict[tuple[str, ...], Bounds] = {}
        #: units covered so far by bounds built on goals' parts (Parts.bounds_for)
        self._part_bounds_spent: dict[tuple[str, ...], int] = {}
        self._weights: dict[tuple[str, ...], list[int]] = {}
        self._dominators: dict[tuple[str, ...], Dominators] = {}

    def dominators(self, ranked_objectives: tuple[str, ...]) -> Dominators:
        """The dominated units' dominators (foon2asp.asp.dominance) for these objectives, kept."""
        if ranked_objectives not in self._dominators:
            self._dominators[ranked_objectives] = Dominators(self.problem, ranked_objectives)
        return self._dominators[ranked_objectives]

    def bounds(self, ranked_objectives: tuple[str, ...]) -> Bounds:
        """The bounds (foon2asp.methods.bounds) for these ranked objectives, built once."""
        if ranked_objectives not in self._bounds:
            self._bounds[ranked_objectives] = Bounds(self.problem, ranked_objectives)
        return self._bounds[ranked_objectives]

    def bounds_for(self, ranked_objectives: tuple[str, ...], units: list[int]) -> Bounds:
        """The bounds for a goal whose relevant part is ``units``: built on the part alone while
        that is cheaper than the whole FOON's, then the whole FOON's, built once.

        A goal's bounds depend on its part only (foon2asp.methods.bounds), so both give the
        same answers.  On a large FOON the whole build takes seconds (18 s on 242,241 units)
        and one goal would wait for it; parts are built instead while the units they cover
        add up to less than the FOON's viable units (then the whole build has paid for itself:
        the total work stays within twice the better of the two)."""
        whole = self._bounds.get(ranked_objectives)
        size = len(self.viable)
        if whole is None and size > PART_BOUNDS_MIN and PART_BOUNDS_SHARE * len(units) < size:
            spent = self._part_bounds_spent.get(ranked_objectives, 0) + len(units)
            if spent <= size:
                self._part_bounds_spent[ranked_objectives] = spent
                if ranked_objectives not in self._weights:
                    self._weights[ranked_objectives] = weights(self.problem, ranked_objectives)
                return Bounds(self.problem, ranked_objectives, units, self._weights[ranked_objectives])
        return self.bounds(ranked_objectives)

    @cached_property
    def derivable(self) -> frozenset[int]:
        return self.problem.derivable

    def relevant(self, goal: Goals) -> tuple[list[int], set[int], bool]:
        """``(units, objects, choice)`` of the goal's relevant part (a meal's: all its goals').

        ``units`` are the encoding's candidates for ``goal``, ``objects`` the
        goal and the required inputs reached, ``choice`` whether some object
        has more than one candidate producer.
        """
        units, seen, choice = walk_back(meal_of(goal), self.problem.kitchen, self.producers, self.problem.required)
        return sorted(units), seen, choice


def plain(options: AspOptions) -> bool:
    """May the shortcuts answer for these options (plain optimisation of monotone objectives)?"""
    return (
        not options.driven
        and not options.programs
        and not options.encodings
        and not options.heuristic
        and not options.substitutes
        and all(name in MONOTONE for name in ranked(options))
    )


def _view(problem: Problem, objects: set[int]) -> Problem:
    """``problem`` with the kitchen cut down to ``objects`` (the goal's part)."""
    return problem.with_kitchen(o for o in objects if o in problem.kitchen)


class GoalRunner:
    """The runner of one registered method for many goals (see the module docstring).

    ``options`` are the caller's: every solve of the runner uses them (with the
    method's adjustments, :func:`~foon2asp.methods.registry.effective_options`).
    ``goals``: the goals the runner will be asked, if known; an ASP method then grounds
    only the units a tree for one of them can use (:meth:`Problem.units_for`), unless
    ``options.units`` says otherwise.  ``parts``: the viable units and relevant parts of
    ``problem`` when the caller has them (several runners share them).
    """

    #: MaxSAT (foon2asp.maxsat) proves what the branch and bound leaves, before clingo is asked
    maxsat = True

    def __init__(
        self,
        name: str,
        problem: Problem,
        options: AspOptions,
        grounding: str = "whole",
        shortcuts: bool = True,
        parts: Parts | None = None,
        goals: Iterable[Goals] | None = None,
    ):
        if grounding not in GROUNDINGS:
            raise ValueError(f"unknown grounding {grounding!r}")
        check_substitutes(name, options)  # before anything is solved: a method that cannot honour them refuses
        problem = with_substitutes(problem, options)
        if options.substitutes:  # a goal's part would leave out the kitchen items that stand in
            grounding = "whole"
        method = get(name)
        if goals is not None and method.kind == "asp" and options.units is None:
            # no tree for one of these goals can use another unit
            options = replace(options, units=problem.units_for({g for goal in goals for g in meal_of(goal)}))
        self.name = name
        self.problem = problem
        self.options = options
        self.grounding = grounding
        self.kind = method.kind
        self.parts = parts if parts is not None and parts.problem is problem else Parts(problem)
        self.shortcuts = shortcuts and self.kind == "asp" and plain(self.options)
        #: how each goal was answered: "solver" | "unreachable" | "no-choice" | "bounds" | "branch-and-bound"
        self.counts = {"solver": 0, "unreachable": 0, "no-choice": 0, "bounds": 0, "branch-and-bound": 0, "maxsat": 0}
        #: nodes the branch and bound (foon2asp.methods.exact) may search per goal before the solver is asked
        self.search_nodes = NODE_LIMIT
        self._label: str | None = None
        self._whole: Runner | None = None
        #: units the caller allows (options.units); a goal whose part lies inside them is answered exactly
        self._allowed = None if self.options.units is None else frozenset(self.options.units)
        #: the options the method's sessions use, and the ranked objectives the bounds see
        self._effective = effective_options(name, self.options) if self.kind == "asp" else self.options
        ranked_objectives = ranked(self._effective)
        self._ranked = ranked_objectives
        #: the method's own objectives only add weights of used units (asp-depth's do not)
        self._monotone = all(objective in MONOTONE for objective in ranked_objectives)
        #: the bounds of foon2asp.methods.bounds decide canonical trees and (with shortcuts) answer goals
        self._bounded = self.kind == "asp" and plain(self._effective) and bounds_supports(ranked_objectives)
        #: depth first, then an objective of the bounds, nothing else asked: MaxSAT within the goal's level
        rest = tuple(o for o in self._effective.objective if o != "depth")
        self._depth_first = (
            shortcuts
            and self.kind == "asp"
            and ranked_objectives[:1] == ("depth",)
            and bounds_supports(ranked_objectives[1:])
            and plain(replace(self._effective, objective=rest))
        )
        self._weights: list[int] | None = None
        if self.kind == "asp":
            self._label = self._effective.method
        else:
            assert method.factory is not None, f"search method {name!r} has no factory"
            self._whole = method.factory(problem, self.options)

    def _session(self, problem: Problem, units: tuple[int, ...]) -> Session:
        """A session of the method grounding ``units`` of ``problem`` (a view, or the whole problem)."""
        return Session(problem, replace(self._effective, units=units))

    def _whole_runner(self) -> Runner:
        """The one grounding of all viable (or allowed) units, built on first use."""
        if self._whole is None:
            units = self.options.units
            if units is None:
                units = tuple(sorted(self.parts.viable))
            self._whole = self._session(self.problem, tuple(units)).solve
        return self._whole

    def _solve(self, goal: Goals, floor: int | None = None) -> TaskTree:
        """The solver's tree (a search baseline's answer); ``floor``: a lower bound on the first
        objective's weight from the landmarks (an unproven answer reports the better bound)."""
        self.counts["solver"] += 1
        if self.kind != "asp" or self.grounding == "whole":
            run = self._whole_runner()
            tree = run(goal) if floor is None else run(goal, floor=floor)  # type: ignore[call-arg]
        else:
            units, objects, _ = self.parts.relevant(goal)
            if self._allowed is not None:
                units = [u for u in units if u in self._allowed]
            tree = self._session(_view(self.problem, objects), tuple(units)).solve(goal, floor=floor)
        self._label = tree.method
        return tree

    def _solve_pruned(self, goal: int, units: list[int], objects: set[int], bounds: Bounds) -> TaskTree:
        """Solve on the goal's part without the units no optimal tree uses, landmark units required."""
        keep = bounds.keep(goal, units)
        landmarks = bounds.landmarks(goal)
        canonical = keep == units and not landmarks  # nothing pruned: this is the goal's canonical session
        if not canonical and self.grounding == "whole" and 2 * len(keep) > len(self.parts.viable):
            return self._solve(goal)  # the pruned part is most of the FOON: the whole grounding is cheaper
        self.counts["solver"] += 1
        view = _view(self.problem, objects)
        session = Session(view, replace(self._effective, units=tuple(keep)), require=landmarks, goal=goal)
        best = bounds.tree(goal) or ()
        tree = session.solve(goal, known=(best, bounds.cost(best)), floor=bounds.first_lower(goal))
        tree.stats["pruned_units"] = len(units) - len(keep)
        return tree

    def _canonical(self, tree: TaskTree, bounds: Bounds, t0: float, search: bool = True) -> TaskTree:
        """The canonical tree in place of an optimal tree from the solver: the bounds tree when
        it is optimal, else the branch and bound's smallest optimal tree when the search
        settles it (``search``: not tried yet for this goal), else the solver's tree (found in
        the goal's canonical session, foon2asp.asp.canonical)."""
        best = bounds.tree(tree.goal)
        if best is None or tree.status != "optimal" or not self._effective.canonical:
            return tree
        if tuple(sorted(tree.units)) == best:
            return tree
        if bounds.cost(best) != list(tree.extra.get("asp_cost", ())):
            units, _, _ = self.parts.relevant(tree.goal)
            found = canonical_tree(bounds, tree.goal, units, self.search_nodes) if search else None
            if found is None or tuple(sorted(tree.units)) == found:
                return tree
            best = found
            tree.stats.pop("canonical_search", None)  # the smallest optimal tree after all
        tree.units = executable_order(self.problem, list(best))
        tree.cost = measures(self.problem, tree.goal, tree.units)
        tree.time_s = round(time.perf_counter() - t0, 6)
        return settle(self.problem, tree, self._ranked)  # the bound is the new tree's cost

    def __call__(self, goal: Goals) -> TaskTree:
        """The tree for ``goal``: an object id, or a tuple of them (a meal, one tree for all)."""
        meal = meal_of(goal)
        if len(meal) > 1 and self.kind != "asp":
            raise InputError(f"meals (several goals in one tree) need an ASP method; {self.name!r} is not one")
        if self._depth_first and len(meal) == 1 and self.maxsat:
            by_depth = self._by_depth(meal[0], time.perf_counter())
            if by_depth is not None:
                return by_depth
        if self.kind != "asp" or len(meal) > 1 or not (self.shortcuts or self._bounded):
            # meals go to the solver: it names the goals that cannot be made
            return self._solve(meal if len(meal) > 1 else meal[0])
        goal = meal[0]
        t0 = time.perf_counter()
        label = self._label or self._effective.method
        if self.shortcuts and goal not in self.parts.derivable:
            self.counts["unreachable"] += 1
            return TaskTree(
                goal,
                label,
                "unreachable",
                time_s=round(time.perf_counter() - t0, 6),
                stats={"shortcut": "unreachable"},
            )
        units, objects, choice = self.parts.relevant(goal)
        # exact when the caller's units (if any) hold the goal's whole part
        exact = self._allowed is None or self._allowed.issuperset(units)
        if not exact or goal not in self.parts.derivable:
            return self._solve(goal)
        if self.shortcuts and not choice and self._monotone:
            self.counts["no-choice"] += 1
            return self._answer(goal, label, executable_order(self.problem, units), "no-choice", t0)
        if not self._bounded:
            return self._solve(goal)
        bounds = self.parts.bounds_for(self._ranked, units)
        if not self.shortcuts:
            return self._canonical(self._solve(goal, bounds.first_lower(goal)), bounds, t0)
        if bounds.proven(goal):
            self.counts["bounds"] += 1
            tree = bounds.tree(goal) or ()
            return self._answer(goal, label, executable_order(self.problem, list(tree)), "bounds", t0)
        skip = self.maxsat and hopeless(bounds, goal)  # MaxSAT without the search that would fail
        found = None if skip else canonical_tree(bounds, goal, units, self.search_nodes)
        if found is not None:
            self.counts["branch-and-bound"] += 1
            return self._answer(goal, label, executable_order(self.problem, list(found)), "branch-and-bound", t0)
        if self.maxsat:
            self.counts["maxsat"] += 1
            dominators = self.parts.dominators(self._ranked)
            return proofs.by_maxsat(
                self.problem, self._effective, self._ranked, goal, label, units, bounds, t0, dominators
            )
        # the branch and bound ran out of nodes: it would again
        return self._canonical(self._solve_pruned(goal, units, objects, bounds), bounds, t0, search=False)

    def _answer(self, goal: int, label: str, order: list[int], shortcut: str, t0: float) -> TaskTree:
        """An optimal tree found without the solver."""
        return proofs.answer(self.problem, goal, label, order, self._ranked, shortcut, t0)

    def _by_depth(self, goal: int, t0: float) -> TaskTree | None:
        """Depth first by MaxSAT (foon2asp.methods.proofs), or None: the driver's rounds answer."""
        if goal not in self.parts.derivable or goal in self.problem.kitchen:
            return None
        units, _, choice = self.parts.relevant(goal)
        if self._allowed is not None and not self._allowed.issuperset(units):
            return None
        label = self._label or self._effective.method
        if not choice:  # the whole part is the only tree
            self.counts["no-choice"] += 1
            return self._answer(goal, label, executable_order(self.problem, units), "no-choice", t0)
        self.counts["maxsat"] += 1
        if self._weights is None:
            self._weights = weights(self.problem, self._ranked[1:])
        dominators = self.parts.dominators(self._ranked)
        return proofs.by_maxsat_depth(
            self.problem, self._effective, self._ranked, goal, label, units, self._weights, t0, dominators
        )


def solve_goals(
    problem: Problem,
    goals: Iterable[Goals],
    method: str,
    options: AspOptions,
    grounding: str = "whole",
    shortcuts: bool = True,
) -> Iterator[TaskTree]:
    """The trees of ``method`` for ``goals``, in order, each solved when it is asked for.

    The one "solve these goals" entry point: ``solve``, ``compare``, ``check`` and the
    library call it; ``batch``, whose processes are handed goals one by one, builds the
    same :class:`GoalRunner` once per process.  The runner is built here, at the call,
    so a bad method or grounding is an error before any goal is solved.

    A goal is an object id, or a tuple of them (a meal: one tree for all).
    ASP methods ground only the units a tree for one of ``goals`` can use
    (:meth:`Problem.units_for`) unless ``options.units`` says otherwise.
    """
    goals = list(goals)
    run = GoalRunner(method, problem, options, grounding, shortcuts, goals=goals)  # built now: errors come first
    return map(run, goals)


def runner(name: str, problem: Problem, options: AspOptions) -> Runner:
    """The goal runner of method ``name`` for any goal of ``problem``, asked one goal at a time."""
    return GoalRunner(name, problem, options)
