"""What a unit weighs under each objective that sums weights of the used units.

The one table (:data:`UNIT_WEIGHTS`) the facts, objectives, bounds and cheapest trees all read.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable

from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem

#: fixed-point scale of success weights: rates are exact to 1/SCALE, logs to 1/SCALE
SCALE = 1000


def success_permille(rate: float) -> int:
    """The success rate in thousandths (1..SCALE), as the facts state it."""
    return max(1, min(SCALE, round(rate * SCALE)))


def neglog_weight(rate: float) -> int:
    """Integer weight round(-SCALE * ln p); summing it maximises the product of rates."""
    return round(-math.log(success_permille(rate) / SCALE) * SCALE)


#: objective -> the non-negative integer weight of unit ``u`` of a problem
UNIT_WEIGHTS: dict[str, Callable[[Problem, int], int]] = {
    "units": lambda problem, u: 1,
    "success": lambda problem, u: neglog_weight(problem.rates[u]),
    "inputs": lambda problem, u: len(problem.inputs[u]),
}


def unit_weight(problem: Problem, objective: str) -> Callable[[int], int]:
    """Unit id -> its weight under ``objective``: :data:`UNIT_WEIGHTS`, and ``cost`` the
    unit's motion cost in hundredths from the problem's motion-cost table
    (:attr:`Problem.motion_costs`, :mod:`foon2asp.foon.motioncost`)."""
    if objective == "cost":
        table = problem.motion_costs
        if table is None:
            raise InputError("the objective 'cost' needs a motion-cost table", hint="motion-cost")
        return lambda u: table.weight(problem.units[u].motion)
    weight = UNIT_WEIGHTS[objective]
    return lambda u: weight(problem, u)


def total(problem: Problem, objective: str, units: Iterable[int]) -> int:
    """The cost of ``units`` under ``objective`` (a key of :data:`UNIT_WEIGHTS`)."""
    weight = UNIT_WEIGHTS[objective]
    return sum(weight(problem, u) for u in units)


def lexicographic(problem: Problem, objective: str) -> list[int]:
    """One weight per unit whose sum orders trees by ``objective``, then by the number of
    units: ``w(u) * M + 1`` with ``M`` the number of units plus one (1 for ``units``)."""
    if objective == "units":
        return [1] * len(problem.units)
    weight = UNIT_WEIGHTS[objective]
    scale = len(problem.units) + 1
    return [weight(problem, u) * scale + 1 for u in range(len(problem.units))]


#: the greedy heuristics of the search baselines and of greedy retrieval in the solver: unit ->
#: its score among the producers of an object, higher first (ties in FOON file order):
#: h1 the highest motion success rate, h2 the fewest input nodes as the FOON lists them
HEURISTICS: dict[str, Callable[[Problem, int], float]] = {
    "h1": lambda problem, u: problem.rates[u],
    "h2": lambda problem, u: -len(problem.inputs[u]),
}
