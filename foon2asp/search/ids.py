"""Iterative deepening search, faithful to the earlier FOON programs (see the package docstring)."""

from __future__ import annotations

import time

from foon2asp.foon.problem import Problem
from foon2asp.search.common import result
from foon2asp.tree.tasktree import TaskTree, executable_order

#: sentinel in the IDS memo: the object is a kitchen item
_KITCHEN = -1


class IDS:
    """Iterative deepening depth-first search over one problem (memo shared by all goals)."""

    def __init__(self, problem: Problem):
        self.problem = problem
        obj_level, unit_level = problem.derivation_levels()
        #: number of fixpoint levels: no object needs a deeper tree than this
        self.max_depth = max(unit_level.values(), default=0)
        #: (object, depth) -> unit chosen, _KITCHEN, or None (fails)
        self.memo: dict[tuple[int, int], int | None] = {}

    def choose(self, obj: int, depth: int) -> int | None:
        """The unit that makes ``obj`` within ``depth`` levels (first in FOON order), or None."""
        key = (obj, depth)
        if key in self.memo:
            return self.memo[key]
        problem = self.problem
        if obj in problem.kitchen:
            found: int | None = _KITCHEN
        elif depth == 0:
            found = None
        else:
            found = None
            for u in problem.producers.get(obj, ()):
                if all(self.choose(i, depth - 1) is not None for i in problem.required[u]):
                    found = u
                    break
        self.memo[key] = found
        return found

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
                units = self.derivation(goal, bound)
                units.reverse()
                order = executable_order(self.problem, units)
                _, level = self.problem.derivation_levels(units)
                if all(u in level for u in units):
                    units = order
                return result(self.problem, goal, "ids", units, t0)
        return result(self.problem, goal, "ids", None, t0)
