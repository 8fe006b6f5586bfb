"""One goal on a grounded Session with the features beyond a single optimisation.

Depth bounds, human steps, the K best trees, all optimal trees and greedy retrieval, as the
session's grounding (:class:`foon2asp.asp.grounding.Grounding`, decided by the plan) names
them; each solve switches its externals off again, so the next goal starts clean (the further
trees: docs/proofs/solving.md, "Alternatives").
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

import clingo

from foon2asp.asp import objectives
from foon2asp.asp.answers import Shot, cost_vector, finish, solve_shot, status
from foon2asp.asp.canonical import canonicalise
from foon2asp.asp.control import remaining
from foon2asp.asp.multishot import depth as depth_mod
from foon2asp.tree.tasktree import Goals, TaskTree, goal_fields, meal_of, measures


class Driver:
    """Solves goals on ``session`` as its grounding says."""

    def __init__(self, session):
        self.session = session
        self.control = session.control
        self.options = session.options
        self.problem = session.problem
        self.grounding = session.grounding
        self.ranked = objectives.ranked(self.options)
        #: "first" or "later" (depth is an objective at that place), "bound" (only --max-depth) or "none"
        self.depth_mode = self.grounding.depth
        #: the canonical tree is searched after each level's optimum
        self.canonical = self.grounding.canonical != "none"
        self.solves = 0
        self.last_stats: dict = {}
        #: "budget" when a search for the smallest optimal tree of the current goal did not end
        self.canonical_search: str | None = None
        self.rounds: depth_mod.Rounds | None = None
        self.depth = depth_mod.DepthSearch()

    def shot(
        self,
        goal: Goals,
        externals: Sequence[clingo.Symbol | int],
        mode: str | None,
        deadline: float | None,
        count: int = 1,
        on_model: Callable[[clingo.Model], None] | None = None,
    ) -> Shot:
        """Solve once in ``mode`` (None: "opt"; "optN" up to ``count`` trees; "first") with ``externals`` on."""
        mode = mode or "opt"
        goals = [clingo.Function("goal", [clingo.Number(g)]) for g in meal_of(goal)]
        control = self.control
        self.solves += 1
        with control.switched([*goals, *externals]):
            shot = solve_shot(control, mode, count, on_model, remaining(deadline))
            self.last_stats = control.stats()  # before the externals change: that resets them
            found = shot.answers
            settled = (mode == "opt" and shot.exhausted) or (mode == "optN" and bool(found) and found[0].proven)
            if found and shot.finished and settled and self.canonical:
                # the canonical tree first, the others in id order
                first, complete = canonicalise(control, found[0], deadline)
                if not complete:
                    self.canonical_search = "budget"
                shot.answers = [first] + [a for a in found if a.units != first.units][: max(0, count - 1)]
        return shot

    def depth_floor(self) -> int | None:
        """With depth the first objective: a lower bound on the depth of the current goal's trees."""
        return self.depth.bound if self.depth_mode == "first" and self.depth.bound else None

    def level(self, goal: Goals, guards: list[int], count: int, deadline, on_model) -> tuple[Shot, int | None]:
        """The best trees (up to ``count``, distinct) not yet excluded, with the depth bound used."""
        mode = "optN" if count > 1 else "opt"

        def shot(externals: Sequence[clingo.Symbol], solve_mode: str | None = None) -> Shot:
            return self.shot(goal, [*guards, *externals], solve_mode or mode, deadline, count, on_model)

        if self.depth_mode == "none":
            return shot([]), None

        def tree_depth(answer: TaskTree) -> int:
            return measures(self.problem, goal, list(answer.units))["depth"] or 0

        if self.rounds is None:
            self.rounds = depth_mod.Rounds.of(self.session)
        rounds, state, max_depth = self.rounds, self.depth, self.options.max_depth
        if self.depth_mode == "bound":
            assert max_depth is not None
            return shot(rounds.externals(goal, max_depth, False)), max_depth
        least = rounds.levels.level(goal)
        limit = [] if max_depth is None else rounds.externals(goal, max_depth, False)
        if self.depth_mode == "later":
            first = shot(limit, "opt")
            if not first.answers:
                return first, max_depth
            bound = tree_depth(first.answers[0])
            if count != 1 or (bound > 1 and (least is None or bound > least)):
                return shot(rounds.externals(goal, bound, True)), bound
            # no tree is shallower than the goal's level; the depth cost was off in that solve
            at = self.ranked.index("depth")
            levels = len(self.ranked) + ("human_limit" in self.grounding.facts)
            for a in first.answers:
                a.asp_cost = list(_with_depth(cost_vector(a), at, tree_depth(a), levels))
            return first, bound
        # depth first: raise the bound from the goal's level until the goal is derivable within it
        if state.bound is None:
            start = max(1, least or 1)
            state.refuted.extend((t, "grounder") for t in range(1, start))
            state.bound = start
        bound = state.bound
        ceiling = None  # the depth of some remaining tree, once a bound fails
        while True:
            if max_depth is not None and bound > max_depth:
                return shot(limit, "first"), max_depth  # unsatisfiable: nothing within --max-depth
            result = shot(rounds.externals(goal, bound, True))
            if result.answers or not result.finished:
                state.bound = bound
                return result, bound
            state.refuted.append((bound, "solver"))
            if ceiling is None or bound >= ceiling:
                # constraints or excluded trees removed the shallow trees: any remaining one bounds the search
                feasible = shot(limit, "first")
                if not feasible.answers:
                    return feasible, max_depth
                ceiling = tree_depth(feasible.answers[0])
            bound += 1
            state.bound = bound

    def solve(self, goal: Goals, on_model=None, time_limit: float | None = None) -> TaskTree:
        """The best tree for ``goal`` (the further ones as its alternatives)."""
        options = self.options
        time_limit = options.time_limit if time_limit is None else time_limit
        t0 = time.perf_counter()
        deadline = None if not time_limit else t0 + time_limit
        self.solves = 0
        self.last_stats = {}
        self.canonical_search = None
        meal = meal_of(goal)
        goal = meal if len(meal) > 1 else meal[0]
        if any(g not in self.session.goal_atoms for g in meal):
            return self._tree(goal, None, "unreachable", t0)
        if all(g in self.problem.kitchen for g in meal):
            kitchen = TaskTree(status="optimal", method=options.method, asp_cost=[], **goal_fields(goal))
            return self._tree(goal, kitchen, "optimal", t0)
        if not all(self.control.has_atom(clingo.Function("reach", [clingo.Number(g)])) for g in meal):
            return self._tree(goal, None, "unreachable", t0)  # the grounder's fixpoint never derives a goal
        if self.grounding.greedy:
            return self._greedy(goal, deadline, t0, on_model)
        self.depth = depth_mod.DepthSearch()
        found, first, capped = self._levels(goal, deadline, on_model)
        if not found:
            tree = self._tree(goal, None, status(None, first), t0)
            if tree.status == "unreachable" and options.max_depth is not None:
                tree.reason = f"no tree of depth <= {options.max_depth}"
            return tree
        best_cost = found[0][0].asp_cost
        trees = []
        for rank, (answer, bound) in enumerate(found, 1):
            tree = self._tree(goal, answer, status(answer, first, best_cost), t0, bound)
            if options.models > 1 or options.all_optimal:
                tree.rank = rank
            trees.append(tree)
        best, best.alternatives = trees[0], trees[1:]
        if capped:
            cap = options.all_optimal_cap
            best.note = f"more than {cap} optimal trees: only the first {cap} are given"
        return best

    def _levels(self, goal: Goals, deadline, on_model) -> tuple[list[tuple[TaskTree, int | None]], Shot, bool]:
        """The trees (with their depth bounds) level by level, each level's trees excluded from the
        next; the first level's shot; whether --all-optimal's cap cut."""
        options = self.options
        want = max(1, int(options.models))
        cap = int(options.all_optimal_cap)
        guards: list[int] = []
        found: list[tuple[TaskTree, int | None]] = []
        first: Shot | None = None
        capped = False
        try:
            while True:
                count = cap + 1 if options.all_optimal else want - len(found)
                shot, bound = self.level(goal, guards, count, deadline, on_model)
                first = first or shot
                found += [(a, bound) for a in shot.answers[:count]]
                if options.all_optimal:
                    capped = len(found) > cap
                    found = found[:cap]
                    break
                if len(found) >= want or not shot.answers or not shot.finished:
                    break
                for answer in shot.answers:  # the tree and its supersets
                    guards.append(self.control.guard(clingo.Function("use", [clingo.Number(u)]) for u in answer.units))
        finally:
            self.control.release(guards)
        assert first is not None  # the loop solves at least once
        return found, first, capped

    def _greedy(self, goal: Goals, deadline, t0: float, on_model) -> TaskTree:
        shot = self.shot(goal, [], "first", deadline, 1, on_model)
        if shot.answers:
            return self._tree(goal, shot.answers[0], "found", t0)
        return self._tree(goal, None, status(None, shot), t0)

    def _tree(self, goal: Goals, answer: TaskTree | None, status: str, t0: float, bound: int | None = None) -> TaskTree:
        """``answer`` (a tree read from a model; None: none) finished for ``goal``."""
        stats = dict(self.last_stats, solves=self.solves)
        if answer is not None and self.canonical_search:
            stats["canonical_search"] = self.canonical_search
        human = "human_limit" in self.grounding.facts
        elapsed = time.perf_counter() - t0
        tree = finish(self.problem, self.options.method, goal, status, answer, elapsed, stats, human)
        if answer is not None and bound is not None and self.depth_mode == "first":
            refuted = self.depth.refuted
            tree.depth_bound = bound
            tree.depth_refuted = {how: sum(1 for _, h in refuted if h == how) for how in ("grounder", "solver")}
        return tree


def _with_depth(cost: tuple[int, ...], at: int, depth: int, levels: int) -> tuple[int, ...]:
    """``cost`` with ``depth`` at priority slot ``at`` (which clingo may have left out)."""
    if len(cost) < levels:
        return cost[:at] + (depth,) + cost[at:]
    return cost[:at] + (depth,) + cost[at + 1 :]


def alternatives(tree: TaskTree) -> list[TaskTree]:
    """``tree`` and the further trees found with it (--models / --all-optimal), best first."""
    return [tree, *tree.alternatives]
