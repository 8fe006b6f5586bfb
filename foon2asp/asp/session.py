"""Ground and solve with the clingo Python API: one :class:`Session` carries out one grounding.

A :class:`~foon2asp.asp.grounding.Grounding` (decided by :func:`foon2asp.methods.plan.plan`)
names the entry encoding, the facts and clingo's arguments; the session loads the entry (clingo
resolves its ``#include`` directives), adds the facts, grounds once and answers goal after goal: one
plain optimisation, the prepared part's search (:mod:`foon2asp.asp.prepared`) or the
multi-shot :class:`~foon2asp.asp.multishot.driver.Driver`, as the grounding says.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import clingo

from foon2asp.asp import encoding_files, objectives, substitute_facts
from foon2asp.asp.answers import Shot, Watch, cost_vector, finish, solve_shot, status
from foon2asp.asp.canonical import canonicalise
from foon2asp.asp.control import Control
from foon2asp.asp.facts import fact_objects
from foon2asp.asp.grounding import Grounding, canonical_grounding, fact_programs
from foon2asp.asp.multishot.driver import Driver
from foon2asp.asp.prepared import search
from foon2asp.bounds.upper import cheapest_tree
from foon2asp.tree.gap import first_level, settle
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, meal_of, measures

#: the statistics of a goal decided without a solve call
NO_SOLVE = {"choices": 0, "conflicts": 0, "models": 0, "solve_s": 0.0}


class Session:
    """One grounding (:class:`Grounding`), ground once, asked goal after goal."""

    def __init__(self, grounding: Grounding):
        self.grounding = grounding
        self.prepared = grounding.prepared
        self.options = grounding.options
        self.problem = grounding.problem
        self.units = grounding.units
        #: the goal (as a meal) this session was grounded for; None: any goal
        self.goal = grounding.goal
        #: no solve has run yet (the solver state of any fresh session of the same grounding)
        self._fresh = True
        self._driver: Driver | None = None
        #: the lower bound the last solve proved (solver weights per level)
        self._lower: tuple[int, ...] | None = None
        #: the fact programs of the grounding (:func:`fact_programs`)
        self._programs: list[tuple[str, str]] | None = None
        self.control = self._grounded()
        self.goal_atoms = self._goal_atoms()

    def _grounded(self, args: tuple[str, ...] | None = None) -> Control:
        """A control with this session's encodings and facts, grounded (``args``: clingo's
        arguments instead of the grounding's)."""
        g = self.grounding
        control = Control(list(g.args if args is None else args))
        control.statistics = g.prepared is None
        if self._programs is None:  # written once: a single-shot session grounds them again for each round
            self._programs = fact_programs(g)
        programs = self._programs
        control.add_all(programs[:1])  # the problem's facts first, then the encodings that read them
        for name in g.files():
            control.load(encoding_files.entry(name))
        control.add_all(programs[1:], user=[name for name, _ in self.options.programs])
        control.ground()
        return control

    def _renew(self) -> Control:
        """A fresh grounding of this single-shot session for another solve call."""
        self.control = self._grounded()
        return self.control

    def _for_cuts(self) -> Control:
        """A fresh grounding of this single-shot session as one multi-shot control, for the rounds
        after a loop cut (the plan's ``cut_args``)."""
        self.control = self._grounded(self.grounding.cut_args)
        return self.control

    def _goal_atoms(self) -> set[int]:
        """The objects a solve may switch on as goals."""
        if self.goal is not None:
            return set(self.goal)
        if self.options.programs:  # a user program may add objects
            return {
                a.symbol.arguments[0].number
                for a in self.control.ctl.symbolic_atoms.by_signature("goal", 1)
                if a.is_external
            }
        return fact_objects(self.problem, list(self.units))

    def solve(
        self,
        goal: Goals,
        on_model: Callable[[clingo.Model], bool | None] | None = None,
        time_limit: float | None = None,
        floor: int | None = None,
    ) -> TaskTree:
        """The best tree for ``goal`` (an object id, or a tuple of them: a meal), proven optimal
        unless time runs out or ``options.gap`` is reached (then with its lower bound and gap).

        ``floor``: a lower bound on the first objective's weight (the landmarks).
        """
        meal = meal_of(goal)
        self._lower = None
        tree = self._solve(meal, on_model, time_limit, floor)
        if self._driver is not None:
            # the driver's solves weigh other levels: only the depth bound counts
            self._lower = None
            depth = self._driver.depth_floor()
            if depth is not None:
                floor = max(floor or 0, depth)
        if len(meal) > 1 and tree.status == "unreachable":
            self._explain(meal, tree)
        if tree.status == "unknown" and self.grounding.fallback:
            self._fallback(meal, tree)
        if "substitutes" in self.grounding.facts and tree.has_tree:
            tree.substitutions = substitute_facts.report(self.problem, meal, tree.units, self.options.substitutes)
        if self._lower:
            tree.stats["lower"] = list(self._lower)
        return settle(self.problem, tree, self.levels, self._lower, floor)

    @property
    def levels(self) -> tuple[str, ...]:
        """The names of the solver's priority levels, highest first."""
        return self.grounding.levels

    def _fallback(self, meal: tuple[int, ...], tree: TaskTree) -> None:
        """No tree within the time limit: a cheapest-first tree as ``feasible``."""
        t0 = time.perf_counter()
        units = cheapest_tree(self.problem, meal, self.units, objectives.ranked(self.options)[0])
        if units is None:
            return
        tree.units = executable_order(self.problem, units)
        tree.status = "feasible"
        tree.cost = measures(self.problem, meal, tree.units)
        tree.time_s = round(tree.time_s + time.perf_counter() - t0, 6)
        tree.fallback = "cheapest-first"
        tree.note = "no tree from the solver within the time limit: a cheapest-first tree, not proven optimal"

    def _explain(self, meal: tuple[int, ...], tree: TaskTree) -> None:
        """Which goals of an unreachable meal cannot be made (each solved alone)."""
        alone = [g for g in meal if self._solve((g,), None, None).status == "unreachable"]
        names = "; ".join(str(self.problem.objects[g]) for g in alone)
        why = f"unreachable goal(s): {names}" if alone else "each goal can be made alone, but not all in one tree"
        earlier = tree.reason  # e.g. the depth bound
        tree.reason = f"{earlier}; {why}" if earlier else why
        tree.unreachable_goals = [self.problem.objects[g].to_json() for g in alone]

    def _solve(
        self,
        meal: tuple[int, ...],
        on_model: Callable[[clingo.Model], bool | None] | None,
        time_limit: float | None,
        floor: int | None = None,
    ) -> TaskTree:
        """The search the grounding names for ``meal``: the prepared part's, the driver's, or one plain
        optimisation and then the canonical tree; the proven lower bound goes to ``_lower``."""
        if self.prepared is not None:
            return self._solve_prepared(meal, on_model, time_limit)
        if self.grounding.driven:
            if self._driver is None:
                self._driver = Driver(self)
            return self._driver.solve(meal if len(meal) > 1 else meal[0], on_model, time_limit)
        if self.goal is not None and meal != self.goal:
            raise ValueError(f"a session grounded for {self.goal} cannot solve {meal}")
        time_limit = self.options.time_limit if time_limit is None else time_limit
        t0 = time.perf_counter()
        if any(g not in self.goal_atoms for g in meal):
            return self._tree(meal, None, "unreachable", t0, dict(NO_SOLVE))
        canonical = self.grounding.canonical
        here = canonical == "here" and self._fresh
        self._fresh = False
        mode, count = ("optN", 2) if canonical != "none" else ("opt", 1)
        watch = Watch(first_level(self.levels), self.options.gap, floor, self.options.progress)

        def seen(model: clingo.Model) -> bool | None:
            watch.on_model(model)
            return on_model(model) if on_model is not None else None

        with self.control.switched(clingo.Function("goal", [clingo.Number(g)]) for g in meal):
            shot = solve_shot(self.control, mode, count, seen, time_limit or None, watch.on_lower, watch.stop)
            self._lower = shot.lower
            if shot.last is not None and shot.finished and shot.last.proven:
                self._lower = cost_vector(shot.last)
            stats = self.control.stats()
            answer, start = self._choose(shot)
            if start is not None and here:
                answer = self._canonicalise(start, t0, time_limit, stats)
        if start is not None and not here:
            left = None if not time_limit else max(0.0, time_limit - (time.perf_counter() - t0))
            if left is None or left > 0:
                return self._canonical_session(meal, left, t0)
            answer, stats["canonical_search"] = start, "time"
        return self._tree(meal, answer, status(answer, shot), t0, stats)

    def _solve_prepared(
        self,
        meal: tuple[int, ...],
        on_model: Callable[[clingo.Model], bool | None] | None,
        time_limit: float | None,
    ) -> TaskTree:
        """The search over the prepared part, stopped once a tree meets the lower bound; the hint
        when its cost is the optimum (or, with the canonical tree searched here, the smallest optimal tree)."""
        prep = self.prepared
        assert prep is not None
        time_limit = self.options.time_limit if time_limit is None else time_limit
        t0 = time.perf_counter()
        deadline = None if not time_limit else t0 + time_limit
        renew = self._renew if self.grounding.single_shot else None
        if renew is not None and not self._fresh:
            renew()  # this goal was solved before: a single-shot control solves once
        self._fresh = False
        watch = Watch(first_level(self.levels), self.options.gap, prep.floor, self.options.progress)
        shot, answer, lower, cuts = search(
            self.control,
            prep,
            self.problem,
            self.grounding.closed,
            deadline,
            watch,
            on_model,
            self._for_cuts if renew else None,
        )
        cost = None if answer is None else cost_vector(answer)
        self._lower = cost if answer is not None and answer.proven else lower
        stats = self.control.stats()
        if cuts:
            stats["loop_cuts"] = cuts
        if answer is not None and answer.proven and prep.known is not None and cost == prep.known:
            answer.units = sorted(prep.hint)  # the hint is an optimum: the tree answered for this cost
        elif answer is not None and answer.proven and self.grounding.canonical == "here":
            answer = self._canonicalise(answer, t0, time_limit, stats)
        elif not shot.finished and prep.known is not None and (cost is None or prep.known < cost):
            answer = TaskTree(meal[0], self.options.method, "feasible", sorted(prep.hint), asp_cost=list(prep.known))
            stats["answer"] = "known"
        return self._tree(meal, answer, status(answer, shot), t0, stats)

    def _tree(self, meal: tuple[int, ...], answer: TaskTree | None, status: str, t0: float, stats: dict) -> TaskTree:
        return finish(self.problem, self.options.method, meal, status, answer, time.perf_counter() - t0, stats)

    def _choose(self, shot: Shot) -> tuple[TaskTree | None, TaskTree | None]:
        """The answer of ``shot``, and an optimal tree to search the canonical tree from (None: none)."""
        answer = shot.last
        if answer is None or not shot.finished:
            return answer, None
        if len(shot.answers) > 1:
            return answer, shot.answers[0]  # the distinct optimal trees are proven
        return answer, None

    def _canonicalise(self, start: TaskTree, t0: float, time_limit: float | None, stats: dict) -> TaskTree:
        """The smallest optimal tree (proven), searched from ``start`` here; a search cut short is
        noted in ``stats``."""
        deadline = None if not time_limit else t0 + time_limit
        answer, complete = canonicalise(self.control, start, deadline)
        if not complete:
            stats["canonical_search"] = "budget" if not deadline or time.perf_counter() < deadline else "time"
        answer.status = "optimal"
        return answer

    def _canonical_session(self, meal: tuple[int, ...], time_limit: float | None, t0: float) -> TaskTree:
        """Solve ``meal`` again in its canonical session (a fresh grounding of its part)."""
        session = Session(canonical_grounding(self.grounding, meal))
        tree = session._solve(meal, None, time_limit if time_limit is not None else 0.0)
        tree.time_s = round(time.perf_counter() - t0, 6)
        tree.stats["canonical_session"] = True
        return tree
