"""Task trees: a goal, units in executable order, status and measures."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from foon2asp.foon.problem import Problem

STATUSES = ("optimal", "ranked", "feasible", "unreachable", "unknown", "found", "not-found")


@dataclass
class TaskTree:
    """The answer for one goal by one method.

    ``units`` are unit ids in executable order (empty when there is no tree).
    ``status``: ``optimal`` | ``feasible`` | ``unreachable`` | ``unknown`` for
    ASP methods, ``found`` | ``not-found`` for the search baselines.
    """

    goal: int
    method: str
    status: str
    units: list[int] = field(default_factory=list)
    cost: dict = field(default_factory=dict)
    time_s: float = 0.0
    stats: dict = field(default_factory=dict)
    extra: dict = field(default_factory=dict)

    @property
    def has_tree(self) -> bool:
        return self.status in ("optimal", "ranked", "feasible", "found")


def executable_order(problem: Problem, units: list[int] | set[int]) -> list[int]:
    """``units`` sorted so each runs after the units that make its inputs.

    Units that can never fire (their inputs rest on a cycle) go last, in id
    order; callers that need validity use :mod:`foon2asp.validate`.
    """
    units = sorted(set(units))
    _, level = problem.derivation_levels(units)
    return sorted(units, key=lambda u: (level.get(u, math.inf), u))


def measures(problem: Problem, goal: int, units: list[int]) -> dict:
    """Every measure of a tree: units, success product, input nodes, depth."""
    obj_level, _ = problem.derivation_levels(list(units))
    success = 1.0
    for u in units:
        success *= problem.rates[u]
    depth = obj_level.get(goal)
    return {
        "units": len(units),
        "success": float(f"{success:.6g}"),
        "inputs": sum(len(problem.inputs[u]) for u in units),
        "depth": depth,
    }
