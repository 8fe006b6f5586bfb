"""Bounds on the optimum without the solver: a valid tree (upper bound) and a lower bound.

For the monotone objectives -- the cost of a tree is a sum of non-negative
weights of its units -- in the ranked orders ``units``, ``success,units`` and
``inputs,units``.  A lexicographic pair (objective, then units) is one sum of
weights ``w(u) * M + 1`` with ``M`` greater than the number of units, so
minimising the sum minimises the pair.  Everything here is plain Python over a
:class:`~foon2asp.foon.problem.Problem` (no clingo).

**Upper bound: the cheapest-set tree.**  A Knuth-style generalised Dijkstra
over the FOON whose key is the *weight of a set of units*, not the cost of the
unfolded tree.  Kitchen items are settled with the empty set.  A unit *fires*
once all its required inputs are settled; its set is ``{u}`` plus the union of
the sets of its required inputs, and it offers that set to each product.  An
object is settled with the smallest offer popped first, ordered by (weight,
size, producing unit).

*Why every settled set is a valid, well-founded tree.*  By induction on the
settling order: the sets of the inputs were settled before, so each is a
valid tree for its input; their union still derives every input (adding units
never disables one: the FOON is delete-free), and then ``u`` fires, so the set
derives the object.  Every unit in it fires after units settled strictly
earlier, so nothing rests on a cycle.

*Why it is deterministic and depends on the goal's relevant part only.*  An
offer made after popping key ``(c, n)`` has a key ``(c', n')`` with ``c' >= c``
(weights are non-negative and the set grows) and ``n' > n`` (a unit fires once,
so it is not yet in its inputs' sets).  So no offer equal to or below a popped
key comes later, and the settled set of an object is the least of *all* its
offers in a total order that names nothing outside it.  Its offers come from
its viable producers, built from the settled sets of their required inputs:
all inside the object's relevant part.  The same set results whether the run
sees the whole FOON or only that part, and in whatever order units are listed.

The set is then made *irredundant*: its units are tried heaviest first (ties:
higher id first) and dropped when the rest still derives the goal (checked by
a fixpoint); the result is still a valid tree.  This trimmed set is *the
bounds tree* of the goal; its weight is the upper bound ``UB``.

**Lower bound.**  *Landmarks*: the greatest fixpoint of
``LM(o) = intersection over the viable producers u of o of ulm(u)``,
``ulm(u) = {u} + union of LM(i) over u's required inputs``, ``LM(kitchen) = {}``.
Every tree for ``o`` contains ``LM(o)``: in a tree the units fire in some
order; by induction on it, when ``o`` is first had through ``u``, the units
fired so far include ``ulm(u)`` (its inputs were had before), and
``LM(o) <= ulm(u)``.  Likewise every tree that uses ``u`` contains ``ulm(u)``.
So ``w(LM(g))`` is a lower bound, strengthened by three valid arguments:

* *closure*: a tree containing a set ``S`` weighs at least ``w(S)`` plus, for
  the required inputs of ``S``'s units that no unit of ``S`` makes (and that
  are not kitchen items), a *packing*: each needs a producer outside ``S``;
  producer sets that are pairwise disjoint need distinct units, each weighing
  at least its set's lightest unit.
* *one more producer*: a needed object (the goal, or a required input of a
  landmark unit) that no landmark unit makes is made by one of its viable
  producers ``u``, so the tree contains ``ulm(u) + LM(g)``; the lower bound is
  at least the least closure bound over those producers.
* *depth* (``units`` alone): a tree for ``g`` has at least ``level(g)`` units,
  a chain of that many units that fire one after another.

When ``LB == UB`` the bounds tree is optimal.  Otherwise :meth:`Bounds.keep`
prunes the goal's part exactly: a unit ``u`` whose closure bound of
``ulm(u) + LM(g)`` exceeds ``UB`` is in no optimal tree, and the units of
``LM(g)`` are in every tree.
"""

from __future__ import annotations

from collections.abc import Iterable

from foon2asp.foon.derive import least_fixpoint
from foon2asp.foon.problem import Problem, walk_back
from foon2asp.tree.upper import cheapest_sets
from foon2asp.tree.weights import lexicographic, total

#: ranked objective lists (as :func:`foon2asp.asp.objectives.ranked` gives them) the bounds handle
SUPPORTED = (("units",), ("success", "units"), ("inputs", "units"))


