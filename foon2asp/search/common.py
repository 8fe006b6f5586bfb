"""What every search baseline returns: a task tree with status found/not-found."""

from __future__ import annotations

import time

from foon2asp.foon.problem import Problem
from foon2asp.tree.tasktree import TaskTree, measures


def result(problem: Problem, goal: int, method: str, units: list[int] | None, t0: float) -> TaskTree:
    elapsed = round(time.perf_counter() - t0, 6)
    if units is None:
        return TaskTree(goal, method, "not-found", time_s=elapsed)
    return TaskTree(goal, method, "found", units, measures(problem, goal, units), elapsed)
