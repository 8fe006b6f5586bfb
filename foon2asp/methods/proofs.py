"""The goal runner's MaxSAT steps: a goal proven by foon2asp.maxsat, then its canonical tree.

:func:`by_maxsat` answers the sum objectives of :mod:`foon2asp.methods.bounds` on a
goal the bounds and the branch and bound leave open; :func:`by_maxsat_depth` answers
depth first, then one of those objectives: no tree is shallower than the goal's level
in the least fixpoint, so the optimum is the least weight among the trees within that
many rounds.  Both solve on the goal's part without the units a dominance rule leaves
out (:mod:`foon2asp.asp.dominance`; the canonical tree uses none of them) and walk on
to the smallest optimal tree in the canonical order (:mod:`foon2asp.asp.canonical`)
inside the MaxSAT solver (:func:`foon2asp.maxsat.trees.minimum_tree`).
Cut short by the time limit or the gap, the answer is ``feasible``: the bounds tree
(or a shallowest tree, for depth) with the lower bound MaxSAT proved.  RC2 hands a goal it
has not proven after :data:`UWR_AFTER_S` to UWrMaxSat, and HiGHS joins after
:func:`mip_after` (:func:`foon2asp.maxsat.trees.minimum_tree`).
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

from foon2asp.asp.answers import Watch
from foon2asp.asp.dominance import Dominators
from foon2asp.asp.dominance import applies as dominance_applies
from foon2asp.asp.options import AspOptions
from foon2asp.foon.problem import Problem
from foon2asp.maxsat.trees import minimum_tree
from foon2asp.methods.bounds import Bounds
from foon2asp.tree.gap import first_level, settle
from foon2asp.tree.tasktree import TaskTree, executable_order, measures
from foon2asp.tree.weights import total

#: seconds of RC2 before HiGHS joins it on the second core (BENCHMARKS.md, "HiGHS beside RC2")
MIP_AFTER_S = 1.0
#: the same for a worker that shares the cores (a batch's pool): the hard-4k batch over every
#: object took 1,183 s with HiGHS after 1 s, 863 s without it (2 answers then not proven)
MIP_AFTER_SHARED_S = 10.0
#: seconds of RC2 before UWrMaxSat takes over from it (BENCHMARKS.md, "UWrMaxSat after RC2")
UWR_AFTER_S = 0.5
#: the processes solving goals at once on this machine's cores (:func:`share_cores`)
_processes = 1


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
    problem: Problem,
    goal: int,
    units: list[int],
    ranked: tuple[str, ...],
    options: AspOptions,
    dominators: Dominators | None = None,
) -> list[int]:
    """``units`` without those a unit among them dominates for ``goal`` (none when the rule
    does not apply); ``dominators``: the problem's, kept by the caller for ``ranked``."""
    if not dominance_applies(options, ranked):
        return units
    dominated = (dominators or Dominators(problem, ranked)).dominated(goal, units)
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


@dataclass
class _Goal:
    """One goal being answered: the problem, the runner's options and ranked objectives, the
    method's label, the goal's relevant part and the time the runner started on it."""

    problem: Problem
    options: AspOptions
    ranked: tuple[str, ...]
    goal: int
    label: str
    units: list[int]
    t0: float

    def answer(self, units: Sequence[int], stats: dict) -> TaskTree:
        order = executable_order(self.problem, list(units))
        tree = answer(self.problem, self.goal, self.label, order, self.ranked, "maxsat", self.t0)
        tree.stats.update(stats)
        return tree