def supports(ranked: Iterable[str]) -> bool:
    """Do the bounds handle this ranked objective list?"""
    return tuple(ranked) in SUPPORTED


def weights(problem: Problem, ranked: tuple[str, ...]) -> list[int]:
    """One non-negative weight per unit whose sum orders trees as ``ranked`` does."""
    return lexicographic(problem, ranked[0])


def landmarks(
    problem: Problem, units: Iterable[int] | None = None
) -> tuple[dict[int, frozenset[int]], dict[int, frozenset[int]]]:
    """``(LM, ulm)``: object -> units every tree for it uses; viable unit -> units every
    tree using it uses (the greatest fixpoint of the module docstring)."""
    pool = list(range(len(problem.units))) if units is None else list(units)
    kitchen = problem.kitchen
    # the kitchen items the units need (not the whole kitchen: a large FOON's is large)
    lm: dict[int, frozenset[int]] = {i: frozenset() for u in pool for i in problem.required[u] if i in kitchen}
    producers: dict[int, list[int]] = {}
    users: dict[int, list[int]] = {}
    for u in pool:
        for o in problem.products[u]:
            if o not in kitchen:
                producers.setdefault(o, []).append(u)
        for i in set(problem.required[u]):
            users.setdefault(i, []).append(u)
    ulm: dict[int, frozenset[int]] = {}
    # undefined = the set of all units (top); a chaotic iteration from top reaches the greatest fixpoint
    work = [u for u in pool if all(i in lm for i in problem.required[u])]
    queued = set(work)
    while work:
        u = work.pop()
        queued.discard(u)
        new = frozenset().union(*(lm[i] for i in problem.required[u])) | {u}
        if ulm.get(u) == new:
            continue
        ulm[u] = new
        for o in problem.products[u]:
            if o in kitchen:
                continue
            val = frozenset.intersection(*(ulm[p] for p in producers[o] if p in ulm))
            if lm.get(o) != val:
                lm[o] = val
                for v in users.get(o, ()):
                    if v not in queued and all(i in lm for i in problem.required[v]):
                        queued.add(v)
                        work.append(v)
    return lm, ulm


