"""Why a task tree is not valid: the first problem, walking back from the goal.

The verdict is :mod:`foon2asp.tree.validate`'s; :func:`diagnose` names a missing input
(not in the kitchen, made by no unit of the tree) or circular support, the cycle as
(object, unit) pairs.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from foon2asp.foon.problem import Problem
from foon2asp.foon.treefiles import TreeFile
from foon2asp.tree.validate import Validation, circular_support, validate


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


def _had(problem: Problem, order: list[int]) -> set[int]:
    have = set(problem.kitchen)
    for u in order:
        have.update(problem.products[u])
    return have


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
    """The first problem of a tree that does not validate, walking back from the goal
    (docs/proofs/preparation.md, "Diagnosis"); ``name(u)`` words a unit in messages."""
    if validation.valid:
        return None
    name = name or (lambda u: describe_unit(problem, u))
    have = _had(problem, validation.order)
    makers: dict[int, list[int]] = {}
    for u in dict.fromkeys(units):
        for o in problem.products[u]:
            makers.setdefault(o, []).append(u)

    def missing(u: int) -> list[int]:
        return [i for i in problem.required[u] if i not in have]

    done: set[int] = set()

    def edges(obj: int):
        return iter([(u, i) for u in makers.get(obj, []) for i in missing(u)])

    def walk(root: int, needed_by: int | None) -> Finding | None:
        """Depth-first search over objects not had; an object on the path again closes a cycle."""
        if root in done or root in have:
            return None
        if not makers.get(root):
            return _missing(problem, root, needed_by, goal, name)
        path: list[list] = [[root, None]]  # [object, unit being tried for it]
        on_path = {root: 0}
        stack = [edges(root)]
        while stack:
            step = next(stack[-1], None)
            if step is None:
                obj = path.pop()[0]
                stack.pop()
                del on_path[obj]
                done.add(obj)
                continue
            u, nxt = step
            path[-1][1] = u
            if nxt in on_path:
                return _cycle(problem, [(o, uu) for o, uu in path[on_path[nxt] :]], name)
            if nxt in done:
                continue
            if not makers.get(nxt):
                return _missing(problem, nxt, u, goal, name)
            on_path[nxt] = len(path)
            path.append([nxt, None])
            stack.append(edges(nxt))
        return None

    if goal not in have:
        found = walk(goal, None)
        if found:
            return found
    for u in validation.stuck:
        for i in missing(u):
            found = walk(i, u)
            if found:
                return found
    return Finding("goal-not-made", validation.problem or "the tree is not valid", obj=goal)


def _missing(problem: Problem, obj: int, needed_by: int | None, goal: int, name: Callable[[int], str]) -> Finding:
    if needed_by is None:
        return Finding("goal-not-made", f"no unit of the tree makes the goal {problem.objects[goal]}", obj=goal)
    return Finding(
        "missing-input",
        f"missing input: {problem.objects[obj]} is needed by {name(needed_by)} "
        "but is not in the kitchen and no unit of the tree makes it",
        obj=obj,
        unit=needed_by,
    )


def _cycle(problem: Problem, cycle: list[tuple[int, int]], name: Callable[[int], str]) -> Finding:
    words = circular_support([(problem.objects[o], u) for o, u in cycle], name)
    return Finding("cycle", words, list(cycle))


def check_units(
    problem: Problem, goal: int, units: list[int], name: Callable[[int], str] | None = None
) -> tuple[Validation, Finding | None]:
    """Validate FOON unit ids for ``goal`` and explain the first problem."""
    validation = validate(problem, goal, units)
    return validation, diagnose(problem, goal, units, validation, name)
