"""The goal runner's MaxSAT steps: a goal proven by foon2asp.maxsat, then its canonical tree.

:func:`by_maxsat` answers the sum objectives of :mod:`foon2asp.methods.bounds` on a
goal the bounds and the branch and bound leave open; :func:`by_maxsat_depth` answers
depth first, then one of those objectives: no tree is shallower than the goal's level
in the least fixpoint, so the optimum is the least weight among the trees within that
many rounds.  Both solve on the goal's part without the units a dominance rule leaves
out (:mod:`foon2asp.asp.dominance`), and hand the tree found to the goal's canonical
session, which searches for the canonical tree from it (:mod:`foon2asp.asp.canonical`).
Cut short by the time limit or the gap, the answer is ``feasible``: the bounds tree
(or a shallowest tree, for depth) with the lower bound MaxSAT proved.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import replace

from foon2asp.asp.answers import Watch
from foon2asp.asp.canonical import canonical_problem
from foon2asp.asp.dominance import applies as dominance_applies
from foon2asp.asp.dominance import dominance_pairs
from foon2asp.asp.options import AspOptions
from foon2asp.asp.session import Session
from foon2asp.foon.problem import Problem
from foon2asp.maxsat.trees import Result, minimum_tree
from foon2asp.methods.bounds import Bounds
from foon2asp.tree.gap import first_level, settle
from foon2asp.tree.tasktree import TaskTree, executable_order, measures
from foon2asp.tree.weights import total


def answer(
    problem: Problem, goal: int, label: str, order: list[int], ranked: tuple[str, ...], shortcut: str, t0: float
) -> TaskTree:
    """An optimal tree found without clingo's optimisation (``shortcut`` names how)."""
    asp_cost = [total(problem, name, order) if name != "depth" else _depth(problem, goal, order) for name in ranked]
    tree = TaskTree(
        goal,
        label,
        "optimal",
        order,
        measures(problem, goal, order),
        round(time.perf_counter() - t0, 6),
        {"shortcut": shortcut},
        {"asp_cost": asp_cost},
    )
    return settle(problem, tree, ranked)


def _depth(problem: Problem, goal: int, units: list[int]) -> int:
    return measures(problem, goal, units)["depth"] or 0


def undominated(
    problem: Problem, goal: int, units: list[int], ranked: tuple[str, ...], options: AspOptions
) -> list[int]:
    """``units`` without those a unit among them dominates for ``goal`` (none when the rule does not apply)."""
    if not dominance_applies(options, ranked):
        return units
    relevant = {goal}.union(*(problem.required[u] for u in units))
    dominated = {u for _, u, extra in dominance_pairs(problem, units, ranked) if relevant.isdisjoint(extra)}
    return [u for u in units if u not in dominated]


def _stop(ranked: tuple[str, ...], options: AspOptions, upper: Sequence[int], floor: Callable[[int], list[int]]):
    """The ``stop`` of :func:`~foon2asp.maxsat.trees.minimum_tree`: reports the bound to the
    progress display and says when the gap of ``options`` is reached (``floor``: the
    lower bound per level from MaxSAT's)."""
    first = first_level(ranked)
    watch = Watch(first, options.gap, None, options.progress)
    watch.cost = tuple(upper)
    seen = [-1]

    def stop(lower: int) -> bool:
        if lower > seen[0]:
            seen[0] = lower
            watch.on_lower(tuple(floor(lower)))
        return watch.stop()

    return stop


def _stats(found: Result, units: list[int], keep: list[int]) -> dict:
    stats: dict = {"shortcut": "maxsat", "maxsat_s": round(found.time_s, 6), "pruned_units": len(units) - len(keep)}
    if found.cuts:
        stats["loop_cuts"] = found.cuts
    return stats


def _feasible(
    problem: Problem, goal: int, label: str, order: list[int], ranked, cost, stats: dict, lower: list[int], t0: float
) -> TaskTree:
    """A tree cut short, with the lower bound per level."""
    elapsed = round(time.perf_counter() - t0, 6)
    tree = TaskTree(
        goal, label, "feasible", order, measures(problem, goal, order), elapsed, stats, {"asp_cost": list(cost)}
    )
    return settle(problem, tree, ranked, lower)


