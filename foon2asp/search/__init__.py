"""Search baselines: the classic task-tree searches: IDS and greedy best-first search (h1, h2).

Each answers ``found`` or ``not-found``; how each searches and where it falls short:
docs/experiment.md.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable

from foon2asp.foon.problem import Problem
from foon2asp.tree.tasktree import TaskTree, executable_order, measures
from foon2asp.tree.weights import HEURISTICS

__all__ = ["IDS", "gbfs", "h1", "h2"]

Score = Callable[[Problem, int], float]

#: sentinel in the IDS memo: the object is a kitchen item
_KITCHEN = -1


def _result(problem: Problem, goal: int, method: str, units: list[int] | None, t0: float) -> TaskTree:
    elapsed = round(time.perf_counter() - t0, 6)
    if units is None:
        return TaskTree(goal, method, "not-found", time_s=elapsed)
    return TaskTree(goal, method, "found", units, measures(problem, goal, units), elapsed)


#: greedy score by motion success rate: higher is better (foon2asp.tree.weights.HEURISTICS)
h1 = HEURISTICS["h1"]
#: greedy score by input nodes: fewer is better
h2 = HEURISTICS["h2"]


def gbfs(problem: Problem, goal: int, score: Score, method: str) -> TaskTree:
    """Greedy best-first search from ``goal`` choosing producers by ``score`` (highest wins)."""
    t0 = time.perf_counter()
    queue = deque([goal])
    searched: set[int] = set()
    selected: dict[int, None] = {}
    while queue:
        obj = queue.popleft()
        if obj in searched:
            continue
        searched.add(obj)
        if obj in problem.kitchen:
            continue
        candidates = problem.producers.get(obj)
        if not candidates:
            return _result(problem, goal, method, None, t0)
        # max() keeps the first of equal scores; producers are in FOON file order
        unit = max(candidates, key=lambda u: score(problem, u))
        if unit in selected:
            continue
        selected[unit] = None
        queue.extend(i for i in problem.required[unit] if i not in searched)
    return _result(problem, goal, method, list(reversed(selected)), t0)


class IDS:
    """Iterative deepening depth-first search over one problem (memo shared by all goals)."""

    def __init__(self, problem: Problem):
        self.problem = problem
        _, unit_level = problem.derivation_levels()
        #: number of fixpoint levels: no object needs a deeper tree than this
        self.max_depth = max(unit_level.values(), default=0)
        #: (object, depth) -> unit chosen, _KITCHEN, or None (fails)
        self.memo: dict[tuple[int, int], int | None] = {}

    def choose(self, obj: int, depth: int) -> int | None:
        """The unit that makes ``obj`` within ``depth`` levels (first in FOON order), or None."""
        key = (obj, depth)
        if key not in self.memo:
            found: int | None = None
            if obj in self.problem.kitchen:
                found = _KITCHEN
            elif depth > 0:
                producers = self.problem.producers.get(obj, ())
                required = self.problem.required
                found = next(
                    (u for u in producers if all(self.choose(i, depth - 1) is not None for i in required[u])), None
                )
            self.memo[key] = found
        return self.memo[key]

    def derivation(self, goal: int, depth: int) -> list[int]:
        """Units of the derivation of ``goal`` at ``depth``, each once, goal's unit first."""
        seen: dict[int, None] = {}
        visited: set[tuple[int, int]] = set()
        stack = [(goal, depth)]
        while stack:
            obj, d = stack.pop()
            if (obj, d) in visited:
                continue
            visited.add((obj, d))
            u = self.choose(obj, d)
            if u is None or u == _KITCHEN:
                continue
            seen.setdefault(u, None)
            stack.extend((i, d - 1) for i in reversed(self.problem.required[u]))
        return list(seen)

    def __call__(self, goal: int) -> TaskTree:
        t0 = time.perf_counter()
        for bound in range(self.max_depth + 1):
            if self.choose(goal, bound) is not None:
                units = self.derivation(goal, bound)[::-1]
                _, level = self.problem.derivation_levels(units)
                if all(u in level for u in units):
                    units = executable_order(self.problem, units)
                return _result(self.problem, goal, "ids", units, t0)
        return _result(self.problem, goal, "ids", None, t0)
