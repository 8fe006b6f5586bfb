"""Producer scores of the greedy baselines (higher is better)."""

from __future__ import annotations

from collections.abc import Callable

from foon2asp.foon.problem import Problem

Score = Callable[[Problem, int], float]


def h1(problem: Problem, u: int) -> float:
    """Greedy score by motion success rate: higher is better."""
    return problem.rates[u]


def h2(problem: Problem, u: int) -> float:
    """Greedy score by input nodes: fewer is better."""
    return -len(problem.inputs[u])
