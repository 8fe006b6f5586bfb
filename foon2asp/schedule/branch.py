"""Joint scheduling by branch and bound over the first makers of what a tree needs.

A schedule's first makers of what is needed form a tree of their own that is as
short (:mod:`foon2asp.schedule.joint`): each needed object is had when its
*designated* maker ends.  So the joint optimum is the best schedule over
designations: the goal and every object a designated unit needs get one maker
each.  The search assigns them one object at a time; a node holds the candidate
units with the objects assigned so far, every unit waiting for the designated
maker of what it needs.  At each node:

* units that never get their inputs, lead to no goal, or cannot end within the best
  makespan found (earliest start plus shortest chain to a goal) are dropped;
* the units every remaining tree holds are the *landmarks* (a greatest fixpoint:
  an object's landmarks are those shared by all its makers, a unit's are itself and
  those of what it needs);
* the lower bound is the energetic bound (:func:`foon2asp.schedule.bounds.energy_over`) over the landmarks and one part per needed object no landmark makes (the
  least any of its makers could run in a window; the makers of distinct parts disjoint),
  at least the earliest a goal can be made and the parts' work over the agents; a
  landmark's chain to the goal is at least the longest chain of landmarks waiting for it
  (:func:`chain_tails`).

A node whose bound is no better than the best key (makespan, human units, tree
objective) is cut.  Otherwise it branches on an object the landmarks (or the goals) need
that still has several makers -- even one a landmark makes, since another maker may make
it first -- one child per maker.  When there is none, the landmarks are a tree: it is
scheduled alone (:func:`foon2asp.schedule.solve.schedule_fixed` through the ``solve``
callback) and may become the best.  Every designation lies under exactly one leaf, so when
the search ends without a time limit cutting it (and every leaf was solved to its optimum)
the best is proven.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace
from typing import Any

from foon2asp.schedule.bounds import energy_over
from foon2asp.schedule.model import Instance, divisor, earliest, joint_tails


@dataclass
class Outcome:
    """The best result found, whether it is proven, the nodes looked at and the least bound of
    what was left unexplored (None when nothing was)."""

    best: Any
    proven: bool
    nodes: int
    open_bound: int | None


def designate(inst: Instance, chosen: dict[int, int]) -> Instance:
    """``inst`` with each object of ``chosen`` made, for every unit needing it, by its chosen maker only."""
    if not chosen:
        return inst
    needs = {u: tuple((o, (chosen[o],) if o in chosen else ms) for o, ms in inst.needs[u]) for u in inst.units}
    return replace(inst, needs=needs)


def landmarks(
    inst: Instance, goals: Iterable[int], makers: dict[int, list[int]], ready: dict[int, int]
) -> frozenset[int] | None:
    """The units every tree of ``inst`` for ``goals`` holds (None: some goal has no tree):
    the greatest fixpoint of LM(o) = the intersection of ulm(m) over o's makers m,
    ulm(u) = {u} + the union of LM(o) over the objects u needs; ``ready``: the units' earliest starts."""
    needs = inst.needs
    makes: dict[int, list[int]] = {}
    for o, ms in makers.items():
        for m in ms:
            makes.setdefault(m, []).append(o)
    ulm: dict[int, frozenset[int]] = {}
    lm: dict[int, frozenset[int]] = {}
    # the units in order of their earliest start: a unit's needs are made by units before it
    order = sorted(ready, key=lambda u: (ready[u], u))
    changed = True
    while changed:
        changed = False
        for u in order:
            parts = [lm.get(o) for o, _ in needs[u]]
            if any(p is None for p in parts):
                continue
            new = frozenset().union(*parts) | {u}  # type: ignore[arg-type]
            if ulm.get(u) != new:
                ulm[u] = new
                changed = True
                for o in makes.get(u, ()):
                    known = [ulm[m] for m in makers.get(o, ()) if m in ulm]
                    lm[o] = frozenset.intersection(*known)
    out: set[int] = set()
    for g in goals:
        known = [ulm[m] for m in makers.get(g, ()) if m in ulm]
        if not known:
            return None
        out |= frozenset.intersection(*known)
    return frozenset(out)


def energy(
    inst: Instance,
    start: dict[int, int],
    tail: dict[int, int],
    groups: list[list[int]],
    floor: int,
    step: int,
    limit: int | None = None,
) -> int:
    """The energetic bound (:func:`foon2asp.schedule.bounds.energy_over`) over ``groups`` (each:
    the units one part may be, landmarks alone in theirs) on the agents of ``inst``."""
    d = {u: inst.min_duration(u) for g in groups for u in g}
    return energy_over(groups, d, start, tail, len(inst.agents), floor, step, limit)


def chain_tails(node: Instance, units: frozenset[int], tail: dict[int, int]) -> dict[int, int]:
    """``tail`` raised, for ``units`` (in every tree of the node), by the longest chain of them
    that must wait one for another (a unit waits for the sole maker of what it needs)."""
    succs: dict[int, list[int]] = {u: [] for u in units}
    for v in units:
        for _, ms in node.needs[v]:
            if len(ms) == 1 and ms[0] in units:
                succs[ms[0]].append(v)
    out = dict(tail)
    done: dict[int, int] = {}

    def longest(u: int) -> int:
        if u not in done:
            done[u] = tail[u]  # a guard: the designated makers form no cycle among ready units
            done[u] = max(tail[u], node.min_duration(u) + max((longest(v) for v in succs[u]), default=0))
        return done[u]

    for u in units:
        out[u] = longest(u)
    return out


