"""A cheap, valid tree for any derivable goal: an upper bound, not an optimum.

Why it is a tree: docs/proofs/preparation.md, "The cheapest-set tree".
"""

from __future__ import annotations

import heapq
import time
from collections.abc import Iterable, Sequence

from foon2asp.foon.problem import Implied, Problem
from foon2asp.tree.weights import UNIT_WEIGHTS, lexicographic

#: the longest time spent dropping redundant units from a cheapest-set tree
PRUNE_S = 0.5


def cheapest_tree(
    problem: Problem,
    goals: Iterable[int],
    units: Iterable[int] | None = None,
    objective: str = "units",
) -> list[int] | None:
    """The units of a tree that makes every goal from the kitchen, using only ``units``
    (None: all); None when some goal cannot be made.  ``objective``: a key of
    :data:`~foon2asp.tree.weights.UNIT_WEIGHTS` (any other, e.g. depth, counts units).  Dropping
    redundant units stops after :data:`PRUNE_S` seconds."""
    wanted = set(goals)
    w = lexicographic(problem, objective if objective in UNIT_WEIGHTS else "units")
    sets = cheapest_sets(problem, w, units, wanted)
    if any(g not in sets for g in wanted):
        return None
    tree = set(frozenset().union(*(sets[g] for g in wanted)))
    deadline = time.perf_counter() + PRUNE_S
    for u in sorted(tree, key=lambda u: (-w[u], u)):  # drop the units no goal needs, heaviest first
        if time.perf_counter() > deadline:
            break
        made, _ = problem.derivation_levels(sorted(tree - {u}))
        if all(g in made for g in wanted):
            tree.discard(u)
    return sorted(tree)


def cheapest_sets(
    problem: Problem, w: Sequence[float], units: Iterable[int] | None = None, goals: Iterable[int] = ()
) -> dict[int, frozenset[int]]:
    """Object -> its cheapest-set tree (kitchen items: the empty set), by Knuth's
    generalisation of Dijkstra's algorithm over sets of units priced by their total weight
    ``w`` (ties: fewer units, then unit and object ids).  With ``goals`` the search stops
    once all of them are settled."""
    pool = range(len(problem.units)) if units is None else units
    kitchen = problem.kitchen
    settled: dict[int, frozenset[int]] = Implied({}, kitchen, frozenset())
    waiting: dict[int, int] = {}
    users: dict[int, list[int]] = {}
    heap: list[tuple[float, int, int, int, frozenset[int]]] = []

    def fire(u: int) -> None:
        s = frozenset().union(*(settled[i] for i in problem.required[u])) | {u}
        c = sum(w[x] for x in s)
        for o in problem.products[u]:
            if o not in settled:
                heapq.heappush(heap, (c, len(s), u, o, s))

    for u in pool:
        req = {i for i in problem.required[u] if i not in kitchen}
        waiting[u] = len(req)
        for i in req:
            users.setdefault(i, []).append(u)
        if not req:
            fire(u)
    left = {g for g in goals if g not in kitchen}
    stop = bool(left)
    while heap:
        _, _, _, o, s = heapq.heappop(heap)
        if o in settled:
            continue
        settled[o] = s
        left.discard(o)
        if stop and not left:
            break
        for u in users.get(o, ()):
            waiting[u] -= 1
            if waiting[u] == 0:
                fire(u)
    return settled
