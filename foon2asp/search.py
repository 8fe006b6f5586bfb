"""The classic task-tree searches: IDS and greedy best-first search (h1, h2).

They are faithful to the earlier FOON search programs, weaknesses included:
neither checks that the tree it returns is well-founded, so a greedy tree may
rest on a cycle (``foon2asp check`` and ``foon2asp compare`` report that).
All read the semantics from :class:`~foon2asp.problem.Problem`:
``required`` (the utensil rule), ``producers`` (outputs with no state,
ingredient or container are not products) and ``kitchen``.

* ``ids`` -- iterative deepening: a depth-limited recursive search from the
  goal with bound 0, 1, 2, ...  An object in the kitchen succeeds; otherwise,
  with depth left, the producers are tried in FOON file order and a unit
  succeeds when all its required inputs succeed with one level less.  Results
  are memoised per (object, depth), so a bound costs at most
  objects x depth unit tries.  A goal not found within as many levels as the
  kitchen's derivation fixpoint has is not found (no deeper tree exists).
* ``gbfs-h1`` / ``gbfs-h2`` -- a FIFO queue of objects, starting with the
  goal; already searched objects are skipped, kitchen objects are done,
  otherwise one producer is chosen by the heuristic and its required inputs
  are queued.  h1: highest motion success rate; h2: fewest input nodes
  (all inputs of the unit).  Ties go to the unit first in FOON file order.
  An object with no producer makes the search fail.  The tree is the
  selected units in reverse selection order, as the earlier programs wrote
  it; that order is kept as it is, even when it is not executable.

Status is ``found`` or ``not-found``; the cost is :func:`~foon2asp.tree.measures`.
"""

from __future__ import annotations

import time
from collections import deque
from typing import Callable

from .methods import Runner, register
from .problem import Problem
from .solver import AspOptions
from .tree import TaskTree, executable_order, measures

#: sentinel in the IDS memo: the object is a kitchen item
_KITCHEN = -1


def _result(problem: Problem, goal: int, method: str, units: list[int] | None, t0: float) -> TaskTree:
    elapsed = round(time.perf_counter() - t0, 6)
    if units is None:
        return TaskTree(goal, method, "not-found", time_s=elapsed)
    return TaskTree(goal, method, "found", units, measures(problem, goal, units), elapsed)


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
                return _result(self.problem, goal, "ids", units, t0)
        return _result(self.problem, goal, "ids", None, t0)


def h1(problem: Problem, u: int) -> float:
    """Greedy score by motion success rate: higher is better."""
    return problem.rates[u]


def h2(problem: Problem, u: int) -> float:
    """Greedy score by input nodes: fewer is better."""
    return -len(problem.inputs[u])


def gbfs(problem: Problem, goal: int, score: Callable[[Problem, int], float], method: str) -> TaskTree:
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
    units = list(selected)
    units.reverse()
    return _result(problem, goal, method, units, t0)


@register("ids", "search", "iterative deepening search (first producer in FOON order per depth; not optimal)")
def _ids(problem: Problem, options: AspOptions) -> Runner:
    return IDS(problem)


@register("gbfs-h1", "search", "greedy best-first, h1: highest motion success rate (no cycle check)")
def _gbfs_h1(problem: Problem, options: AspOptions) -> Runner:
    return lambda goal: gbfs(problem, goal, h1, "gbfs-h1")


@register("gbfs-h2", "search", "greedy best-first, h2: fewest input nodes (no cycle check)")
def _gbfs_h2(problem: Problem, options: AspOptions) -> Runner:
    return lambda goal: gbfs(problem, goal, h2, "gbfs-h2")
