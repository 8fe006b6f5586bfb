"""Ground and solve with the clingo Python API, one grounding for many goals.

Each :meth:`Session.solve` switches ``goal(G)`` on for one goal or a meal and runs one
plain optimisation, the prepared part's search (:mod:`foon2asp.asp.prepared`) or the
:class:`~foon2asp.asp.multishot.driver.Driver` when the options ask for more.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from functools import lru_cache

import clingo

from foon2asp.asp import encodings, objectives, substitute_facts
from foon2asp.asp.answers import Shot, Watch, solve_shot, status, task_tree
from foon2asp.asp.canonical import canonical_problem, canonicalise, chain_facts
from foon2asp.asp.control import Answer, Control
from foon2asp.asp.facts import OPTIONAL, fact_objects, facts
from foon2asp.asp.multishot.driver import Driver
from foon2asp.asp.options import OBJECTIVES, AspOptions, check_objectives
from foon2asp.asp.prepared import Preparation, search
from foon2asp.foon.problem import Problem
from foon2asp.tree.gap import first_level, levels, settle
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, meal_of, measures
from foon2asp.tree.upper import cheapest_tree


def _objective_facts(objective: Iterable[str]) -> str:
    objective = list(objective)
    check_objectives(objective)
    n = len(objective)
    return "".join(f"objective({name},{n - i}).\n" for i, name in enumerate(objective))


_OPTIONAL_FACTS = re.compile(r"\b(" + "|".join((*OPTIONAL, "input_nodes")) + r")\s*\(")


@lru_cache(maxsize=256)
def _mentions(text: str) -> frozenset[str]:
    """The optional fact predicates (facts.OPTIONAL, input_nodes) ``text`` mentions (comments too)."""
    return frozenset(m.group(1) for m in _OPTIONAL_FACTS.finditer(text))


#: the statistics of a goal decided without a solve call
NO_SOLVE = {"choices": 0, "conflicts": 0, "models": 0, "solve_s": 0.0}


class Session:
    """One grounding of ``problem`` with the tree encoding and an objective."""

    def __init__(
        self,
        problem: Problem,
        options: AspOptions | None = None,
        goal: Goals | None = None,
        prepared: Preparation | None = None,
    ):
        """``goal``: a session for this goal (or meal) alone; ``prepared``: a session for one goal's
        prepared part.  It grounds ``options.units`` (None: the viable units)."""
        self.prepared = prepared
        #: the prepared part is searched as closed sets with loop cuts
        self._closed = prepared is not None and not (options and (options.programs or options.threads > 1))
        units: Iterable[int] | None = None if options is None else options.units
        if prepared is not None:
            goal, units = prepared.goal, prepared.candidates
        #: the goal (as a meal) this session was grounded for; None: any goal
        self.goal = None if goal is None else meal_of(goal)
        self.options = options or AspOptions()
        problem = self.problem = substitute_facts.prepare(problem, self.options)
        own = []
        if (
            prepared is not None
            and prepared.hint
            and (prepared.bound is not None or (self.options.opt_strategy or "").startswith("bb"))
        ):
            # the hint steers a decision or a search from above (core-guided search climbs from below)
            own.append("--heuristic=Domain")
        #: an optimisation over the prepared part is one solve call: clingo may preprocess as for one shot
        self._single = prepared is not None and prepared.bound is None and self.options.threads == 1
        if self._single:
            own.append("--single-shot")
        self._args = self.options.args(own)
        if units is None:
            units = sorted(problem.viable_units)
        self.units = tuple(units)
        #: no solve has run yet (the solver state of any fresh session of the same grounding)
        self._fresh = True
        self._driver: Driver | None = None
        #: the lower bound the last solve proved (solver weights per level)
        self._lower: tuple[int, ...] | None = None
        programs = self._parts()
        self.control = self._grounded(programs)
        #: the programs again for a fresh grounding (a single-shot control solves once)
        self._programs = programs if self._single else None
        self.goal_atoms = self._goal_atoms()

    def _grounded(self, programs: list[tuple[str, str]]) -> Control:
        """A control with ``programs`` (this session's), grounded."""
        control = Control(self._args)
        control.statistics = self.prepared is None
        control.add_all(programs, user=[name for name, _ in self.options.programs])
        control.ground()
        return control

    def _renew(self) -> Control:
        """A fresh grounding of this single-shot session for another solve call."""
        assert self._programs is not None
        self.control = self._grounded(self._programs)
        return self.control

    def _parts(self) -> list[tuple[str, str]]:
        """The named programs of the grounding: facts, encodings, objective, goal, extras."""
        options, units = self.options, list(self.units)
        names = objectives.encoding_names(options, OBJECTIVES) + options.encodings
        if self.prepared is not None:
            names = ["closed" if self._closed else "prepared"] + [n for n in names if n != "dominance"]
        else:
            names = ["tree"] + names
        rules = [(f"encodings/{n}.lp", encodings.encoding(n)) for n in dict.fromkeys(names)]
        rules.append(("objective", _objective_facts(objectives.ranked(options))))
        rules += objectives.extra_parts(self.problem, options, units, dominated=self.prepared is None)
        if self.goal is None:
            rules.append(("goal", "#external goal(O) : object(O).\n"))
        else:
            rules.append(("goal", "".join(f"goal({g}).\n" for g in self.goal)))
        if self.prepared is not None:
            rules.append(("preparation", self.prepared.facts()))
        if options.canonical and not options.heuristic and (self.prepared is None or options.threads > 1):
            rules.append(("encodings/canonical.lp", encodings.encoding("canonical")))
            rules.append(("unit order", chain_facts(units)))
        rules += list(options.programs)
        # facts nobody reads are left out (only encodings and user programs read facts)
        readers = {name for name, _ in options.programs}
        read = set().union(
            *(_mentions(text) for name, text in rules if name.startswith("encodings/") or name in readers)
        )
        rules = [(name, text) for name, text in rules if name != "input nodes" or "input_nodes" in read]
        leave_out = [p for p in OPTIONAL if p not in read]
        whole = self.prepared is None
        declare = whole or bool(options.programs)  # prepared.lp reads neither unit/1 nor object/1
        text = facts(self.problem, units=units, leave_out=leave_out, whole_kitchen=whole, declare=declare)
        return [("facts", text)] + rules

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
        known: tuple[Sequence[int], Sequence[int]] | None = None,
        floor: int | None = None,
    ) -> TaskTree:
        """The best tree for ``goal`` (an object id, or a tuple of them: a meal), proven optimal
        unless time runs out or ``options.gap`` is reached (then with its lower bound and gap).

        ``known``: a valid tree the caller has and its solver cost vector; ``floor``: a lower
        bound on the first objective's weight (the landmarks).
        """
        meal = meal_of(goal)
        self._lower = None
        tree = self._solve(meal, on_model, time_limit, known, floor)
        if self.options.driven and self._driver is not None:
            # the driver's solves weigh other levels: only the depth bound counts
            self._lower = None
            depth = self._driver.depth_floor()
            if depth is not None:
                floor = max(floor or 0, depth)
        if len(meal) > 1 and tree.status == "unreachable":
            self._explain(meal, tree)
        if tree.status == "unknown" and self.options.plain:
            self._fallback(meal, tree)
        if substitute_facts.applies(self.options) and tree.has_tree:
            tree.extra["substitutions"] = substitute_facts.report(
                self.problem, meal, tree.units, self.options.substitutes
            )
        if self._lower:
            tree.stats["lower"] = list(self._lower)
        return settle(self.problem, tree, self.levels, self._lower, floor)

    @property
    def levels(self) -> tuple[str, ...]:
        """The names of the solver's priority levels, highest first."""
        o = self.options
        return levels(objectives.ranked(o), substitute_facts.applies(o), o.human_steps is not None)

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
        tree.extra["fallback"] = "cheapest-first"
        tree.extra["note"] = "no tree from the solver within the time limit: a cheapest-first tree, not proven optimal"

    def _explain(self, meal: tuple[int, ...], tree: TaskTree) -> None:
        """Which goals of an unreachable meal cannot be made (each solved alone)."""
        alone = [g for g in meal if self._solve((g,), None, None).status == "unreachable"]
        names = "; ".join(str(self.problem.objects[g]) for g in alone)
        why = f"unreachable goal(s): {names}" if alone else "each goal can be made alone, but not all in one tree"
        earlier = tree.extra.get("reason")  # e.g. the depth bound
        tree.extra["reason"] = f"{earlier}; {why}" if earlier else why
        tree.extra["unreachable_goals"] = [self.problem.objects[g].to_json() for g in alone]

    def _solve(
        self,
        meal: tuple[int, ...],
        on_model: Callable[[clingo.Model], bool | None] | None,
        time_limit: float | None,
        known: tuple[Sequence[int], Sequence[int]] | None = None,
        floor: int | None = None,
    ) -> TaskTree:
        """One plain optimisation for ``meal`` (the driver or the prepared search when those
        apply), then the canonical tree; the proven lower bound goes to ``_lower``."""
        if self.prepared is not None:
            return self._solve_prepared(meal, on_model, time_limit)
        if self.options.driven:
            if self._driver is None:
                self._driver = Driver(self)
            return self._driver.solve(meal if len(meal) > 1 else meal[0], on_model, time_limit)
        time_limit = self.options.time_limit if time_limit is None else time_limit
        t0 = time.perf_counter()
        if any(g not in self.goal_atoms for g in meal):
            return self._tree(meal, None, "unreachable", t0, dict(NO_SOLVE))
        here = self._canonical_here(meal)
        # with a known tree, one plain optimisation decides whether it is optimal
        plain = known is not None and self.options.canonical and not here
        mode, count = ("optN", 2) if self.options.canonical and not plain else ("opt", 1)
        watch = Watch(first_level(self.levels), self.options.gap, floor, self.options.progress)
        if known is not None:
            watch.cost = tuple(known[1])

        def seen(model: clingo.Model) -> bool | None:
            watch.on_model(model)
            return on_model(model) if on_model is not None else None

        with self.control.switched(clingo.Function("goal", [clingo.Number(g)]) for g in meal):
            shot = solve_shot(self.control, mode, count, seen, time_limit or None, watch.on_lower, watch.stop)
            self._lower = shot.lower
            if shot.last is not None and shot.finished and shot.last.proven:
                self._lower = shot.last.cost
            stats = self.control.stats()
            answer, start = self._choose(shot, known, plain)
            if not shot.finished and known is not None and (answer is None or tuple(known[1]) < answer.cost):
                answer = Answer(tuple(sorted(known[0])), tuple(known[1]), False)
                stats["answer"] = "known"
            if start is not None and here:
                answer = self._canonicalise(start, t0, time_limit, stats)
        if start is not None and not here:
            left = None if not time_limit else max(0.0, time_limit - (time.perf_counter() - t0))
            if left is None or left > 0:
                return self._canonical_session(meal, known, left, t0)
            answer, stats["canonical_search"] = start, "time"
        return self._tree(meal, answer, status(answer, shot), t0, stats)

    def _solve_prepared(
        self,
        meal: tuple[int, ...],
        on_model: Callable[[clingo.Model], bool | None] | None,
        time_limit: float | None,
    ) -> TaskTree:
        """The search over the prepared part, stopped once a tree meets the lower bound; the hint
        when its cost is the optimum (with several threads, the smallest optimal tree)."""
        prep = self.prepared
        assert prep is not None
        time_limit = self.options.time_limit if time_limit is None else time_limit
        t0 = time.perf_counter()
        deadline = None if not time_limit else t0 + time_limit
        renew = self._renew if self._single else None
        if renew is not None and not self._fresh:
            renew()  # this goal was solved before: a single-shot control solves once
        self._fresh = False
        watch = Watch(first_level(self.levels), self.options.gap, prep.floor, self.options.progress)
        shot, answer, lower, cuts = search(
            self.control, prep, self.problem, self._closed, deadline, watch, on_model, renew
        )
        self._lower = answer.cost if answer is not None and answer.proven else lower
        stats = self.control.stats()
        if cuts:
            stats["loop_cuts"] = cuts
        if answer is not None and answer.proven and prep.known is not None and answer.cost == prep.known:
            answer = Answer(tuple(sorted(prep.hint)), answer.cost, True, answer.human)
        elif answer is not None and answer.proven and self.options.canonical and self.options.threads > 1:
            answer = self._canonicalise(answer, t0, time_limit, stats)
        elif not shot.finished and prep.known is not None and (answer is None or prep.known < answer.cost):
            answer = Answer(tuple(sorted(prep.hint)), prep.known, False)
            stats["answer"] = "known"
        return self._tree(meal, answer, status(answer, shot), t0, stats)

    def _tree(self, meal: tuple[int, ...], answer: Answer | None, status: str, t0: float, stats: dict) -> TaskTree:
        return task_tree(self.problem, self.options.method, meal, status, answer, time.perf_counter() - t0, stats)

    def _canonical_here(self, meal: tuple[int, ...]) -> bool:
        """Is this session ``meal``'s canonical session (fresh, grounded for the meal's part)?  It is
        no longer fresh afterwards."""
        if self.goal is not None and meal != self.goal:
            raise ValueError(f"a session grounded for {self.goal} cannot solve {meal}")
        here = False
        if self._fresh and self.goal == meal and self.options.canonical:
            view, part = canonical_problem(self.problem, meal)
            here = self.units == part and self.problem.kitchen == view.kitchen
        self._fresh = False
        return here

    def _choose(
        self, shot: Shot, known: tuple[Sequence[int], Sequence[int]] | None, plain: bool
    ) -> tuple[Answer | None, Answer | None]:
        """The answer of ``shot``, and an optimal tree to search the canonical tree from (None: none)."""
        answer = shot.last
        if answer is None or not shot.finished:
            return answer, None
        if known is not None and self.options.canonical and answer.cost == tuple(known[1]):
            return Answer(tuple(sorted(known[0])), answer.cost, answer.proven, answer.human), None
        if plain:
            return answer, Answer(answer.units, answer.cost, True)
        if len(shot.answers) > 1:
            smallest = shot.answers[0]
            return answer, Answer(smallest.units, smallest.cost, True)
        return answer, None

    def _canonicalise(self, start: Answer, t0: float, time_limit: float | None, stats: dict) -> Answer:
        """The smallest optimal tree, searched from ``start`` here; a search cut short is noted in ``stats``."""
        deadline = None if not time_limit else t0 + time_limit
        answer, complete = canonicalise(self.control, start, deadline)
        if not complete:
            stats["canonical_search"] = "budget" if not deadline or time.perf_counter() < deadline else "time"
        return Answer(answer.units, answer.cost, True, answer.human)

    def _canonical_session(
        self,
        meal: tuple[int, ...],
        known: tuple[Sequence[int], Sequence[int]] | None,
        time_limit: float | None,
        t0: float,
    ) -> TaskTree:
        """Solve ``meal`` again in its canonical session (a fresh grounding of its part)."""
        view, part = canonical_problem(self.problem, meal)
        session = Session(view, replace(self.options, units=part), goal=meal)
        tree = session._solve(meal, None, time_limit if time_limit is not None else 0.0, known)
        tree.time_s = round(time.perf_counter() - t0, 6)
        tree.stats["canonical_session"] = True
        return tree