class Search:
    """The branch and bound of the module docstring over the candidate units of ``inst``."""

    def __init__(
        self,
        inst: Instance,
        goals: tuple[int, ...],
        products: dict[int, tuple[int, ...]],
        solve: Callable[[tuple[int, ...], float | None, int | None], Any],
        key: Callable[[Any], tuple],
        low_key: Callable[[Instance, tuple[int, ...], int, list[list[int]] | None], tuple],
        max_units: int | None = None,
    ) -> None:
        """``solve(units, time left, makespan to beat)``: a unit set's own schedule; ``key``: a
        result's rank; ``low_key(instance of the units, units, makespan bound, groups)``: a lower
        bound on the key of every tree holding those units and one unit of each group (disjoint
        from them and each other; None: the tree is those units); ``max_units``: trees hold at
        most that many units."""
        self.inst = inst
        self.max_units = max_units
        self.goals = goals
        self.products = products
        self.solve = solve
        self.key = key
        self.low_key = low_key
        self.step = divisor(inst)
        self.nodes = 0

    def run(self, best: Any, time_limit: float | None) -> Outcome:
        """Search from ``best`` (a result or None) for at most ``time_limit`` seconds."""
        deadline = None if time_limit is None else time.perf_counter() + time_limit
        proven = True
        open_bound: int | None = None
        stack: list[tuple[Instance, dict[int, int], int]] = [(self.inst, {}, 0)]
        while stack:
            if deadline is not None and time.perf_counter() >= deadline:
                open_bound = min(b for _, _, b in stack)
                return Outcome(best, False, self.nodes, open_bound)
            inst, chosen, _ = stack.pop()
            self.nodes += 1
            step = self._expand(inst, chosen, best)
            if step is None:
                continue
            if isinstance(step, tuple):  # a leaf: the landmarks are a tree
                units, low = step
                left = None if deadline is None else max(0.0, deadline - time.perf_counter())
                within = None
                if best is not None:  # a tree no better on the tie-breakers must be strictly shorter
                    worse = self.low_key(self.inst.restrict(units), units, best.makespan, None) >= self.key(best)
                    within = best.makespan - self.step if worse else best.makespan
                r = self.solve(units, left, within)
                if r.status not in ("optimal", "unschedulable"):
                    proven = False
                    open_bound = low if open_bound is None else min(open_bound, low)
                if r.has_schedule and (best is None or self.key(r) < self.key(best)):
                    best = r
                continue
            stack.extend(reversed(step))
        return Outcome(best, proven, self.nodes, open_bound)

    def _expand(self, inst: Instance, chosen: dict[int, int], best: Any):
        """None (cut), (tree, bound) for a leaf, or the children (instance, designation, bound)
        best first."""
        limit = None if best is None else best.makespan
        node, start, tail = self._trim(inst, chosen, limit)
        if node is None:
            return None
        makers: dict[int, list[int]] = {}
        for u in node.units:
            for o, ms in node.needs[u]:
                makers.setdefault(o, list(ms))
        for u in node.units:
            for g in self.goals:
                if g in self.products[u]:
                    makers.setdefault(g, [])
                    if u not in makers[g]:
                        makers[g].append(u)
        for o, u in chosen.items():
            if u not in node.needs:
                return None  # the chosen maker was dropped
            makers[o] = [u]
        lm = landmarks(node, self.goals, makers, start)
        if lm is None:
            return None
        made = {o for u in lm for o in self.products[u]}
        wanted = [g for g in self.goals if g not in made] + sorted(
            {o for u in lm for o, _ in node.needs[u] if o not in made}
        )
        groups: list[list[int]] = [[u] for u in sorted(lm)]
        taken = set(lm)
        for o in wanted:
            ms = [m for m in makers.get(o, ()) if m in start]
            if ms and taken.isdisjoint(ms):
                taken.update(ms)
                groups.append(ms)
        m = len(node.agents)
        floor = max(
            (min((start[u] + node.min_duration(u) for u in makers.get(g, ()) if u in start), default=0))
            for g in self.goals
        )
        work = -(-sum(min(node.min_duration(u) for u in g) for g in groups) // m)
        tail = chain_tails(node, lm, tail)
        low = energy(node, start, tail, groups, max(floor, work), self.step, limit)
        others = groups[len(lm) :]
        if self.max_units is not None and len(groups) > self.max_units:
            return None  # every tree here holds the landmarks and a unit of each other part
        if best is not None and self.low_key(node.restrict(lm), tuple(sorted(lm)), low, others) >= self.key(best):
            return None
        # an object with several makers is open even when a landmark makes it: another maker
        # may make it first, and a unit waits for the first
        needed = list(self.goals) + sorted({o for u in lm for o, _ in node.needs[u]})
        open_objects = [o for o in needed if o not in chosen and len(makers.get(o, ())) > 1]
        if not open_objects:
            return tuple(sorted(lm)), low
        o = min(open_objects, key=lambda o: (len(makers.get(o, ())), o))
        kids = sorted(makers.get(o, ()), key=lambda u: (start[u] + node.min_duration(u), u))
        return [(node, {**chosen, o: u}, low) for u in kids if u in start]

    def _trim(self, inst: Instance, chosen: dict[int, int], limit: int | None):
        """The node's instance (designation applied, useless units dropped), earliest starts and
        shortest tails; (None, ..) when a goal can no longer be made."""
        node = designate(inst, chosen)
        while True:
            start = earliest(node)
            tail = joint_tails(node, self.goals, self.products)
            keep = [
                u for u in node.units if u in start and u in tail and (limit is None or start[u] + tail[u] <= limit)
            ]
            if len(keep) == len(node.units):
                break
            node = node.restrict(keep)
        if not any(g in self.products[u] for g in self.goals for u in node.units):
            return None, start, tail
        return node, start, tail
