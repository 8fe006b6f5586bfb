"""Why a task tree is not valid: the first problem, walking back from the goal."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from foon2asp.foon.problem import Problem
from foon2asp.foon.treefiles import TreeFile
from foon2asp.tree.validate import Validation, circular_support, validate, walk_back


@dataclass
class Finding:
    """The first problem of an invalid tree."""

    #: "unknown-unit" | "missing-input" | "cycle" | "goal-not-made"; for a file that gives no units
    #: for its goal: "unreachable" (the FOON confirms there is no tree) or "no-tree" (there is one)
    kind: str
    message: str
    #: for a cycle: (object, unit) pairs -- the object is made by the unit, which
    #: needs the next pair's object; the last unit needs the first object
    cycle: list[tuple[int, int]] = field(default_factory=list)
    #: the object that is missing or not made (missing-input, goal-not-made)
    obj: int | None = None
    #: the unit that needs the missing object
    unit: int | None = None


def describe_unit(problem: Problem, u: int, tree: TreeFile | None = None, ids: list[int | None] | None = None) -> str:
    """``unit 12 (mix, step 3 at tree.txt:40)``."""
    where = ""
    if tree is not None and ids is not None and u in ids:
        tu = tree.units[ids.index(u)]
        where = f", step {tu.step}" + (f" at line {tu.line}" if tu.line else "")
    return f"unit {u} ({problem.units[u].motion}{where})"


def diagnose(
    problem: Problem, goal: int, units: list[int], validation: Validation, name: Callable[[int], str] | None = None
) -> Finding | None:
    """The first problem of a tree that does not validate (None when it does): a missing input
    (not in the kitchen, made by no unit of the tree) or circular support, walking back from the
    goal, then from each stuck unit; ``name(u)`` words a unit in messages."""
    if validation.valid:
        return None
    name = name or (lambda u: describe_unit(problem, u))
    have = set(problem.kitchen).union(*(problem.products[u] for u in validation.order))
    makers: dict[int, list[int]] = {}
    for u in dict.fromkeys(units):
        for o in problem.products[u]:
            makers.setdefault(o, []).append(u)

    def lacking(u: int) -> list[int]:
        return [i for i in problem.required[u] if i not in have]

    roots = [(goal, None)] if goal not in have else []
    found = walk_back(roots + [(i, u) for u in validation.stuck for i in lacking(u)], makers, lacking)
    if found is None:
        return Finding("goal-not-made", validation.problem or "the tree is not valid", obj=goal)
    if found[0] == "cycle":
        cycle = found[1]
        return Finding("cycle", circular_support([(problem.objects[o], u) for o, u in cycle], name), cycle)
    obj, needed_by = found[1]
    if needed_by is None:
        return Finding("goal-not-made", f"no unit of the tree makes the goal {problem.objects[goal]}", obj=goal)
    return Finding(
        "missing-input",
        f"missing input: {problem.objects[obj]} is needed by {name(needed_by)} "
        "but is not in the kitchen and no unit of the tree makes it",
        obj=obj,
        unit=needed_by,
    )


def check_units(
    problem: Problem, goal: int, units: list[int], name: Callable[[int], str] | None = None
) -> tuple[Validation, Finding | None]:
    """Validate FOON unit ids for ``goal`` and explain the first problem."""
    validation = validate(problem, goal, units)
    return validation, diagnose(problem, goal, units, validation, name)
