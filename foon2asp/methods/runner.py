"""The goal runner: the one place that decides how a goal is answered.

:class:`GoalRunner` answers goal after goal for one method; :func:`solve_goals` is what
``solve``, ``compare``, ``check``, ``batch`` and the library call.  Each goal takes one
route (:meth:`GoalRunner.route`): ``search`` (a search baseline), ``fixpoint`` (not
derivable, or a kitchen item), ``only-tree`` (the relevant part has no choice),
``prepared`` (clingo on the goal's prepared part) or ``clingo`` (the whole grounding or
the goal's part: meals, depth rounds, alternatives, ...).  Why each answer is proven:
docs/proofs/solving.md, "The routes".
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import replace

import clingo

from foon2asp.asp.control import Control
from foon2asp.asp.dominance import applies as dominance_applies
from foon2asp.asp.facts import facts
from foon2asp.asp.interrupts import deferred_signals
from foon2asp.asp.objectives import ranked
from foon2asp.asp.options import AspOptions
from foon2asp.asp.predicates import checkable, only_constraints
from foon2asp.asp.prepared import Preparation
from foon2asp.asp.session import Session
from foon2asp.asp.substitute_facts import prepare as with_substitutes
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem
from foon2asp.methods.bounds import supports as bounds_supports
from foon2asp.methods.parts import GROUNDINGS, Parts
from foon2asp.methods.registry import Runner, Search, check_substitutes, effective_options, get
from foon2asp.tree.gap import settle
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, meal_of, measures
from foon2asp.tree.weights import UNIT_WEIGHTS, total

#: objectives whose cost is a sum of non-negative weights of the used units
MONOTONE = frozenset(UNIT_WEIGHTS)

#: the routes of :meth:`GoalRunner.route` and what proves their answers (None: nothing)
PROVEN_BY: dict[str, str | None] = {
    "search": None,
    "fixpoint": "fixpoint",
    "only-tree": "only-tree",
    "prepared": "clingo",
    "clingo": "clingo",
}

#: statuses that are proven answers
PROVEN = ("optimal", "ranked", "unreachable", "infeasible")


def plain(options: AspOptions) -> bool:
    """Is this plain optimisation of monotone objectives (nothing but the objectives asked)?"""
    return options.plain and all(name in MONOTONE for name in ranked(options))


def preparable(options: AspOptions) -> bool:
    """May a goal take the prepared route (plain, perhaps with programs that only remove trees)?"""
    return plain(replace(options, programs=[])) and only_constraints(options.programs)


def _view(problem: Problem, objects: set[int]) -> Problem:
    """``problem`` with the kitchen cut down to ``objects``."""
    return problem.with_kitchen(o for o in objects if o in problem.kitchen)


class _Constraints(clingo.Observer):
    """Sees whether grounding left any integrity constraint (a rule with an empty head)."""

    def __init__(self) -> None:
        self.found = False

    def rule(self, choice: bool, head: Sequence[int], body: Sequence[int]) -> None:
        self.found = self.found or (not choice and not head)

    def weight_rule(self, choice: bool, head: Sequence[int], lower_bound: int, body: Sequence[tuple[int, int]]) -> None:
        self.found = self.found or (not choice and not head)


class ConstraintCheck:
    """The user's ``programs`` grounded once over ``problem``'s ``units`` (None: all), asked tree by tree."""

    def __init__(self, problem: Problem, programs: Sequence[tuple[str, str]], units: Iterable[int] | None = None):
        self.control = Control(["--opt-mode=ignore"])
        ids = sorted(set(units)) if units is not None else None
        parts = [("facts", facts(problem, units=ids)), ("trees", "#external use(U) : unit(U).\n")]
        self.control.add_all([*parts, *programs], user=[name for name, _ in programs])
        seen = _Constraints()
        self.control.ctl.register_observer(seen)
        self.control.ground()
        self.vacuous = not seen.found

    def allows(self, tree: Iterable[int]) -> bool:
        """Does the tree whose units are ``tree`` satisfy every program?"""
        if self.vacuous:
            return True
        atoms = [clingo.Function("use", [clingo.Number(u)]) for u in tree]
        with self.control.switched(a for a in atoms if self.control.has_atom(a)):
            return self.control.solve().satisfiable is True


class GoalRunner:
    """The runner of one registered method for many goals.

    ``options``: the caller's (the method adjusts them); ``goals``: the goals it will be
    asked, if known (the ``clingo`` route grounds only their units); ``parts``: the caller's
    :class:`Parts` of ``problem``; ``shortcuts=False``: no ``only-tree`` route.
    """

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
        check_substitutes(name, options)
        problem = with_substitutes(problem, options)
        if options.substitutes:  # a goal's part would leave out the kitchen items that stand in
            grounding = "whole"
        method = get(name)
        if goals is not None and method.kind == "asp" and options.units is None:
            options = replace(options, units=problem.units_for({g for goal in goals for g in meal_of(goal)}))
        self.name = name
        self.problem = problem
        self.options = options
        self.grounding = grounding
        self.kind = method.kind
        self.parts = parts if parts is not None and parts.problem is problem else Parts(problem)
        #: how many goals took each route (:data:`PROVEN_BY`)
        self.counts = dict.fromkeys(PROVEN_BY, 0)
        self._whole: Runner | None = None
        #: units the caller allows (options.units)
        self._allowed = None if self.options.units is None else frozenset(self.options.units)
        self._effective = effective_options(name, self.options) if self.kind == "asp" else self.options
        self._ranked = ranked(self._effective) if self.kind == "asp" else ()
        self._label = self._effective.method if self.kind == "asp" else name
        self._preparable = self.kind == "asp" and preparable(self._effective)
        #: the depth objective with nothing else asked: a goal without choice is settled first
        depthless = replace(self._effective, objective=tuple(o for o in self._effective.objective if o != "depth"))
        self._depth_settles = self.kind == "asp" and "depth" in self._ranked and plain(depthless)
        self._settle = shortcuts
        #: under user programs the bounds tree is a hint only and nothing is pruned
        self._constrained = bool(self._effective.programs)
        #: a tree can be checked against the user's programs
        self._checkable = self._constrained and checkable(self._effective.programs)
        self._check: ConstraintCheck | None = None
        #: the same method without the user's programs (their optimum, checked against them)
        self._free: GoalRunner | None = None
        self._bounded = self._preparable and bounds_supports(self._ranked)
        self._search: Search | None = None
        if self.kind != "asp":
            assert method.factory is not None, f"search method {name!r} has no factory"
            self._search = method.factory(problem, self.options)

    def route(self, goal: Goals) -> str:
        """How ``goal`` is answered: a key of :data:`PROVEN_BY`."""
        meal = meal_of(goal)
        if self.kind != "asp":
            return "search"
        if len(meal) > 1 or not (self._preparable or self._depth_settles):
            return "clingo"
        goal = meal[0]
        if goal not in self.problem.derivable or goal in self.problem.kitchen:
            return "fixpoint"
        units, _, choice = self.parts.relevant(goal)
        if self._allowed is not None and not self._allowed.issuperset(units):
            return "clingo"  # the caller's units cut into the part
        if self._depth_settles:
            return "only-tree" if self._settle and not choice else "clingo"
        if self._settle and not choice and self._allows(units):
            return "only-tree"
        return "prepared"

    def _allows(self, tree: Iterable[int]) -> bool:
        """Does ``tree`` satisfy the user's programs (no programs: yes; unchecked: no)?"""
        if not self._constrained:
            return True
        if not self._checkable:
            return False
        if self._check is None:
            self._check = ConstraintCheck(self.problem, self._effective.programs, self.options.units)
        return self._check.allows(tree)

    def __call__(self, goal: Goals) -> TaskTree:
        """The tree for ``goal``: an object id, or a tuple of them (a meal, one tree for all)."""
        meal = meal_of(goal)
        if len(meal) > 1 and self.kind != "asp":
            raise InputError(f"meals (several goals in one tree) need an ASP method; {self.name!r} is not one")
        t0 = time.perf_counter()
        how = self.route(goal)
        self.counts[how] += 1
        if self._search is not None:
            return self._search(meal[0])
        if how == "clingo":
            tree = self._solve(meal if len(meal) > 1 else meal[0])
        elif how == "fixpoint":
            tree = self._fixpoint(meal[0], t0)
        elif how == "only-tree":
            units, _, _ = self.parts.relevant(meal[0])
            tree = self._answer(meal[0], units, t0)
        else:
            tree = self._prepared(meal[0], t0)
        if self._effective.programs and tree.status == "unreachable" and all(g in self.problem.derivable for g in meal):
            self._infeasible(tree)
        for answer in (tree, *tree.alternatives):
            if answer.status in PROVEN:
                answer.proven_by = PROVEN_BY[how]
        if self._effective.programs:
            tree.extra["constraints"] = [name for name, _ in self._effective.programs]
        return tree

    def _fixpoint(self, goal: int, t0: float) -> TaskTree:
        """A goal the least fixpoint settles: not derivable, or a kitchen item (no units)."""
        if goal in self.problem.kitchen:
            return self._answer(goal, [], t0)
        return TaskTree(goal, self._label, "unreachable", time_s=round(time.perf_counter() - t0, 6))

    def _answer(self, goal: int, units: list[int], t0: float) -> TaskTree:
        """An optimal tree that preparation proved."""
        order = executable_order(self.problem, units)
        cost = measures(self.problem, goal, order)
        asp_cost = [
            cost["depth"] or 0 if name == "depth" else total(self.problem, name, order) for name in self._ranked
        ]
        tree = TaskTree(goal, self._label, "optimal", order, cost, round(time.perf_counter() - t0, 6))
        tree.extra["asp_cost"] = asp_cost
        return settle(self.problem, tree, self._ranked)

    def preparation(self, goal: int) -> Preparation:
        """What Python hands clingo for ``goal`` (a derivable goal that is no kitchen item)."""
        units, _, _ = self.parts.relevant(goal)
        if not self._bounded:
            landmarks = self.parts.bounds_for(("units",), units).landmarks(goal)
            return Preparation(goal, tuple(units), tuple(sorted(landmarks)))
        bounds = self.parts.bounds_for(self._ranked, units)
        tree = bounds.tree(goal) or ()
        lower = bounds.lower(goal)
        scale = len(self.problem.units) + 1

        def meets(cost: tuple[int, ...]) -> bool:
            weight = cost[0] if len(cost) == 1 else cost[0] * scale + cost[1]
            return weight <= lower

        if not self._constrained:  # user programs may need any relevant unit
            units = bounds.keep(goal, units)
            if dominance_applies(self._effective, self._ranked):
                dominated = self.parts.dominators(self._ranked).dominated(goal, units)
                units = [u for u in units if u not in dominated or u in tree]
        return Preparation(
            goal,
            tuple(units),
            tuple(sorted(bounds.landmarks(goal))),
            hint=tuple(tree),
            known=None if self._constrained else tuple(bounds.cost(tree)),
            floor=bounds.first_lower(goal),
            meets=meets if len(self._ranked) <= 2 else None,
        )

    def _prepared(self, goal: int, t0: float) -> TaskTree:
        """clingo on the goal's prepared part; under checkable user programs, the optimum without
        them when it satisfies them."""
        if self._checkable:
            if self._free is None:
                free = replace(self._effective, programs=[])
                self._free = GoalRunner(self.name, self.problem, free, self.grounding, self._settle, self.parts)
            tree = self._free._prepared(goal, t0)
            if tree.status == "optimal" and self._allows(tree.units):
                return tree
        prep = self.preparation(goal)
        with deferred_signals():  # one section for the grounding and the search
            session = Session(self.problem, self._effective, prepared=prep)
            tree = session.solve(goal, floor=prep.floor)
        tree.time_s = round(time.perf_counter() - t0, 6)
        tree.stats["candidates"] = len(prep.candidates)
        return tree

    def _solve(self, goal: Goals) -> TaskTree:
        """clingo on the whole grounding (all viable or allowed units, grounded once) or the goal's part."""
        if self.grounding == "whole" or len(meal_of(goal)) > 1:
            if self._whole is None:
                units = self.options.units if self.options.units is not None else sorted(self.parts.viable)
                self._whole = Session(self.problem, replace(self._effective, units=tuple(units))).solve
            return self._whole(goal)
        units, objects, _ = self.parts.relevant(goal)
        if self._allowed is not None:
            units = [u for u in units if u in self._allowed]
        return Session(_view(self.problem, objects), replace(self._effective, units=tuple(units))).solve(goal)

    def _infeasible(self, tree: TaskTree) -> None:
        """Trees exist but the user's programs rule them all out: ``infeasible``, naming each program
        that alone does."""
        tree.status = "infeasible"
        programs = self._effective.programs
        alone = []
        if len(programs) == 1:
            alone = [programs[0][0]]
        else:
            units, objects, _ = self.parts.relevant(tree.meal)
            limit = self._effective.time_limit
            for name, text in programs:
                # does this program alone leave a tree?
                one = replace(self._effective, programs=[(name, text)], units=tuple(units))
                session = Session(_view(self.problem, objects), one, goal=tree.meal)
                if one.driven:
                    left = session.solve(tree.meal if tree.is_meal else tree.goal, time_limit=limit).status
                    none = left == "unreachable"
                else:
                    with session.control.solving("first"):
                        none = bool(session.control.solve(time_limit=limit).unsatisfiable)
                if none:
                    alone.append(name)
        why = "trees exist, but the constraints rule them all out"
        if alone:
            why += f"; {alone[0]} alone does" if len(alone) == 1 else f"; each of {', '.join(alone)} alone does"
            tree.extra["infeasible_by"] = alone
        tree.extra["reason"] = why


def solve_goals(
    problem: Problem,
    goals: Iterable[Goals],
    method: str,
    options: AspOptions,
    grounding: str = "whole",
    shortcuts: bool = True,
) -> Iterator[TaskTree]:
    """The trees of ``method`` for ``goals`` (object ids, or tuples of them: meals), in order,
    each solved when it is asked for (a bad method or grounding fails at the call)."""
    goals = list(goals)
    run = GoalRunner(method, problem, options, grounding, shortcuts, goals=goals)
    return map(run, goals)


def runner(name: str, problem: Problem, options: AspOptions) -> Runner:
    """The goal runner of method ``name`` for any goal of ``problem``, asked one goal at a time."""
    return GoalRunner(name, problem, options)