def _canonical(
    problem: Problem,
    options: AspOptions,
    ranked: tuple[str, ...],
    goal: int,
    label: str,
    units: tuple[int, ...],
    cost: list[int],
    t0: float,
    stats: dict,
) -> TaskTree:
    """The canonical tree searched from the optimal tree ``units`` in the goal's canonical
    session; with the time limit spent, ``units`` as they are (marked)."""
    limit = options.time_limit
    left = None if not limit else limit - (time.perf_counter() - t0)
    if left is not None and left <= 0:
        tree = answer(problem, goal, label, executable_order(problem, list(units)), ranked, "maxsat", t0)
        tree.stats.update(stats, canonical_search="time")
        return tree
    view, part = canonical_problem(problem, [goal])
    tree = Session(view, replace(options, units=part), goal=goal).canonical_from(goal, units, cost, left)
    tree.stats.update(stats)
    tree.time_s = round(time.perf_counter() - t0, 6)
    return tree


def by_maxsat(
    problem: Problem,
    options: AspOptions,
    ranked: tuple[str, ...],
    goal: int,
    label: str,
    units: list[int],
    bounds: Bounds,
    t0: float,
) -> TaskTree:
    """The optimum by MaxSAT on the goal's part pruned by ``bounds``, the landmark units
    required; the canonical tree searched from its tree (the bounds tree when that is optimal)."""
    pruned = bounds.keep(goal, units)
    keep = undominated(problem, goal, pruned, ranked, options)
    best = bounds.tree(goal) or ()
    upper = bounds.cost(best)
    floor = bounds.first_lower(goal)

    def lower_of(weight: int) -> list[int]:
        return [max(floor, bounds.first(weight))]

    limit = options.time_limit
    deadline = t0 + limit if limit else None
    stop = _stop(ranked, options, upper, lower_of)
    found = minimum_tree(problem, goal, keep, bounds.w, bounds.landmarks(goal), deadline, stop)
    stats = _stats(found, units, keep)
    if found.tree is None:  # cut short (no tree cannot be: the bounds tree lies in the pruned part)
        order = executable_order(problem, list(best))
        return _feasible(problem, goal, label, order, ranked, upper, stats, lower_of(found.lower), t0)
    cost = bounds.cost(found.tree)
    if cost == upper or not options.canonical:
        chosen = best if cost == upper else found.tree
        tree = answer(problem, goal, label, executable_order(problem, list(chosen)), ranked, "maxsat", t0)
        tree.stats.update(stats)
        return tree
    return _canonical(problem, options, ranked, goal, label, found.tree, cost, t0, stats)


def by_maxsat_depth(
    problem: Problem,
    options: AspOptions,
    ranked: tuple[str, ...],
    goal: int,
    label: str,
    units: list[int],
    weights: Sequence[int],
    t0: float,
) -> TaskTree:
    """Depth first (``ranked[0]``), then the sum objective ``ranked[1:]`` of ``weights``:
    MaxSAT over the trees within the goal's level."""
    levels, unit_levels = problem.derivation_levels(units)
    depth = levels[goal]
    keep = undominated(problem, goal, units, ranked, options)
    scale = 1 if ranked[1] == "units" else len(problem.units) + 1

    def lower_of(weight: int) -> list[int]:
        return [depth, weight // scale]

    shallow = executable_order(problem, _shallowest(problem, goal, units, levels, unit_levels))
    upper = [depth] + [total(problem, name, shallow) for name in ranked[1:]]
    limit = options.time_limit
    deadline = t0 + limit if limit else None
    found = minimum_tree(problem, goal, keep, weights, (), deadline, _stop(ranked, options, upper, lower_of), depth)
    stats = _stats(found, units, keep)
    if found.tree is None:
        return _feasible(problem, goal, label, shallow, ranked, upper, stats, lower_of(found.lower), t0)
    cost = [depth] + [total(problem, name, found.tree) for name in ranked[1:]]
    if not options.canonical:
        tree = answer(problem, goal, label, executable_order(problem, list(found.tree)), ranked, "maxsat", t0)
        tree.stats.update(stats)
        return tree
    return _canonical(problem, options, ranked, goal, label, found.tree, cost, t0, stats)


def _shallowest(problem: Problem, goal: int, units: list[int], levels, unit_levels: dict[int, int]) -> list[int]:
    """A tree of the least depth: each needed object made by its first producer (in id order)
    among those that fire at the object's level."""
    first: dict[int, int] = {}
    for u in sorted(unit_levels):
        for o in problem.products[u]:
            if o not in first and o in levels and levels[o] == unit_levels[u]:
                first[o] = u
    tree: set[int] = set()
    todo = [goal]
    while todo:
        o = todo.pop()
        if o in problem.kitchen or first[o] in tree:
            continue
        u = first[o]
        tree.add(u)
        todo.extend(problem.required[u])
    return sorted(tree)
