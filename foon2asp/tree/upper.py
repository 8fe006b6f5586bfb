"""A cheap, valid tree for any derivable goal: an upper bound, not an optimum.

:func:`cheapest_tree` runs Knuth's generalisation of Dijkstra's algorithm over
the units: the kitchen items cost 0, a unit costs its weight plus the costs
of its required inputs, and an object is settled by its cheapest unit once
that unit's inputs are settled.  Following the settling units back from the
goals gives a well-founded tree (every unit's inputs were settled before its
product), which is then made irredundant: units whose removal keeps every
goal derivable are dropped, heaviest first.  The solver uses it when it has
no tree of its own within the time limit.
"""

from __future__ import annotations

import heapq
import math
import time
from collections.abc import Callable, Iterable

from foon2asp.foon.problem import Problem

#: objective name -> weight of a unit (the others, e.g. depth, count units)
WEIGHTS: dict[str, Callable[[Problem, int], float]] = {
    "success": lambda problem, u: -math.log(max(problem.rates[u], 1e-9)) + 1e-6,
    "inputs": lambda problem, u: float(len(problem.inputs[u])),
}


def cheapest_tree(
    problem: Problem,
    goals: Iterable[int],
    units: Iterable[int] | None = None,
    objective: str = "units",
    prune_s: float = 0.5,
) -> list[int] | None:
    """The units of a tree that makes every goal from the kitchen, using only ``units``
    (None: all); None when some goal cannot be made.  ``prune_s`` bounds the time spent
    dropping redundant units."""
    weight = WEIGHTS.get(objective, lambda problem, u: 1.0)
    allowed = range(len(problem.units)) if units is None else units
    kitchen = problem.kitchen
    cost: dict[int, float] = {o: 0.0 for o in kitchen}
    best: dict[int, int] = {}
    waiting: dict[int, int] = {}
    users: dict[int, list[int]] = {}
    heap: list[tuple[float, int, int]] = []

    def fire(u: int) -> None:
        c = weight(problem, u) + sum(cost[i] for i in problem.required[u])
        for o in problem.products[u]:
            if o not in cost:
                heapq.heappush(heap, (c, o, u))

    for u in allowed:
        need = [i for i in problem.required[u] if i not in kitchen]
        waiting[u] = len(need)
        for i in need:
            users.setdefault(i, []).append(u)
        if not need:
            fire(u)
    wanted = set(goals)
    left = {g for g in wanted if g not in kitchen}
    while heap and left:
        c, o, u = heapq.heappop(heap)
        if o in cost:
            continue
        cost[o], best[o] = c, u
        left.discard(o)
        for v in users.get(o, ()):
            waiting[v] -= 1
            if waiting[v] == 0:
                fire(v)
    if left:
        return None
    tree: set[int] = set()
    stack = [g for g in wanted if g not in kitchen]
    seen = set(stack)
    while stack:
        u = best[stack.pop()]
        if u in tree:
            continue
        tree.add(u)
        for i in problem.required[u]:
            if i not in kitchen and i not in seen:
                seen.add(i)
                stack.append(i)
    return _irredundant(problem, wanted, tree, weight, time.perf_counter() + prune_s)


def _irredundant(
    problem: Problem, goals: set[int], tree: set[int], weight: Callable[[Problem, int], float], deadline: float
) -> list[int]:
    """``tree`` without the units every goal can do without (heaviest first, until ``deadline``)."""
    for u in sorted(tree, key=lambda u: (-weight(problem, u), u)):
        if time.perf_counter() > deadline:
            break
        rest = sorted(tree - {u})
        made, _ = problem.derivation_levels(rest)
        if all(g in made for g in goals):
            tree.discard(u)
    return sorted(tree)
