"""The canonical optimal tree of one goal without the solver: branch and bound over the bounds.

For the objectives of :mod:`foon2asp.methods.bounds` (a tree costs the sum of
positive unit weights), :func:`canonical_tree` finds the optimum of a goal on
its part and the canonical tree -- the bounds tree when it is optimal, else
the lexicographically smallest optimal tree -- or gives up (None) after
:data:`NODE_LIMIT` search nodes (fewer on large parts, :data:`WORK_LIMIT`), and the
caller asks the solver.

**The search.**  A node is a set ``S`` of units that every tree of the branch
contains.  A tree is a set of units that all fire (the tree encoding,
``tree.lp``), so a tree ``T`` that contains ``S`` holds a producer of every
*open* object -- the goal and the required inputs of ``S``'s units that no unit
of ``S`` makes and that are not kitchen items -- and every tree that uses a
unit ``p`` holds ``ulm(p)`` (the landmarks of :mod:`foon2asp.methods.bounds`).
So the branches ``S + ulm(p)``, one per producer ``p`` outside ``S`` of the
open object with the fewest such producers, hold every such tree.  A node is
cut when

* an open object has no producer left, or
* the weight of ``S`` plus a lower bound on what ``T - S`` weighs is not below
  the target: pairwise disjoint producer groups of open objects need distinct
  units (the sum of their lightest weights), and any one open object needs a
  producer ``p`` and with it ``ulm(p) - S``.

A node without open objects is *closed*.  When the units of ``S`` that fire
from the kitchen (a fixpoint over ``S`` alone) make the goal, they are a tree
(a *witness*).  Otherwise some unit of ``S`` does not fire; in ``T`` it does,
and the first such unit to fire in ``T`` has a required input that the units
of ``S`` that fire do not make, so ``T`` makes it with a unit outside ``S``:
the branches are ``S + ulm(p)`` for every such input and every producer ``p``
outside ``S`` of it (this is how cycles are handled, exactly).

So every tree of weight below the target lies in some branch and is reached
unless a valid bound cuts it: a search without a witness proves there is none.

**Optimum.**  Branch and bound from the goal's landmarks with the weight of
the bounds tree as the first target; each witness, made irredundant, lowers
the target.  Without a witness the bounds tree is optimal: it is the answer.

**The smallest optimal tree.**  Otherwise, with the optimum ``C``, a second
search with the target ``C + 1`` reaches every tree of weight ``C`` (at a
closed node ``S`` inside it: the tree of the units that fire weighs at least
``C``, so it is all of ``S``) and keeps the lexicographically smallest: order
the units by id and compare two trees at the smallest unit in which they
differ -- the tree holding it is smaller (the order of
:mod:`foon2asp.asp.canonical`).

Sets are bit sets over the part's units and objects, numbered in id order.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from foon2asp.methods.bounds import Bounds

#: search nodes one goal may use before the caller asks the solver instead ...
NODE_LIMIT = 20_000
#: ... and on a large part fewer: nodes times units of the part at most this (a node's work grows with the part)
WORK_LIMIT = 5_000_000
#: with ``units`` first, a goal whose bounds are further apart than this goes to MaxSAT without
#: the search: on every 10th object of hard-4k the search settled 12 of 31 goals at gaps 6-8, 2 of
#: 31 at 9-11 and none of 182 at 12 or more (BENCHMARKS.md, "Searches that would fail")
UNITS_GAP_LIMIT = 11


def hopeless(bounds: Bounds, goal: int) -> bool:
    """Is the branch and bound not worth trying on ``goal`` (:data:`UNITS_GAP_LIMIT`)?"""
    upper = bounds.upper(goal)
    return bounds.ranked[0] == "units" and upper is not None and upper - bounds.lower(goal) > UNITS_GAP_LIMIT


class OutOfNodes(Exception):
    """The search used up its nodes."""


def _bits(mask: int) -> Iterator[int]:
    """The positions of the set bits of ``mask``, lowest first."""
    while mask:
        low = mask & -mask
        yield low.bit_length() - 1
        mask ^= low


class Part:
    """A goal's part as bit sets: unit ``k`` is the k-th smallest unit id of the part."""

    def __init__(self, bounds: Bounds, goal: int, units: Iterable[int]):
        problem = bounds.problem
        kitchen = problem.kitchen
        pool = {u for u in units if u in bounds.ulm}
        while True:  # units whose landmarks leave the part are in no tree inside it
            inside = {u for u in pool if bounds.ulm[u] <= pool}
            if inside == pool:
                break
            pool = inside
        #: the part's units, in id order (bit k is units[k])
        self.units = sorted(pool)
        index = {u: k for k, u in enumerate(self.units)}
        objects: dict[int, int] = {}

        def bit(o: int) -> int:
            if o not in objects:
                objects[o] = len(objects)
            return 1 << objects[o]

        self.goal = bit(goal)
        self.w = [bounds.w[u] for u in self.units]
        self.uniform = len(set(self.w)) <= 1
        self.req = []
        self.prod = []
        self.lm = []
        for u in self.units:
            self.req.append(sum({bit(i) for i in problem.required[u] if i not in kitchen}))
            self.prod.append(sum({bit(o) for o in problem.products[u] if o not in kitchen}))
            self.lm.append(sum(1 << index[v] for v in bounds.ulm[u]))
        #: object bit position -> the units that make it (a bit set)
        self.producers = [0] * len(objects)
        for k, made in enumerate(self.prod):
            for j in _bits(made):
                self.producers[j] |= 1 << k

    def weight(self, mask: int) -> int:
        if self.uniform:
            return mask.bit_count() * (self.w[0] if self.w else 0)
        w = self.w
        return sum(w[k] for k in _bits(mask))

    def mask(self, units: Iterable[int]) -> int:
        index = {u: k for k, u in enumerate(self.units)}
        return sum(1 << index[u] for u in set(units))

    def ids(self, mask: int) -> tuple[int, ...]:
        return tuple(self.units[k] for k in _bits(mask))

    def fire(self, mask: int) -> tuple[int, int]:
        """``(fired, had)``: the units of ``mask`` that fire from the kitchen, and what they make."""
        req, prod = self.req, self.prod
        waiting = list(_bits(mask))
        fired = had = 0
        progress = True
        while progress:
            progress = False
            rest = []
            for k in waiting:
                if req[k] & ~had:
                    rest.append(k)
                else:
                    fired |= 1 << k
                    had |= prod[k]
                    progress = True
            waiting = rest
        return fired, had

    def trim(self, tree: int) -> int:
        """``tree`` without the units the goal does not need, heaviest (then highest) first."""
        w = self.w
        for k in sorted(_bits(tree), key=lambda k: (-w[k], -k)):
            rest = tree & ~(1 << k)
            if self.fire(rest)[1] & self.goal:
                tree = rest
        return tree


