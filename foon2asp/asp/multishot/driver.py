"""Solving one goal on a grounded :class:`~foon2asp.solver.Session` with the
features beyond a single optimisation: depth bounds (:mod:`foon2asp.depth`),
human steps, the K best trees, all optimal trees and greedy retrieval.

A goal may be a meal (a tuple of goal ids): ``goal(G)`` is then switched on
for every goal, and a depth bound applies to the meal (every goal within the
bound; see :mod:`foon2asp.asp.multishot.depth`).

Every solve sets the externals it needs (``goal(G)``, ``query(k)``,
``within(k)``, exclusion guards) and switches them off again afterwards, so
the next goal of the session starts clean; clingo proves each optimum anew
for the current externals (tests compare with a fresh Control per goal).

Alternatives: the optimal trees of one cost level are enumerated with
``opt-mode=optN`` and projection on ``use/1`` (``#project use/1``), so two
answers are always distinct sets of units; for ``--models K`` each tree found
is then excluded together with its supersets by a nogood (guarded by an
external switched on only for this goal) and the next level is solved, so
trees come best first and no tree merely adds units to an earlier one.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import clingo

from foon2asp.asp import objectives
from foon2asp.asp.canonical import canonicalise
from foon2asp.asp.control import Answer, deferred_signals, read_model
from foon2asp.asp.multishot import depth as depth_mod
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, goal_fields, meal_of, measures


@dataclass
class Shot:
    """The outcome of one solve call."""

    answers: list[Answer] = field(default_factory=list)
    unsat: bool = False
    #: the search ran to its end (not stopped by the time limit)
    finished: bool = True


class Driver:
    """Solves goals on ``session`` according to its options."""

    def __init__(self, session):
        self.session = session
        self.options = session.options
        self.problem = session.problem
        self.ranked = objectives.ranked(self.options)
        self.depth_mode = depth_mod.depth_mode(self.options, self.ranked)
        self.solves = 0
        self.last_stats: dict = {}
        #: "budget" when a search for the smallest optimal tree of the current goal did not end
        self.canonical_search: str | None = None
        self._state: dict = {}

    # -- one solve ---------------------------------------------------------

    def shot(
        self,
        goal: Goals,
        externals: dict,
        mode: str | None,
        deadline: float | None,
        count: int = 1,
        on_model: Callable[[clingo.Model], None] | None = None,
    ) -> Shot:
        """Solve once with ``externals`` on.  ``mode``: None/"opt" (best model),
        "optN" (up to ``count`` distinct optimal trees) or "first" (first model)."""
        ctl = self.session.ctl
        conf = ctl.configuration.solve
        mode = mode or "opt"
        conf.opt_mode = {"opt": "opt", "optN": "optN", "first": "ignore"}[mode]
        conf.models = "1" if mode == "first" else str(count) if mode == "optN" else "0"
        conf.project = "project" if mode == "optN" else "no"
        answers: dict[tuple[int, ...], Answer] = {}
        last: list[Answer] = []

        def record(model: clingo.Model) -> None:
            answer = read_model(model)
            last[:] = [answer]
            if mode == "optN" and answer.proven:
                answers.setdefault(answer.units, answer)
            if on_model is not None:
                on_model(model)

        switched = {clingo.Function("goal", [clingo.Number(g)]): True for g in meal_of(goal)}
        switched.update(externals)
        control = self.session.control
        control.assign(switched)
        self.solves += 1
        try:
            remaining = None if deadline is None else max(0.0, deadline - time.perf_counter())
            result = control.solve(record, remaining)
            self.last_stats = self.session.stats()  # before the externals change: that resets them
            finished = result.finished
            if mode == "optN":
                # distinct optimal trees in an input-only order (smallest unit ids first)
                found = sorted(answers.values(), key=lambda a: a.units) or ([] if finished else last)
            else:
                found = last
            if found and mode == "opt" and finished and result.exhausted:
                found = [Answer(a.units, a.cost, True, a.human) for a in found]
                if self.options.canonical:
                    # several optimal trees: the one that depends only on the input
                    found[0], complete = canonicalise(control, found[0], deadline)
                    self._searched(complete)
            elif found and mode == "optN" and finished and found[0].proven and self.options.canonical:
                # the first tree is the canonical one; the others follow in id order
                first, complete = canonicalise(control, found[0], deadline)
                self._searched(complete)
                found = [first] + [a for a in found if a.units != first.units][: max(0, count - 1)]
        finally:
            control.assign(dict.fromkeys(switched, False))
        return Shot(found, result.unsatisfiable is True, finished)

    def _searched(self, complete: bool) -> None:
        """Note a search for the smallest optimal tree that its budget (or time) ended."""
        if not complete:
            self.canonical_search = "budget"

    # -- one cost level ----------------------------------------------------

    def level(self, goal: Goals, guards: dict, count: int, deadline, state: dict, on_model) -> tuple[Shot, int | None]:
        """The best trees (up to ``count``, distinct) not yet excluded, with the depth bound used."""
        mode = "optN" if count > 1 else "opt"

        def shot(externals: dict, solve_mode: str | None) -> Shot:
            return self.shot(goal, {**guards, **externals}, solve_mode or mode, deadline, count, on_model)

        if self.depth_mode == "none":
            return shot({}, None), None

        def tree_depth(answer: Answer) -> int:
            return measures(self.problem, goal, list(answer.units))["depth"] or 0

        result, bound = depth_mod.solve_depth(self.session, goal, shot, tree_depth, self.depth_mode, state, count == 1)
        if state.pop("shortcut", False):
            # the depth cost was off in that solve: fill in the depth the tree has
            at = self.ranked.index("depth")
            levels = len(self.ranked) + (self.options.human_steps is not None)
            result.answers = [
                Answer(a.units, _with_depth(a.cost, at, tree_depth(a), levels), a.proven, a.human)
                for a in result.answers
            ]
        return result, bound

    def exclude(self, answer: Answer) -> int:
        """A nogood forbidding ``answer``'s units together, behind a fresh external guard.

        It forbids the tree and every superset of it: a superset that is a tree
        is never better than the tree it contains (units is always a
        tie-breaker), so the further trees are the next best ones that do not
        merely add units to a tree already given.
        """
        ctl = self.session.ctl
        atoms = ctl.symbolic_atoms
        body = [atoms[clingo.Function("use", [clingo.Number(u)])].literal for u in answer.units]
        with deferred_signals(), ctl.backend() as backend:
            guard = backend.add_atom()
            backend.add_external(guard, clingo.TruthValue.False_)
            backend.add_rule([], [guard] + body)
        return guard

    # -- a goal ------------------------------------------------------------

    def solve(self, goal: Goals, on_model=None, time_limit: float | None = None) -> TaskTree:
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
            return self._tree(goal, Answer((), (), True), "optimal", t0)
        atoms = self.session.ctl.symbolic_atoms
        if any(atoms[clingo.Function("reach", [clingo.Number(g)])] is None for g in meal):
            # the grounder's fixpoint (tree.lp) never derives a goal: no tree at all
            return self._tree(goal, None, "unreachable", t0)
        if options.heuristic:
            return self._greedy(goal, deadline, t0, on_model)
        want = max(1, int(options.models))
        cap = int(options.all_optimal_cap)
        guards: dict = {}
        state = self._state = {}
        found: list[tuple[Answer, int | None]] = []
        first: Shot | None = None
        capped = False
        try:
            while True:
                count = cap + 1 if options.all_optimal else want - len(found)
                shot, bound = self.level(goal, guards, count, deadline, state, on_model)
                first = first or shot
                found += [(a, bound) for a in shot.answers[:count]]
                if options.all_optimal:
                    capped = len(found) > cap
                    found = found[:cap]
                    break
                if len(found) >= want or not shot.answers or not shot.finished:
                    break
                for answer in shot.answers:
                    guards[self.exclude(answer)] = True
        finally:
            with deferred_signals():
                for guard in guards:
                    self.session.ctl.release_external(guard)
        if not found:
            status = "unreachable" if first.unsat and first.finished else "unknown"
            tree = self._tree(goal, None, status, t0)
            if status == "unreachable" and options.max_depth is not None:
                tree.extra["reason"] = f"no tree of depth <= {options.max_depth}"
            return tree
        best_cost = found[0][0].cost
        trees = []
        for rank, (answer, bound) in enumerate(found, 1):
            # "ranked": proven best once the better trees (and their supersets) are excluded;
            # "feasible" only when the time limit stopped that search
            status = ("optimal" if answer.cost == best_cost else "ranked") if answer.proven else "feasible"
            tree = self._tree(goal, answer, status, t0, bound)
            if want > 1 or options.all_optimal:
                tree.extra["rank"] = rank
            trees.append(tree)
        best = trees[0]
        if capped:
            best.extra["note"] = f"more than {cap} optimal trees: only the first {cap} are given"
        if len(trees) > 1:
            best.extra["_alternatives"] = trees[1:]
        return best

    def _greedy(self, goal: Goals, deadline, t0: float, on_model) -> TaskTree:
        shot = self.shot(goal, {}, "first", deadline, 1, on_model)
        if shot.answers:
            return self._tree(goal, shot.answers[0], "found", t0)
        return self._tree(goal, None, "unreachable" if shot.unsat and shot.finished else "unknown", t0)

    def _tree(self, goal: Goals, answer: Answer | None, status: str, t0: float, bound: int | None = None) -> TaskTree:
        elapsed = round(time.perf_counter() - t0, 6)
        method = self.options.method
        if answer is None:
            stats = dict(self.last_stats, solves=self.solves)
            return TaskTree(method=method, status=status, time_s=elapsed, stats=stats, **goal_fields(goal))
        units = executable_order(self.problem, list(answer.units))
        cost = measures(self.problem, goal, units)
        extra: dict = {"asp_cost": list(answer.cost)}
        if self.options.human_steps is not None:
            cost["success"] = objectives.success_product(self.problem, units, answer.human)
            human = [u for u in units if u in set(answer.human)]
            extra["human_steps"] = human
            extra["human_step_numbers"] = [i for i, u in enumerate(units, 1) if u in set(answer.human)]
        if bound is not None and self.depth_mode == "first":
            extra["depth_bound"] = bound
            refuted = self._state.get("refuted", [])
            extra["depth_refuted"] = {how: sum(1 for _, h in refuted if h == how) for how in ("grounder", "solver")}
        stats = dict(self.last_stats, solves=self.solves)
        if self.canonical_search:
            stats["canonical_search"] = self.canonical_search
        return TaskTree(
            method=method,
            status=status,
            units=units,
            cost=cost,
            time_s=elapsed,
            stats=stats,
            extra=extra,
            **goal_fields(goal),
        )


def _with_depth(cost: tuple[int, ...], at: int, depth: int, levels: int) -> tuple[int, ...]:
    """``cost`` with ``depth`` at priority slot ``at`` (clingo leaves out a level whose
    literals were all switched off, so the slot may be missing)."""
    if len(cost) < levels:
        return cost[:at] + (depth,) + cost[at:]
    return cost[:at] + (depth,) + cost[at + 1 :]


def alternatives(tree: TaskTree) -> list[TaskTree]:
    """``tree`` and the further trees found with it (--models / --all-optimal), best first."""
    return [tree] + list(tree.extra.get("_alternatives", []))
