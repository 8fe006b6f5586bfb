"""An independent validator for task trees.

It does not use the encodings nor :meth:`Problem.derivation_levels`: it
replays the units on plain objects, straight from the FOON, the kitchen and
the utensil rule, so it can be trusted to judge every answer.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from foon2asp.foon.model import FoonObject
from foon2asp.foon.problem import Problem, product_outputs, required_flags


@dataclass
class Validation:
    valid: bool
    #: the first problem found, in words (None when valid)
    problem: str | None = None
    #: an executable order of the units that can fire
    order: list[int] = field(default_factory=list)
    #: units that can never fire with these units
    stuck: list[int] = field(default_factory=list)


def _required(problem: Problem, u: int) -> list[FoonObject]:
    unit = problem.units[u]
    flags = required_flags(unit, problem.utensils, problem.utensil_rule)
    return [o for o, f in zip(unit.inputs, flags) if f]


def _products(problem: Problem, u: int) -> list[FoonObject]:
    return product_outputs(problem.units[u])


def validate(problem: Problem, goal: FoonObject | int, units: list[int]) -> Validation:
    """Is ``goal`` derivable from the kitchen with exactly these ``units``?

    Valid means: every unit id exists, every unit can fire (all its required
    inputs are kitchen items or made by units that fired before) and the goal
    is had at the end.  The set is judged, not the order given.
    """
    goal_obj = problem.objects[goal] if isinstance(goal, int) else goal
    for u in units:
        if not (isinstance(u, int) and 0 <= u < len(problem.units)):
            return Validation(False, f"unit {u!r} is not in the FOON")
    have = set(problem.kitchen_items)
    pending = list(dict.fromkeys(units))
    order: list[int] = []
    progress = True
    while progress:
        progress = False
        for u in list(pending):
            if all(o in have for o in _required(problem, u)):
                pending.remove(u)
                order.append(u)
                have.update(_products(problem, u))
                progress = True
    if pending:
        u = pending[0]
        missing = [o for o in _required(problem, u) if o not in have]
        return Validation(
            False,
            f"unit {u} ({problem.units[u].motion}) never fires: missing input {missing[0]}",
            order,
            pending,
        )
    if goal_obj not in have:
        return Validation(False, f"goal {goal_obj} is not made by these units", order)
    return Validation(True, None, order)


def check_order(problem: Problem, goal: FoonObject | int, units: list[int]) -> str | None:
    """None if ``units`` run in the given order make the goal; else the first problem."""
    goal_obj = problem.objects[goal] if isinstance(goal, int) else goal
    have = set(problem.kitchen_items)
    for step, u in enumerate(units, 1):
        for o in _required(problem, u):
            if o not in have:
                return f"step {step} (unit {u}) needs {o}, which is not had yet"
        have.update(_products(problem, u))
    return None if goal_obj in have else f"goal {goal_obj} is not made"