class Search:
    """Branch and bound on one :class:`Part` (module docstring) with a budget of nodes."""

    def __init__(self, part: Part, nodes: int = NODE_LIMIT):
        self.part = part
        self.left = nodes

    def run(self, start: int, target: int, every: bool = False) -> tuple[int | None, int]:
        """Search trees that hold ``start`` and weigh less than ``target``.

        Returns ``(tree, target)``.  Without ``every``: each witness, made irredundant,
        lowers the target, and the last one is a lightest tree (None: no tree is
        lighter than the first target).  With ``every`` the target stays and the tree
        is the smallest (in the unit order) of the witnesses; with the target one above
        the optimum these are all the optimal trees (module docstring).
        """
        part = self.part
        goal, req, prod, lm, producers, w = part.goal, part.req, part.prod, part.lm, part.producers, part.w
        uniform = part.uniform
        weight = part.weight
        best: int | None = None
        seen: set[int] = set()
        made0 = need0 = 0
        for k in _bits(start):
            made0 |= prod[k]
            need0 |= req[k]
        stack = [(start, weight(start), made0, need0 | goal)]
        while stack:
            s, ws, made, need = stack.pop()
            if ws >= target:
                continue
            self.left -= 1
            if self.left < 0:
                raise OutOfNodes
            open_ = need & ~made
            if not open_:
                fired, had = part.fire(s)
                if had & goal:
                    if every:
                        if best is None or (best ^ fired) & -(best ^ fired) & fired:
                            best = fired
                    else:
                        best = part.trim(fired)
                        target = weight(best)
                    continue
                missing = 0
                for k in _bits(s & ~fired):
                    missing |= req[k] & ~had
                branch = 0
                for j in _bits(missing):
                    branch |= producers[j]
                branch &= ~s
            else:
                groups = []
                dead = False
                for j in _bits(open_):
                    group = producers[j] & ~s
                    if not group:
                        dead = True  # an open object without a producer
                        break
                    groups.append((group.bit_count(), j, group))
                if dead:
                    continue
                groups.sort()
                used = extra = one = 0
                for _, _, group in groups:
                    if uniform:
                        if not used & group:
                            used |= group
                            extra += w[0]
                        least = min((lm[p] & ~s).bit_count() for p in _bits(group)) * w[0]
                    else:
                        if not used & group:
                            used |= group
                            extra += min(w[p] for p in _bits(group))
                        least = min(weight(lm[p] & ~s) for p in _bits(group))
                    if least > one:
                        one = least
                if ws + max(extra, one) >= target:
                    continue
                branch = groups[0][2]
            children = []
            for p in _bits(branch):
                child = s | lm[p]
                if child in seen:
                    continue
                seen.add(child)
                added = child & ~s
                cw = ws + weight(added)
                if cw >= target:
                    continue
                cmade, cneed = made, need
                for k in _bits(added):
                    cmade |= prod[k]
                    cneed |= req[k]
                children.append((cw, p, (child, cw, cmade, cneed)))
            # the lightest child first
            children.sort(key=lambda c: (-c[0], -c[1]))
            stack.extend(c[2] for c in children)
        return best, target


def canonical_tree(bounds: Bounds, goal: int, units: Iterable[int], nodes: int = NODE_LIMIT) -> tuple[int, ...] | None:
    """The canonical optimal tree of ``goal`` (sorted unit ids) over ``units`` -- a set holding
    every optimal tree of the goal, e.g. its relevant part -- or None when ``nodes`` search
    nodes (fewer on a part of more than ``WORK_LIMIT / nodes`` units) do not settle it.  The goal must be derivable."""
    tree = bounds.tree(goal)
    if tree is None:
        raise ValueError(f"object {goal} is not derivable")
    part = Part(bounds, goal, units)
    search = Search(part, min(nodes, WORK_LIMIT // max(1, len(part.units))))
    start = part.mask(bounds.landmarks(goal))
    try:
        lighter, optimum = search.run(start, bounds.weight(tree))
        if lighter is None:
            return tree  # nothing is lighter than the bounds tree
        smallest, _ = search.run(start, optimum + 1, every=True)
    except OutOfNodes:
        return None
    assert smallest is not None and part.weight(smallest) == optimum
    return part.ids(smallest)