class Bounds:
    """Upper bound (the bounds tree) and lower bound of every object for one ranked objective list.

    Built once per problem (about 0.1 s for ../shared/foon); the per-goal parts are cached.
    """

    def __init__(
        self,
        problem: Problem,
        ranked: tuple[str, ...] = ("units",),
        units: Iterable[int] | None = None,
        w: list[int] | None = None,
    ):
        """``units``: the units to consider (a goal's relevant part; None: all); ``w``: the
        unit weights of :func:`weights` when the caller has them (one list per problem)."""
        if not supports(ranked):
            raise ValueError(f"no bounds for the objectives {ranked!r}")
        pool = None if units is None else sorted(set(units))
        self.problem = problem
        self.ranked = tuple(ranked)
        self.w = weights(problem, self.ranked) if w is None else w
        self._sets = cheapest_sets(problem, self.w, pool)
        self.lm, self.ulm = landmarks(problem, pool)
        self._producers: dict[int, list[int]] = {}
        for u in sorted(self.ulm):
            for o in problem.products[u]:
                self._producers.setdefault(o, []).append(u)
        self._levels = problem.derivation_levels(pool)[0] if self.ranked == ("units",) else {}
        self._trees: dict[int, tuple[int, ...]] = {}
        self._lower: dict[int, int] = {}
        self._closures: dict[frozenset[int], int] = {}

    def weight(self, units: Iterable[int]) -> int:
        return sum(self.w[u] for u in units)

    def cost(self, units: Iterable[int]) -> list[int]:
        """The cost vector the solver reports (``asp_cost``), in ranked order."""
        units = list(units)
        return [total(self.problem, name, units) for name in self.ranked]

    def tree(self, goal: int) -> tuple[int, ...] | None:
        """The bounds tree of ``goal`` (sorted unit ids), None when it is not derivable."""
        if goal in self._trees:
            return self._trees[goal]
        start = self._sets.get(goal)
        if start is None:
            return None
        tree = set(start)
        for u in sorted(tree, key=lambda u: (-self.w[u], -u)):
            if self._derives(tree - {u}, goal):
                tree.discard(u)
        self._trees[goal] = result = tuple(sorted(tree))
        return result

    def upper(self, goal: int) -> int | None:
        tree = self.tree(goal)
        return None if tree is None else self.weight(tree)

    def _derives(self, units: set[int], goal: int) -> bool:
        """Do ``units`` derive ``goal`` from the kitchen?"""
        kitchen = self.problem.kitchen
        made, _ = least_fixpoint(kitchen, self.problem.required, self.problem.products, units)
        return goal in made or goal in kitchen

    def closure(self, units: frozenset[int]) -> int:
        """A lower bound on the weight of any tree that contains ``units``."""
        value = self._closures.get(units)
        if value is None:
            value = self._closures[units] = self._closure(units, set())
        return value

    def _closure(self, units: frozenset[int], need: set[int]) -> int:
        """``closure(units)`` where the objects ``need`` must be had too."""
        made = {o for u in units for o in self.problem.products[u]}
        need = need | {i for u in units for i in self.problem.required[u]}
        return self.weight(units) + self._packing(
            [u for u in self._producers.get(i, ()) if u not in units]
            for i in sorted(need)
            if i not in self.problem.kitchen and i not in made
        )

    def _packing(self, groups: Iterable[list[int]]) -> int:
        """Pairwise disjoint producer groups need distinct units: the sum of their lightest weights."""
        w = self.w
        sets = sorted((len(g), min(w[u] for u in g), sorted(g)) for g in groups if g)
        used: set[int] = set()
        extra = 0
        for _, lightest, group in sets:
            if used.isdisjoint(group):
                used.update(group)
                extra += lightest
        return extra

    def lower(self, goal: int) -> int:
        """A lower bound on the weight of every tree for ``goal`` (see the module docstring)."""
        if goal in self._lower:
            return self._lower[goal]
        kitchen = self.problem.kitchen
        LM = self.lm.get(goal, frozenset())
        lb = self._closure(LM, {goal})
        made = {o for u in LM for o in self.problem.products[u]}
        need = {goal} | {i for u in LM for i in self.problem.required[u]}
        for i in sorted(need):
            if i in kitchen or i in made:
                continue
            prods = self._producers.get(i, [])
            if prods:
                lb = max(lb, min(self.closure(self.ulm[u] | LM) for u in prods))
        if self.ranked == ("units",):
            lb = max(lb, self._levels.get(goal, 0))
        self._lower[goal] = lb
        return lb

    def first_lower(self, goal: int) -> int:
        """A lower bound on the first objective's weight (as the solver weighs it) of every
        tree for ``goal``: :meth:`lower` with the tie-break on units taken out (the weights
        are ``w(u) * M + 1`` with ``M`` above the number of units, foon2asp.tree.weights)."""
        return self.first(self.lower(goal))

    def first(self, weight: int) -> int:
        """A lower bound ``weight`` on the weights :attr:`w` as one on the first objective's."""
        if self.ranked[0] == "units":
            return weight
        return weight // (len(self.problem.units) + 1)

    def proven(self, goal: int) -> bool:
        """Is the bounds tree of ``goal`` optimal (lower bound == upper bound)?"""
        start = self._sets.get(goal)
        if start is None:
            return False
        lower = self.lower(goal)
        if lower >= self.weight(start):
            # nothing can be trimmed from a set that weighs no more than the lower bound
            self._trees.setdefault(goal, tuple(sorted(start)))
            return True
        ub = self.upper(goal)
        return ub is not None and lower >= ub

    def landmarks(self, goal: int) -> frozenset[int]:
        """The units every tree for ``goal`` uses."""
        return self.lm.get(goal, frozenset())

    def keep(self, goal: int, units: Iterable[int]) -> list[int]:
        """``units`` without those no optimal tree for ``goal`` uses (closure bound above UB)."""
        ub = self.upper(goal)
        if ub is None:
            return sorted(units)
        LM = self.landmarks(goal)
        base = self.weight(LM)
        keep = []
        for u in units:
            if u in LM:
                keep.append(u)
            elif u in self.ulm and base + self.weight(self.ulm[u] - LM) <= ub:
                if self.closure(self.ulm[u] | LM) <= ub:
                    keep.append(u)
        # only units still relevant to the goal through kept producers, and still viable among them
        producers: dict[int, list[int]] = {}
        for u in keep:
            for o in self.problem.products[u]:
                producers.setdefault(o, []).append(u)
        reached, _, _ = walk_back([goal], self.problem.kitchen, producers, self.problem.required)
        _, viable = self.problem.derivation_levels(sorted(reached))
        return sorted(viable)
