"""Greedy best-first search, faithful to the earlier FOON programs (no cycle check)."""

from __future__ import annotations

import time
from collections import deque

from foon2asp.foon.problem import Problem
from foon2asp.search.common import result
from foon2asp.search.heuristics import Score
from foon2asp.tree.tasktree import TaskTree


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
            return result(problem, goal, method, None, t0)
        # max() keeps the first of equal scores; producers are in FOON file order
        unit = max(candidates, key=lambda u: score(problem, u))
        if unit in selected:
            continue
        selected[unit] = None
        queue.extend(i for i in problem.required[unit] if i not in searched)
    units = list(selected)
    units.reverse()
    return result(problem, goal, method, units, t0)
