"""The goal runner: carries out each goal's plan (:func:`foon2asp.methods.plan.plan`).

:class:`GoalRunner` answers goal after goal for one request; :func:`solve_goals` is what
``solve``, ``compare``, ``check``, ``batch`` and the library call.  What to do with a goal is
the plan's; the runner grounds and solves what it names and settles what it settles.
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Iterator

from foon2asp.asp.decisions import decide, decided
from foon2asp.asp.grounding import Decisions
from foon2asp.asp.interrupts import deferred_signals
from foon2asp.asp.options import AspOptions
from foon2asp.asp.prepared import Preparation
from foon2asp.asp.session import Session
from foon2asp.foon.problem import Problem
from foon2asp.methods.parts import Parts
from foon2asp.methods.plan import ROUTES, Plan, Request, decisions, explanations, plan, preparation, request
from foon2asp.methods.registry import Runner, get
from foon2asp.tree.gap import settle
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, measures
from foon2asp.tree.weights import total

#: the routes and what proves their answers (None: nothing)
PROVEN_BY = ROUTES

#: how many goals :meth:`GoalRunner.each` plans ahead at a time (and decides together where it can)
AHEAD = 256
#: seconds :meth:`GoalRunner.ahead` may plan before the first of its goals is answered
AHEAD_S = 1.0

#: statuses that are proven answers
PROVEN = ("optimal", "ranked", "unreachable", "infeasible")


class GoalRunner:
    """The runner of one registered method for many goals.

    ``options``: the caller's (the method adjusts them); ``goals``: the goals it will be
    asked, if known (the ``clingo`` route grounds only their units); ``parts``: the caller's
    :class:`Parts` of ``problem``; ``shortcuts=False``: no ``only-tree`` or ``bounds`` route.
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
        self.request: Request = request(name, problem, options, grounding, shortcuts, parts, goals)
        self.name = name
        self.problem = self.request.problem
        self.options = self.request.options
        self.parts = self.request.parts
        #: how many goals took each route (:data:`PROVEN_BY`)
        self.counts = dict.fromkeys(PROVEN_BY, 0)
        self._shared: Session | None = None
        #: the plans of the goals :meth:`ahead` looked at, until each is asked, with the seconds
        #: each took (counted in the goal's time)
        self._planned: dict[int, tuple[Plan, float]] = {}
        #: goal -> (the grouped decision that decided it, its seconds per goal) (:meth:`ahead`)
        self._decided: dict[int, tuple[Decisions, float]] = {}
        method = get(name)
        self._search = method.factory(self.problem, options) if method.factory is not None else None

    def plan(self, goal: Goals) -> Plan:
        """The plan of ``goal`` (:func:`foon2asp.methods.plan.plan`)."""
        return plan(self.request, goal)

    def route(self, goal: Goals) -> str:
        """How ``goal`` is answered: a key of :data:`PROVEN_BY`."""
        return self.plan(goal).route

    def preparation(self, goal: int) -> Preparation:
        """What Python hands clingo for ``goal`` (a derivable goal that is no kitchen item)."""
        return preparation(self.request, goal)

    def ahead(self, goals: Iterable[Goals]) -> None:
        """Plan ``goals``, the next ones this runner will be asked, in order until
        :data:`AHEAD_S` seconds are spent (the rest are planned when asked), and carry out the
        grouped decision of those planned (:func:`~foon2asp.methods.plan.decisions`) now; each
        answer waits for its goal.  What an earlier call planned and was not asked is forgotten."""
        self._planned.clear()
        self._decided.clear()
        start = time.perf_counter()
        for goal in goals:
            if time.perf_counter() - start >= AHEAD_S and self._planned:
                break  # the first answer waits no longer for the plans of the goals after it
            if isinstance(goal, int) and goal not in self._planned:
                t0 = time.perf_counter()
                how = self.plan(goal)
                self._planned[goal] = (how, time.perf_counter() - t0)
        group = decisions(self.request, [how for how, _ in self._planned.values()])
        if group is None:
            return
        t0 = time.perf_counter()
        with deferred_signals():  # the control is freed with no interrupt in the middle
            found = decide(group)
        share = (time.perf_counter() - t0) / len(group.groundings)
        for g in found:
            self._decided[g] = (group, share)

    def planned(self, goal: Goals) -> bool:
        """Was ``goal`` planned ahead and not asked yet (a meal never is: nothing to plan ahead)?"""
        return not isinstance(goal, int) or goal in self._planned

    def each(self, goals: Iterable[Goals]) -> Iterator[TaskTree]:
        """The trees for ``goals``, in order, each answered when it is asked for; the goals are
        planned ahead, up to :data:`AHEAD` at a time (:meth:`ahead`)."""
        goals = list(goals)
        for i, goal in enumerate(goals):
            if not self.planned(goal):
                self.ahead(goals[i : i + AHEAD])
            yield self(goal)

    def __call__(self, goal: Goals) -> TaskTree:
        """The tree for ``goal``: an object id, or a tuple of them (a meal, one tree for all)."""
        t0 = time.perf_counter()
        planned = self._planned.pop(goal, None) if isinstance(goal, int) else None
        if planned is not None:
            how, spent = planned
            t0 -= spent  # the goal's time holds its planning
        else:
            how = self.plan(goal)
        self.counts[how.route] += 1
        if how.route == "search":
            assert self._search is not None, f"search method {self.name!r} has no factory"
            return self._search(how.goal[0])
        tree = self.carry_out(how, t0)
        if how.programs:
            tree.constraints = list(how.programs)
        return tree

    def carry_out(self, how: Plan, t0: float) -> TaskTree:
        """The answer ``how`` names, with what proved it."""
        if how.route == "fixpoint":
            tree = self._fixpoint(how.goal[0], t0)
        elif how.route in ("only-tree", "bounds"):
            tree = self._settled(how, t0)
        else:
            tree = self._solve(how, t0)
            tree.stats.setdefault("plan", how.describe())  # what was grounded and how clingo ran
        if how.explain and tree.status == "unreachable" and all(g in self.problem.derivable for g in how.goal):
            if self.options.max_depth is None or self._within_depth(how.goal):
                self._infeasible(tree)
        for answer in (tree, *tree.alternatives):
            if answer.status in PROVEN and answer.proven_by is None:
                answer.proven_by = how.proven_by
        return tree

    def _fixpoint(self, goal: int, t0: float) -> TaskTree:
        """A goal the least fixpoint settles: not derivable, or a kitchen item (no units)."""
        if goal in self.problem.kitchen:
            return self._settled(Plan("fixpoint", (goal,), self.request.label, self.request.ranked), t0)
        return TaskTree(goal, self.request.label, "unreachable", time_s=round(time.perf_counter() - t0, 6))

    def _settled(self, how: Plan, t0: float) -> TaskTree:
        """An optimal tree that preparation proved (its units are the plan's)."""
        goal = how.goal[0]
        order = executable_order(self.problem, list(how.tree))
        cost = measures(self.problem, goal, order)
        asp_cost = [cost["depth"] or 0 if name == "depth" else total(self.problem, name, order) for name in how.ranked]
        tree = TaskTree(goal, how.method, "optimal", order, cost, round(time.perf_counter() - t0, 6))
        tree.asp_cost = asp_cost
        return settle(self.problem, tree, how.ranked)

    def _solve(self, how: Plan, t0: float) -> TaskTree:
        """clingo on the plan's grounding; first, when the plan says so, the optimum without the
        user's programs, kept when it satisfies them."""
        if how.free_first is not None:
            tree = self.carry_out(how.free_first, t0)
            if tree.status == "optimal" and self.request.allows(tree.units):
                return tree
        grounding = how.grounding
        assert grounding is not None, f"the {how.route} route needs a grounding"
        if how.shared:
            if self._shared is None:
                self._shared = Session(grounding)
            return self._shared.solve(how.goal if len(how.goal) > 1 else how.goal[0])
        prep = grounding.prepared
        if prep is None:  # the goal's part, grounded for it
            return Session(grounding).solve(how.goal[0])
        if prep.goal in self._decided:  # decided with other goals (:meth:`ahead`)
            group, share = self._decided.pop(prep.goal)
            tree = decided(grounding, time.perf_counter() - t0 + share)
            tree.stats["candidates"] = len(prep.candidates)
            tree.stats["plan"] = {**how.describe(), **group.describe()}
            return tree
        with deferred_signals():  # one section for the grounding and the search
            tree = Session(grounding).solve(prep.goal, floor=prep.floor)
        tree.time_s = round(time.perf_counter() - t0, 6)
        tree.stats["candidates"] = len(prep.candidates)
        return tree

    def _within_depth(self, meal: tuple[int, ...]) -> bool:
        """Is there a tree for ``meal`` within the depth bound when the user's programs are left out?
        (Without one the depth bound, not the programs, rules every tree out.)"""
        free = explanations(self.request.free, meal, alone=False)
        return Session(free).solve(meal if len(meal) > 1 else meal[0]).status != "unreachable"

    def _infeasible(self, tree: TaskTree) -> None:
        """Trees exist but the user's programs rule them all out: ``infeasible``, naming each program
        that alone does."""
        tree.status = "infeasible"
        programs = self.options.programs
        alone = []
        if len(programs) == 1:
            alone = [programs[0][0]]
        else:
            limit = self.options.time_limit
            for name, grounding in explanations(self.request, tree.meal):
                session = Session(grounding)  # does this program alone leave a tree?
                if grounding.driven:
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
            tree.infeasible_by = alone
        tree.reason = why


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
    return run.each(goals)


def runner(name: str, problem: Problem, options: AspOptions) -> Runner:
    """The goal runner of method ``name`` for any goal of ``problem``, asked one goal at a time."""
    return GoalRunner(name, problem, options)
