"""Ground and solve with the clingo Python API; decode models into task trees.

A :class:`Session` grounds the facts of a whole problem together with the
encodings once; each :meth:`Session.solve` then switches the external atom
``goal(G)`` on for one goal, so many goals reuse one grounding.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable, Iterable

import clingo

from . import programs
from .errors import InputError
from .facts import facts
from .problem import Problem
from .tree import TaskTree, executable_order, measures

#: objective name -> encoding that defines it (all use objective(Name,Priority))
OBJECTIVES: dict[str, str] = {"units": "units"}


@dataclass
class AspOptions:
    """How to solve: objectives (lexicographic, first = most important) and solver settings."""

    objective: tuple[str, ...] = ("units",)
    #: extra ASP programs as (name, text): user constraints and the like
    programs: list[tuple[str, str]] = field(default_factory=list)
    #: extra encodings (names in encodings/) to load
    encodings: list[str] = field(default_factory=list)
    time_limit: float | None = None
    opt_strategy: str | None = None
    threads: int = 1
    clingo_args: list[str] = field(default_factory=list)

    @property
    def method(self) -> str:
        return "asp-" + ",".join(self.objective)

    def args(self) -> list[str]:
        args = ["--opt-mode=opt"]
        if self.opt_strategy:
            args.append(f"--opt-strategy={self.opt_strategy}")
        if self.threads and self.threads > 1:
            args.append(f"--parallel-mode={self.threads}")
        return args + list(self.clingo_args)


class _Logger:
    def __init__(self) -> None:
        self.messages: list[str] = []

    def __call__(self, code: clingo.MessageCode, message: str) -> None:
        self.messages.append(" ".join(message.split()))


def _objective_facts(objective: Iterable[str]) -> str:
    objective = list(objective)
    for name in objective:
        if name not in OBJECTIVES:
            raise InputError(f"unknown objective {name!r} (have {', '.join(sorted(OBJECTIVES))})")
    n = len(objective)
    return "".join(f"objective({name},{n - i}).\n" for i, name in enumerate(objective))


class Session:
    """One grounding of ``problem`` with the tree encoding and an objective."""

    def __init__(self, problem: Problem, options: AspOptions | None = None, units: Iterable[int] | None = None):
        self.problem = problem
        self.options = options or AspOptions()
        self._log = _Logger()
        self.ctl = clingo.Control(self.options.args(), logger=self._log, message_limit=20)
        names = ["tree"] + [OBJECTIVES[o] for o in self.options.objective] + self.options.encodings
        parts = [("facts", facts(problem, units=units))]
        parts += [(f"encodings/{n}.lp", programs.encoding(n)) for n in dict.fromkeys(names)]
        parts.append(("objective", _objective_facts(self.options.objective)))
        parts.append(("goal", "#external goal(O) : object(O).\n"))
        parts += list(self.options.programs)
        t0 = time.perf_counter()
        for name, text in parts:
            self._add(name, text)
        self._ground()
        self.ground_s = time.perf_counter() - t0
        self.goal_atoms = {
            a.symbol.arguments[0].number
            for a in self.ctl.symbolic_atoms.by_signature("goal", 1)
            if a.is_external
        }

    def _add(self, name: str, text: str) -> None:
        self._log.messages.clear()
        try:
            self.ctl.add("base", [], text)
        except RuntimeError:
            raise InputError(self._message(name), name) from None

    def _ground(self) -> None:
        self._log.messages.clear()
        try:
            self.ctl.ground([("base", [])])
        except RuntimeError:
            raise InputError(self._message("grounding")) from None

    def _message(self, name: str) -> str:
        msg = self._log.messages[0] if self._log.messages else "error"
        return msg.replace("<block>", name)

    def _set_goal(self, goal: int, value: bool) -> None:
        self.ctl.assign_external(clingo.Function("goal", [clingo.Number(goal)]), value)

    def solve(
        self,
        goal: int,
        on_model: Callable[[clingo.Model], None] | None = None,
        time_limit: float | None = None,
    ) -> TaskTree:
        """The best tree for ``goal`` (an object id), proven optimal unless time runs out."""
        time_limit = self.options.time_limit if time_limit is None else time_limit
        t0 = time.perf_counter()
        if goal not in self.goal_atoms:
            # the goal is not an object of the grounded facts: nothing makes it
            return TaskTree(goal, self.options.method, "unreachable", time_s=time.perf_counter() - t0)
        best: dict = {}

        def record(model: clingo.Model) -> None:
            best["units"] = [s.arguments[0].number for s in model.symbols(shown=True) if s.name == "use"]
            best["cost"] = list(model.cost)
            best["proven"] = model.optimality_proven
            if on_model is not None:
                on_model(model)

        self._set_goal(goal, True)
        try:
            with self.ctl.solve(on_model=record, async_=True) as handle:
                finished = bool(handle.wait(time_limit)) if time_limit else (handle.wait() or True)
                if not finished:
                    handle.cancel()
                result = handle.get()
        finally:
            self._set_goal(goal, False)
        elapsed = time.perf_counter() - t0
        if "units" in best:
            # no cost terms at all (e.g. the goal is in the kitchen): any model is optimal
            proven = best["proven"] or not any(best["cost"])
            status = "optimal" if (result.exhausted and not result.interrupted) or proven else "feasible"
            if not finished and not proven:
                status = "feasible"
        else:
            status = "unreachable" if result.unsatisfiable else "unknown"
        units = executable_order(self.problem, best.get("units", []))
        cost = measures(self.problem, goal, units) if status in ("optimal", "feasible") else {}
        return TaskTree(
            goal,
            self.options.method,
            status,
            units,
            cost,
            round(elapsed, 6),
            self.stats(),
            {"asp_cost": best.get("cost", [])} if best else {},
        )

    def stats(self) -> dict:
        s = self.ctl.statistics
        try:
            solving = s["solving"]["solvers"]
            summary = s["summary"]
            return {
                "choices": int(solving["choices"]),
                "conflicts": int(solving["conflicts"]),
                "models": int(summary["models"]["enumerated"]),
                "solve_s": round(summary["times"]["solve"], 6),
            }
        except (KeyError, RuntimeError):
            return {}


def solve_goals(problem: Problem, goals: Iterable[int], options: AspOptions | None = None) -> list[TaskTree]:
    """Solve each goal in turn on one grounding."""
    session = Session(problem, options)
    return [session.solve(g) for g in goals]
