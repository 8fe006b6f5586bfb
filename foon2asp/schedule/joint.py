"""Joint scheduling by trees: every tree that could beat a known makespan, each scheduled alone.

A schedule's first makers of what is needed form a tree of their own that is
as short, in which every unit makes the goal or something another unit needs.
So the joint optimum is the best fixed-tree optimum over such trees whose
work (each unit at its least duration) fits the agents within the known
makespan and whose units can each end within it (``asp/encodings/schedule_trees.lp``
enumerates them).  They are scheduled one by one (:func:`foon2asp.schedule.solve.schedule_fixed`),
lowest lower bound first, stopping when the next lower bound reaches the best
makespan found: the best is then proven.  Ties go to the fewest human units,
then the tree objective.  When there are more than :data:`MAX_TREES` such trees
the caller solves tree and schedule in one encoding instead.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import clingo

from foon2asp.asp import encodings
from foon2asp.asp.control import Control
from foon2asp.asp.objectives import neglog_sum
from foon2asp.foon.problem import Problem
from foon2asp.schedule.model import Instance, divisor

#: the most trees looked at one by one
MAX_TREES = 200


@dataclass
class Trees:
    """The trees found (sorted unit ids), complete unless the cap or the time limit ended it."""

    trees: list[tuple[int, ...]]
    complete: bool


def candidate_trees(
    inst: Instance,
    head: dict[int, int],
    tail: dict[int, int],
    horizon: int,
    tree_parts: Sequence[tuple[str, str]],
    args: Sequence[str],
    time_limit: float | None,
    cap: int | None = None,
) -> Trees:
    """The trees (over ``inst``'s candidate units; ``tree_parts``: tree.lp and its facts) whose
    work fits the agents within ``horizon`` and whose units can each end within it."""
    cap = MAX_TREES if cap is None else cap
    g = divisor(inst)
    late = [u for u in inst.units if u not in head or u not in tail or head[u] + tail[u] > horizon]
    lines = [f"work({u},{inst.min_duration(u) // g})." for u in inst.units if inst.durations[u]]
    lines += [f"too_late({u})." for u in late]
    lines.append(f"capacity({len(inst.agents) * (horizon // g)}).")
    parts = [
        *tree_parts,
        ("encodings/schedule_trees.lp", encodings.encoding("schedule_trees")),
        ("bounds", "\n".join(lines) + "\n"),
    ]
    control = Control(["--opt-mode=ignore", "--models=0", *args])
    control.add_all(parts)
    control.ground()
    found: list[tuple[int, ...]] = []

    def on_model(model: clingo.Model) -> bool:
        found.append(tuple(sorted(s.arguments[0].number for s in model.symbols(shown=True) if s.name == "use")))
        return len(found) <= cap

    result = control.solve(on_model, time_limit)
    return Trees(found[:cap], result.finished and len(found) <= cap)


def tree_cost(problem: Problem, units: Sequence[int], human: Sequence[int], ranked: Sequence[str]) -> tuple:
    """The tree objective of ``units`` as the solver ranks it (a person's unit succeeds for sure)."""
    out: list[Any] = []
    for name in ranked:
        if name == "units":
            out.append(len(units))
        elif name == "success":
            out.append(neglog_sum(problem, units, human))
        elif name == "inputs":
            out.append(sum(len(problem.inputs[u]) for u in units))
    return (*out, tuple(sorted(units)))


def best_tree(
    trees: list[tuple[int, ...]],
    lower: Callable[[tuple[int, ...]], int],
    solve: Callable[[tuple[int, ...], float | None], Any],
    key: Callable[[Any], tuple],
    time_limit: float | None,
) -> tuple[Any, bool]:
    """The best result of ``solve`` over ``trees`` by ``key`` (makespan first), lowest
    ``lower`` bound first; (best, proven): proven when every tree was solved to its optimum
    or its bound shows it cannot beat the best."""
    t0 = time.perf_counter()
    ranked = sorted(trees, key=lambda t: (lower(t), t))
    best, proven = None, True
    for t in ranked:
        if best is not None and lower(t) > best.makespan:
            break  # sorted: no later tree can reach the best makespan
        left = None if time_limit is None else max(0.0, time_limit - (time.perf_counter() - t0))
        if left == 0.0:
            return best, False
        r = solve(t, left)
        if r.status != "optimal":
            proven = False
        if r.has_schedule and (best is None or key(r) < key(best)):
            best = r
    return best, proven
