"""Ground and solve with the clingo Python API; decode models into task trees.

A :class:`Session` grounds the facts of a whole problem together with the
encodings once; each :meth:`Session.solve` then switches the external atom
``goal(G)`` on for one goal, so many goals reuse one grounding.  A *meal* (a
tuple of goal ids) switches ``goal(G)`` on for each of its goals: the tree
must make all of them, and a unit two dishes share is counted once.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from typing import Any

import clingo

from foon2asp.asp import encodings, objectives, substitutes
from foon2asp.asp.canonical import canonical_problem, canonicalise, chain_facts
from foon2asp.asp.control import Answer, Control
from foon2asp.asp.facts import OPTIONAL, fact_objects, facts
from foon2asp.asp.multishot.driver import Driver
from foon2asp.asp.options import OBJECTIVES, AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, goal_fields, meal_of, measures
from foon2asp.tree.upper import cheapest_tree


def _objective_facts(objective: Iterable[str]) -> str:
    objective = list(objective)
    for name in objective:
        if name not in OBJECTIVES:
            raise InputError(f"unknown objective {name!r} (have {', '.join(sorted(OBJECTIVES))})")
    n = len(objective)
    return "".join(f"objective({name},{n - i}).\n" for i, name in enumerate(objective))


_OPTIONAL_FACTS = re.compile(r"\b(" + "|".join((*OPTIONAL, "input_nodes")) + r")\s*\(")


def _read_predicates(parts: list[tuple[str, str]]) -> set[str]:
    """The optional fact predicates (facts.OPTIONAL, input_nodes) some program mentions
    outside the part that defines them (a mention in a comment counts too: harmless)."""
    return {m.group(1) for name, text in parts if name != "input nodes" for m in _OPTIONAL_FACTS.finditer(text)}


class Session:
    """One grounding of ``problem`` with the tree encoding and an objective."""

    def __init__(
        self,
        problem: Problem,
        options: AspOptions | None = None,
        units: Iterable[int] | None = None,
        require: Iterable[int] = (),
        goal: Goals | None = None,
    ):
        """``units``: ground only these (default ``options.units``, else the viable units);
        ``require``: units every tree must use (a caller that knows them, e.g. landmarks);
        ``goal``: a session for this goal (or meal) alone, grounded with the goal as a fact
        (the grounder then simplifies what follows from it: core-guided proofs on hard parts
        take about half the time of a goal switched on as an external)."""
        #: the goal (as a meal) this session was grounded for, None: any goal, switched per solve
        self.goal = None if goal is None else meal_of(goal)
        self.options = options or AspOptions()
        # with substitutes, what they stand in for counts as available (foon2asp.asp.substitutes)
        problem = self.problem = substitutes.prepare(problem, self.options)
        self.control = Control(self.options.args())
        self.ctl = self.control.ctl
        names = ["tree"] + objectives.encoding_names(self.options, OBJECTIVES) + self.options.encodings
        if units is None:
            units = self.options.units
        if units is None:
            # a unit that never fires in the kitchen's fixpoint is never a candidate
            units = sorted(problem.viable_units)
        units = list(units)
        self.units = tuple(units)
        rules = [(f"encodings/{n}.lp", encodings.encoding(n)) for n in dict.fromkeys(names)]
        rules.append(("objective", _objective_facts(objectives.ranked(self.options))))
        rules += objectives.extra_parts(problem, self.options, units)
        if self.goal is None:
            rules.append(("goal", "#external goal(O) : object(O).\n"))
        else:
            rules.append(("goal", "".join(f"goal({g}).\n" for g in self.goal)))
        if self.options.canonical and not self.options.heuristic:
            rules.append(("encodings/canonical.lp", encodings.encoding("canonical")))
            rules.append(("unit order", chain_facts(units)))
        required = sorted(set(require))
        self.required = tuple(required)
        #: no solve has run yet: the solver state is the same as in any fresh session of the same grounding
        self._fresh = True
        if required:
            rules.append(("required units", "".join(f":- not use({u}).\n" for u in required)))
        rules += list(self.options.programs)
        # facts nobody reads are left out (the strings, input/2, ...: user constraints read them)
        read = _read_predicates(rules)
        rules = [(name, text) for name, text in rules if name != "input nodes" or "input_nodes" in read]
        leave_out = [p for p in OPTIONAL if p not in read]
        parts = [("facts", facts(problem, units=units, leave_out=leave_out))] + rules
        t0 = time.perf_counter()
        self.control.add_all(parts, user=[name for name, _ in self.options.programs])
        self.control.ground()
        self.ground_s = time.perf_counter() - t0
        self._driver: Driver | None = None
        conf: Any = self.ctl.configuration.solve
        self._plain_conf = (conf.opt_mode, conf.models, conf.project)
        if self.options.canonical:
            # up to two distinct optimal trees in one solve: a second one calls for canonicalise()
            conf.opt_mode, conf.models, conf.project = "optN", "2", "project"
        if self.goal is not None:
            self.goal_atoms = set(self.goal)  # the goal is a fact: the solver decides
        elif self.options.programs:
            # a user program may add objects: ask the grounder
            self.goal_atoms = {
                a.symbol.arguments[0].number for a in self.ctl.symbolic_atoms.by_signature("goal", 1) if a.is_external
            }
        else:
            # the goal externals: one per object of the facts (no scan of the grounded atoms)
            self.goal_atoms = fact_objects(problem, units)

    def _set_goal(self, goal: int, value: bool) -> None:
        self.control.assign({clingo.Function("goal", [clingo.Number(goal)]): value})

    def solve(
        self,
        goal: Goals,
        on_model: Callable[[clingo.Model], None] | None = None,
        time_limit: float | None = None,
        known: tuple[Sequence[int], Sequence[int]] | None = None,
    ) -> TaskTree:
        """The best tree for ``goal`` (an object id, or a tuple of them: a meal, one tree
        that makes every goal), proven optimal unless time runs out.

        ``known`` is a valid tree the caller has, with its cost vector (as the solver
        reports it): when its cost is the proven optimum it is the answer, otherwise
        the canonical (smallest) optimal tree is; either way no second optimal model
        is searched for first.
        """
        meal = meal_of(goal)
        tree = self._solve(meal, on_model, time_limit, known)
        if len(meal) > 1 and tree.status == "unreachable":
            self._explain(meal, tree)
        if tree.status == "unknown" and self._plain():
            self._fallback(meal, tree)
        if substitutes.applies(self.options) and tree.has_tree:
            tree.extra["substitutions"] = substitutes.report(self.problem, meal, tree.units, self.options.substitutes)
        return tree

    def _plain(self) -> bool:
        """Is every tree of the grounded units an answer (no constraints, bounds or alternatives)?"""
        o = self.options
        return not (
            o.programs
            or o.encodings
            or o.max_depth is not None
            or o.human_steps is not None
            or o.models > 1
            or o.all_optimal
            or o.heuristic
            or o.substitutes
        )

    def _fallback(self, meal: tuple[int, ...], tree: TaskTree) -> None:
        """No tree within the time limit (core-guided search finds none before its proof):
        report a cheapest-first tree (foon2asp.tree.upper) as ``feasible``."""
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
        on_model: Callable[[clingo.Model], None] | None,
        time_limit: float | None,
        known: tuple[Sequence[int], Sequence[int]] | None = None,
    ) -> TaskTree:
        goal = meal if len(meal) > 1 else meal[0]
        if self.options.driven:
            # depth bounds, human steps, alternatives, greedy: see foon2asp.driver
            if self._driver is None:
                self._driver = Driver(self)
            return self._driver.solve(goal, on_model, time_limit)
        time_limit = self.options.time_limit if time_limit is None else time_limit
        t0 = time.perf_counter()
        if any(g not in self.goal_atoms for g in meal):
            # a goal is not an object of the grounded facts: nothing makes it (no solve call)
            stats: dict[str, Any] = {"choices": 0, "conflicts": 0, "models": 0, "solve_s": 0.0}
            return TaskTree(
                method=self.options.method,
                status="unreachable",
                time_s=time.perf_counter() - t0,
                stats=stats,
                **goal_fields(meal),
            )
        # a fresh session on the goal's own part is its canonical session (foon2asp.asp.canonical)
        if self.goal is not None and meal != self.goal:
            raise ValueError(f"a session grounded for {self.goal} cannot solve {meal}")
        here = False
        if self._fresh and self.goal == meal and not self.required and self.options.canonical:
            view, part = canonical_problem(self.problem, meal)
            here = self.units == part and self.problem.kitchen == view.kitchen
        self._fresh = False
        best: dict = {}
        optimal: dict[tuple[int, ...], list[int]] = {}
        start: Answer | None = None  # an optimal tree to start the search for the canonical one from

        def record(model: clingo.Model) -> None:
            best["units"] = [s.arguments[0].number for s in model.symbols(shown=True) if s.name == "use"]
            best["cost"] = list(model.cost)
            best["proven"] = model.optimality_proven
            if model.optimality_proven:
                optimal.setdefault(tuple(sorted(best["units"])), best["cost"])
            if on_model is not None:
                on_model(model)

        conf: Any = self.ctl.configuration.solve
        saved = (conf.opt_mode, conf.models, conf.project)
        # with a known tree one plain optimisation decides whether it is optimal; the canonical
        # session always looks for a second optimal tree, so its answer does not depend on `known`
        plain = known is not None and self.options.canonical and not here
        if plain:
            conf.opt_mode, conf.models, conf.project = self._plain_conf
        for g in meal:
            self._set_goal(g, True)
        try:
            result = self.control.solve(record, time_limit or None)
            stats = self.stats()
            conf.opt_mode, conf.models, conf.project = saved
            if (
                known is not None
                and self.options.canonical
                and "units" in best
                and result.finished
                and best["cost"] == list(known[1])
            ):
                best["units"] = list(known[0])  # the known tree is optimal: it is the answer
            elif plain and result.finished and "units" in best:
                start = Answer(tuple(sorted(best["units"])), tuple(best["cost"]), True)
            elif len(optimal) > 1 and result.finished:
                # several optimal trees: return the smallest one, which depends only on the input
                smallest = min(optimal)
                start = Answer(smallest, tuple(optimal[smallest]), True)
            if start is not None and here:
                deadline = None if not time_limit else t0 + time_limit
                answer, complete = canonicalise(self.control, start, deadline)
                best["units"], best["cost"], best["proven"] = list(answer.units), list(answer.cost), True
                if not complete:
                    stats["canonical_search"] = "budget" if not deadline or time.perf_counter() < deadline else "time"
        finally:
            conf.opt_mode, conf.models, conf.project = saved
            for g in meal:
                self._set_goal(g, False)
        elapsed = time.perf_counter() - t0
        if start is not None and not here:
            # the canonical tree comes from the goal's canonical session, whatever this session's history
            left = None if not time_limit else max(0.0, time_limit - elapsed)
            if left is None or left > 0:
                return self._canonical_session(meal, known, left, t0)
            best["units"], best["cost"], best["proven"] = list(start.units), list(start.cost), True
            stats["canonical_search"] = "time"
        if "units" in best:
            # no cost terms at all (e.g. the goal is in the kitchen): any model is optimal
            proven = best["proven"] or not any(best["cost"])
            status = "optimal" if result.finished or proven else "feasible"
        else:
            status = "unreachable" if result.unsatisfiable else "unknown"
        units = executable_order(self.problem, best.get("units", []))
        cost = measures(self.problem, meal, units) if status in ("optimal", "feasible") else {}
        return TaskTree(
            method=self.options.method,
            status=status,
            units=units,
            cost=cost,
            time_s=round(elapsed, 6),
            stats=stats,
            extra={"asp_cost": best.get("cost", [])} if best else {},
            **goal_fields(meal),
        )

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

    def stats(self) -> dict:
        """Choices, conflicts, models and solve time of the last solve call."""
        return self.control.stats()


def solve_goals(problem: Problem, goals: Iterable[int], options: AspOptions | None = None) -> list[TaskTree]:
    """Solve each goal in turn on one grounding."""
    session = Session(problem, options)
    return [session.solve(g) for g in goals]