def _prove(
    at: _Goal,
    keep: list[int],
    weights: Sequence[int],
    best: Sequence[int],
    cost_of: Callable[[Sequence[int]], list[int]],
    lower_of: Callable[[int], list[int]],
    require: Iterable[int] = (),
    depth: int | None = None,
    best_is_canonical: bool = False,
) -> TaskTree:
    """MaxSAT over ``keep``, then the answer: ``best`` (a valid tree) with the bound when cut
    short; ``best`` again when it is optimal and ``best_is_canonical``; else the smallest
    optimal tree MaxSAT walked to (its first optimum when the options ask for no canonical tree)."""
    problem, options = at.problem, at.options
    upper = cost_of(best)
    limit = options.time_limit
    deadline = at.t0 + limit if limit else None
    stop = _stop(at.ranked, options, upper, lower_of)
    known = sum(weights[u] for u in best) if best_is_canonical else None
    found = minimum_tree(
        problem,
        at.goal,
        keep,
        weights,
        require,
        deadline,
        stop,
        depth,
        options.canonical,
        known,
        mip_after(),
        UWR_AFTER_S,
    )
    stats: dict = {"shortcut": "maxsat", "maxsat_s": round(found.time_s, 6), "pruned_units": len(at.units) - len(keep)}
    if found.cuts:
        stats["loop_cuts"] = found.cuts
    if found.solver != "rc2":
        stats["proven_by"] = found.solver
    if found.tree is None:  # cut short (no tree cannot be: ``best`` lies in ``keep``)
        if found.incumbent is not None and cost_of(found.incumbent) < list(upper):
            best, upper = found.incumbent, cost_of(found.incumbent)
        order = executable_order(problem, list(best))
        elapsed = round(time.perf_counter() - at.t0, 6)
        extra = {"asp_cost": list(upper)}
        tree = TaskTree(at.goal, at.label, "feasible", order, measures(problem, at.goal, order), elapsed, stats, extra)
        return settle(problem, tree, at.ranked, lower_of(found.lower))
    if best_is_canonical and cost_of(found.tree) == upper:
        return at.answer(best, stats)
    if found.search not in (None, "complete"):
        stats["canonical_search"] = found.search
    return at.answer(found.tree, stats)


def share_cores(processes: int) -> None:
    """This process is one of ``processes`` that solve goals at once (a batch's pool of
    workers): HiGHS starts beside RC2 only when each of them has two cores or more."""
    global _processes
    _processes = max(1, processes)


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def mip_after() -> float | None:
    """When HiGHS starts beside RC2 (:func:`foon2asp.maxsat.trees.minimum_tree`): after
    :data:`MIP_AFTER_S` seconds when this process has two cores or more to itself; after
    :data:`MIP_AFTER_SHARED_S` when it shares them with other workers (HiGHS then takes a
    core from another goal); never on one core."""
    cores = _cores()
    if cores < 2:
        return None
    return MIP_AFTER_S if cores // _processes >= 2 else MIP_AFTER_SHARED_S


def by_maxsat(
    problem: Problem,
    options: AspOptions,
    ranked: tuple[str, ...],
    goal: int,
    label: str,
    units: list[int],
    bounds: Bounds,
    t0: float,
    dominators: Dominators | None = None,
) -> TaskTree:
    """The optimum by MaxSAT on the goal's part without dominated units (``dominators``: the
    problem's for ``ranked``), the landmark units of ``bounds`` required; the smallest optimal
    tree (the bounds tree when that is optimal)."""
    at = _Goal(problem, options, ranked, goal, label, units, t0)
    # the bounds' pruning (Bounds.keep) is left out: it cost more than it saved MaxSAT (BENCHMARKS.md, "MaxSAT")
    keep = undominated(problem, goal, units, ranked, options, dominators)
    floor = bounds.first_lower(goal)

    def lower_of(weight: int) -> list[int]:
        return [max(floor, bounds.first(weight))]

    best = bounds.tree(goal) or ()
    return _prove(at, keep, bounds.w, best, bounds.cost, lower_of, bounds.landmarks(goal), best_is_canonical=True)


def by_maxsat_depth(
    problem: Problem,
    options: AspOptions,
    ranked: tuple[str, ...],
    goal: int,
    label: str,
    units: list[int],
    weights: Sequence[int],
    t0: float,
    dominators: Dominators | None = None,
) -> TaskTree:
    """Depth first (``ranked[0]``), then the sum objective ``ranked[1:]`` of ``weights``:
    MaxSAT over the trees within the goal's level (``dominators`` as for :func:`by_maxsat`)."""
    at = _Goal(problem, options, ranked, goal, label, units, t0)
    levels, unit_levels = problem.derivation_levels(units)
    depth = levels[goal]
    keep = undominated(problem, goal, units, ranked, options, dominators)
    scale = 1 if ranked[1] == "units" else len(problem.units) + 1

    def lower_of(weight: int) -> list[int]:
        return [depth, weight // scale]

    def cost_of(tree: Sequence[int]) -> list[int]:
        return [depth] + [total(problem, name, tree) for name in ranked[1:]]

    shallow = _shallowest(problem, goal, units, levels, unit_levels)
    return _prove(at, keep, weights, shallow, cost_of, lower_of, depth=depth)


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
