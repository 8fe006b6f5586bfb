"""Runners for many goals: pruned groundings and exact shortcuts around the solver.

Three ways to build the runner of a registered ASP method for a batch:

* ``whole`` -- one grounding for all goals (:class:`~foon2asp.solver.Session`,
  the goal switched as an external), restricted to the *viable* units (units
  that fire in the kitchen's least fixpoint).  No other unit can ever be a
  candidate of a tree, so the answers do not change.
* ``per-goal`` -- a small grounding per goal holding only the goal's
  *relevant part*: the viable producers of the goal, of their required
  inputs, and so on (the encoding's ``candidate/1`` units), with the kitchen
  items among their inputs.  The cost of a query then depends on the size of
  the goal's part, not of the FOON; use it for very large FOONs.
* shortcuts (both modes, on by default) that answer without the solver when
  the answer is forced:

  - the goal is not derivable from the kitchen: ``unreachable``;
  - every object of the relevant part has exactly one viable producer: the
    whole part is the only tree (each of its units is needed and together
    they fire), so it is the optimum of every objective that only adds
    non-negative weights per used unit (:data:`MONOTONE`).

  Shortcuts are taken only for plain optimisation (no user programs, extra
  encodings, depth bounds, human steps, alternatives or greedy heuristics);
  anything else goes to the solver.

Search methods (kind ``search``) are built once on the whole problem, as
:func:`foon2asp.methods.runner` does.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Iterable, Iterator
from dataclasses import replace
from functools import cached_property

from foon2asp import methods
from foon2asp.asp.facts import neglog_weight
from foon2asp.asp.objectives import ranked
from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem, walk_back
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, meal_of, measures

GROUNDINGS = ("whole", "per-goal")

#: objectives whose cost is a sum of non-negative weights of the used units,
#: with the cost term the solver reports for a tree (``asp_cost``)
MONOTONE = {
    "units": lambda problem, units: len(units),
    "success": lambda problem, units: sum(neglog_weight(problem.rates[u]) for u in units),
    "inputs": lambda problem, units: sum(len(problem.inputs[u]) for u in units),
}


class Parts:
    """Viable units and per-goal relevant parts of one problem (computed once)."""

    def __init__(self, problem: Problem):
        self.problem = problem
        _, unit_level = problem.derivation_levels()
        #: units that fire in the kitchen's least fixpoint
        self.viable: frozenset[int] = frozenset(unit_level)
        #: object -> its viable producers
        self.producers: dict[int, list[int]] = {}
        for obj, units in problem.producers.items():
            keep = [u for u in units if u in self.viable]
            if keep:
                self.producers[obj] = keep

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
        and all(name in MONOTONE for name in ranked(options))
    )


def _view(problem: Problem, objects: set[int]) -> Problem:
    """``problem`` with the kitchen cut down to ``objects`` (shares everything else)."""
    view = copy.copy(problem)
    view.kitchen = frozenset(o for o in objects if o in problem.kitchen)
    return view


class BatchRunner:
    """The runner of one registered method for many goals (see the module docstring)."""

    def __init__(
        self,
        name: str,
        problem: Problem,
        options: AspOptions | None = None,
        grounding: str = "whole",
        shortcuts: bool = True,
        parts: Parts | None = None,
    ):
        if grounding not in GROUNDINGS:
            raise ValueError(f"unknown grounding {grounding!r}")
        self.name = name
        self.problem = problem
        self.options = options or AspOptions()
        self.grounding = grounding
        self.kind = methods.get(name).kind
        self.parts = parts if parts is not None else Parts(problem)
        self.shortcuts = shortcuts and self.kind == "asp" and plain(self.options)
        #: how each goal was answered: "solver" | "unreachable" | "no-choice"
        self.counts = {"solver": 0, "unreachable": 0, "no-choice": 0}
        self._label: str | None = None
        self._whole = None
        if self.kind != "asp":
            self._whole = methods.runner(name, problem, self.options)
        elif grounding == "whole":
            units = self.options.units
            if units is None:
                units = tuple(sorted(self.parts.viable))
            self._whole = methods.runner(name, problem, replace(self.options, units=units))

    def _solve(self, goal: Goals) -> TaskTree:
        self.counts["solver"] += 1
        if self._whole is not None:
            tree = self._whole(goal)
        else:
            units, objects, _ = self.parts.relevant(goal)
            if self.options.units is not None:
                keep = set(self.options.units)
                units = [u for u in units if u in keep]
            view = _view(self.problem, objects)
            tree = methods.runner(self.name, view, replace(self.options, units=tuple(units)))(goal)
        self._label = tree.method
        return tree

    def __call__(self, goal: Goals) -> TaskTree:
        """The tree for ``goal``: an object id, or a tuple of them (a meal, one tree for all)."""
        meal = meal_of(goal)
        if len(meal) > 1 and self.kind != "asp":
            raise InputError(f"meals (several goals in one tree) need an ASP method; {self.name!r} is not one")
        if not self.shortcuts or self._label is None or self.options.units is not None or len(meal) > 1:
            # meals go to the solver: it names the goals that cannot be made
            return self._solve(meal if len(meal) > 1 else meal[0])
        goal = meal[0]
        t0 = time.perf_counter()
        if goal not in self.parts.derivable:
            self.counts["unreachable"] += 1
            return TaskTree(
                goal,
                self._label,
                "unreachable",
                time_s=round(time.perf_counter() - t0, 6),
                stats={"shortcut": "unreachable"},
            )
        units, _, choice = self.parts.relevant(goal)
        if choice:
            return self._solve(goal)
        self.counts["no-choice"] += 1
        order = executable_order(self.problem, units)
        asp_cost = [MONOTONE[name](self.problem, order) for name in ranked(self.options)]
        return TaskTree(
            goal,
            self._label,
            "optimal",
            order,
            measures(self.problem, goal, order),
            round(time.perf_counter() - t0, 6),
            {"shortcut": "no-choice"},
            {"asp_cost": asp_cost},
        )


def solve_goals(
    problem: Problem,
    goals: Iterable[Goals],
    method: str = "asp",
    options: AspOptions | None = None,
    grounding: str = "whole",
    shortcuts: bool = True,
) -> Iterator[TaskTree]:
    """The one path from goals to trees that ``solve``, ``compare``, ``check`` and the library take.

    A goal is an object id, or a tuple of them (a meal: one tree for all).
    ASP methods ground only the units a tree for one of ``goals`` can use
    (:meth:`Problem.units_for`) unless ``options.units`` says otherwise.
    """
    options = options or AspOptions()
    goals = list(goals)
    if methods.get(method).kind == "asp" and options.units is None:
        options = replace(options, units=problem.units_for({g for goal in goals for g in meal_of(goal)}))
    runner = BatchRunner(method, problem, options, grounding, shortcuts)
    for goal in goals:
        yield runner(goal)
