"""Bounds on the optimum without the solver: a valid tree (upper bound) and a lower bound.

For the ranked objectives of :data:`SUPPORTED` (one sum of non-negative unit weights),
:class:`Bounds` gives each goal's *bounds tree*, its landmarks and a lower bound, and prunes
a goal's part to the units an optimal tree may use (:meth:`Bounds.keep`).  Why these are
bounds: docs/proofs/preparation.md ("Weights", "The cheapest-set tree", "Landmarks").
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace

from foon2asp.bounds.upper import cheapest_sets
from foon2asp.foon.problem import Problem, least_fixpoint, walk_back
from foon2asp.tree.weights import lexicographic, total

#: a set of units with the objects they make, the objects they need and do not have (and the
#: producer group of each that has producers), and their weight
Within = tuple[frozenset[int], frozenset[int], frozenset[int], tuple[tuple[int, tuple[int, ...]], ...], int]

_NOTHING: Within = (frozenset(), frozenset(), frozenset(), (), 0)

#: ranked objective lists (as :func:`foon2asp.asp.objectives.ranked` gives them) the bounds handle
SUPPORTED = (("units",), ("success", "units"), ("inputs", "units"))


#: one case of a split: a unit that makes the split's object, the units every tree using it (and
#: the cases above it) uses beyond those above, landmark sets of those trees, and a split deeper
Case = tuple[int, tuple[int, ...], tuple[tuple[int, ...], ...], "Split | None"]
#: a split: an object every tree of the branch makes, and a case per unit that makes it
Split = tuple[int, tuple[Case, ...]]

#: how many splits deep a witness may nest
SPLIT_DEPTH = 2


def split_fields(split: Split) -> dict:
    """A split as the answer's JSON carries it (``{"object", "cases": [{"unit", "landmarks",
    "landmark_sets", "split"?}]}``)."""
    made, cases = split
    out = []
    for u, marks, sets, deeper in cases:
        case: dict = {"unit": u, "landmarks": list(marks), "landmark_sets": [list(s) for s in sets]}
        if deeper is not None:
            case["split"] = split_fields(deeper)
        out.append(case)
    return {"object": made, "cases": out}


@dataclass(frozen=True)
class Witness:
    """A lower bound on the weight of every tree for one goal, with what proves it without the
    solver (``foon2asp.tree.validate.bounds_proof`` checks it; docs/proofs/solving.md)."""

    #: the bound: every tree weighs at least this much
    bound: int
    #: the units every tree uses
    landmarks: tuple[int, ...]
    #: pairwise disjoint sets of units, none a landmark, of which every tree uses one
    sets: tuple[tuple[int, ...], ...] = ()
    #: an object every tree makes, and for each unit that makes it: the unit with what every tree
    #: using it uses beyond the landmarks, landmark sets of the trees that use it, and perhaps a
    #: split of those trees in turn
    cases: Split | None = None
    #: the goal's derivation level (``units``: every tree has at least that many units)
    level: int | None = None

    def fields(self) -> dict:
        """The witness as an answer carries it (``foon2asp.tree.tasktree.TaskTree``, JSON):
        ``landmarks``, ``landmark_sets``, ``landmark_cases``, ``derivation_level``."""
        return {
            "landmarks": list(self.landmarks),
            "landmark_sets": [list(s) for s in self.sets],
            "landmark_cases": None if self.cases is None else split_fields(self.cases),
            "derivation_level": self.level,
        }


def supports(ranked: Iterable[str]) -> bool:
    """Do the bounds handle this ranked objective list?"""
    return tuple(ranked) in SUPPORTED


def landmarks(
    problem: Problem, units: Iterable[int] | None = None
) -> tuple[dict[int, frozenset[int]], dict[int, frozenset[int]]]:
    """``(LM, ulm)``: object -> units every tree for it uses; viable unit -> units every tree using it uses."""
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
    """Upper bound (the bounds tree) and lower bound of every object for one ranked objective list."""

    def __init__(
        self,
        problem: Problem,
        ranked: tuple[str, ...] = ("units",),
        units: Iterable[int] | None = None,
        w: list[int] | None = None,
    ):
        """``units``: the units to consider (a goal's relevant part; None: all); ``w``: the unit
        weights (:func:`~foon2asp.tree.weights.lexicographic` of the first objective) when the caller has them."""
        if not supports(ranked):
            raise ValueError(f"no bounds for the objectives {ranked!r}")
        pool = None if units is None else sorted(set(units))
        self.problem = problem
        self.ranked = tuple(ranked)
        self.w = lexicographic(problem, self.ranked[0]) if w is None else w
        self._sets = cheapest_sets(problem, self.w, pool)
        self.lm, self.ulm = landmarks(problem, pool)
        producers: dict[int, list[int]] = {}
        for u in sorted(self.ulm):
            for o in problem.products[u]:
                producers.setdefault(o, []).append(u)
        self._producers: dict[int, tuple[int, ...]] = {o: tuple(us) for o, us in producers.items()}
        #: producer group -> its place in the packing order: (size, lightest weight, the group)
        self._key: dict[tuple[int, ...], tuple[int, int, tuple[int, ...]]] = {}
        self._levels = problem.derivation_levels(pool)[0] if self.ranked == ("units",) else {}
        self._trees: dict[int, tuple[int, ...]] = {}
        self._lower: dict[int, int] = {}
        self._closures: dict[frozenset[int], int] = {}
        #: unit -> what the units every tree using it uses make and need (:meth:`_unit_needs`)
        self._needs: dict[int, tuple[set[int], list[tuple[int, int]], int]] = {}
        self._gids: tuple[dict[int, int], list[tuple[int, ...]], list[tuple[int, int, tuple[int, ...]]]] | None = None

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
        landmarks = self.landmarks(goal)  # every tree uses them: none can go
        for u in sorted(tree, key=lambda u: (-self.w[u], -u)):
            if u not in landmarks and self._derives(tree - {u}, goal):
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

    def closure(self, units: frozenset[int], within: Within | None = None) -> int:
        """A lower bound on the weight of any tree that contains ``units``; ``within``: a subset of
        them with what it makes, needs and weighs (:meth:`_within`), read instead of recomputed."""
        value = self._closures.get(units)
        if value is None:
            value = self._closures[units] = self._closure(units, (), within)
        return value

    def _within(self, units: frozenset[int]) -> Within:
        """``units`` with the objects they make, the objects they need that are neither made by them
        nor kitchen items (with the producer group of each that has producers), and their weight."""
        made: set[int] = set()
        need: set[int] = set()
        for u in units:
            made.update(self.problem.products[u])
            need.update(self.problem.required[u])
        kitchen, producers = self.problem.kitchen, self._producers
        open_ = frozenset(i for i in need if i not in kitchen and i not in made)
        groups = tuple((i, producers[i]) for i in sorted(open_) if producers.get(i))
        return units, frozenset(made), open_, groups, self.weight(units)

    def _closure(self, units: frozenset[int], need: Iterable[int], within: Within | None = None) -> int:
        """``closure(units)`` where the objects ``need`` must be had too: the units' weight and the
        lightest weights of pairwise disjoint producer groups (each the producers of an object the
        units or ``need`` require that the units do not make)."""
        weight, groups = self._open_groups(units, need, within)
        return weight + self._packing(groups)

    def _open_groups(
        self, units: frozenset[int], need: Iterable[int], within: Within | None = None
    ) -> tuple[int, set[tuple[int, ...]]]:
        """The weight of ``units`` and the producer groups of the objects they or ``need`` require
        that they do not make and the kitchen does not hold."""
        problem = self.problem
        products, required, w = problem.products, problem.required, self.w
        sub, made_in, _, open_groups, weight = within if within is not None else _NOTHING
        made: set[int] = set()
        wanted = set(need)
        for u in units - sub:
            made.update(products[u])
            wanted.update(required[u])
            weight += w[u]
        kitchen, producers = problem.kitchen, self._producers
        # identical groups count once: a second copy is never disjoint from the first; a unit of
        # ``units`` is in no group (what it makes is made)
        groups = {group for i, group in open_groups if i not in made}
        for i in wanted:
            if i in made or i in made_in or i in kitchen:
                continue
            group = producers.get(i)
            if group:
                groups.add(group)
        return weight, groups

    def _group_ids(self) -> tuple[dict[int, int], list[tuple[int, ...]], list[tuple[int, int, tuple[int, ...]]]]:
        """Each object's producer group as a number (identical groups one number), the groups by
        number, and each group's place in the packing order (:meth:`_keyed`)."""
        if self._gids is None:
            number: dict[tuple[int, ...], int] = {}
            gid = {o: number.setdefault(group, len(number)) for o, group in self._producers.items()}
            groups = list(number)
            key = self._keyed(groups)
            self._gids = gid, groups, [key[g] for g in groups]
        return self._gids

    def _unit_needs(self, u: int) -> tuple[set[int], list[tuple[int, int]], int]:
        """What the units every tree using ``u`` uses make, the objects they need that they do not
        make and the kitchen does not hold, with their producer groups' numbers (those some unit
        makes), and their weight (computed once per unit)."""
        found = self._needs.get(u)
        if found is None:
            problem = self.problem
            made: set[int] = set()
            wanted: set[int] = set()
            for v in self.ulm[u]:
                made.update(problem.products[v])
                wanted.update(problem.required[v])
            kitchen, gid = problem.kitchen, self._group_ids()[0]
            open_ = [(i, gid[i]) for i in wanted if i not in made and i not in kitchen and i in gid]
            found = self._needs[u] = (made, open_, self.weight(self.ulm[u]))
        return found

    def _packs_within(self, groups: set[int], room: int) -> bool:
        """Do the lightest weights of pairwise disjoint groups of ``groups`` (numbers), packed as
        :meth:`_packed` packs them, sum to at most ``room`` (stopped once they are above)?"""
        _, members, key = self._group_ids()
        if sum(key[g][1] for g in groups) <= room:  # every group packed would still fit
            return True
        used: set[int] = set()
        for g in sorted(groups, key=key.__getitem__):
            group = members[g]
            if used.isdisjoint(group):
                used.update(group)
                room -= key[g][1]
                if room < 0:
                    return False
        return True

    def _packing(self, groups: set[tuple[int, ...]]) -> int:
        """The summed lightest weights of pairwise disjoint producer groups, taken smallest first."""
        return self._packed_bound(0, groups)[0]

    def _keyed(self, groups: Iterable[tuple[int, ...]]) -> dict[tuple[int, ...], tuple[int, int, tuple[int, ...]]]:
        """The packing order, with ``groups`` in it."""
        key = self._key
        for g in groups:
            if g not in key:
                key[g] = (len(g), min(self.w[u] for u in g), g)
        return key

    def _packed(self, groups: set[tuple[int, ...]]) -> list[tuple[int, ...]]:
        """Pairwise disjoint groups of ``groups``, taken smallest first (their order is known)."""
        used: set[int] = set()
        packed = []
        for group in sorted(groups, key=self._key.__getitem__):
            if used.isdisjoint(group):
                used.update(group)
                packed.append(group)
        return packed

    def lower(self, goal: int) -> int:
        """A lower bound on the weight of every tree for ``goal``."""
        if goal in self._lower:
            return self._lower[goal]
        kitchen = self.problem.kitchen
        LM = self.lm.get(goal, frozenset())
        within = self._within(LM)
        _, made, open_, _, _ = within
        lb = self._closure(LM, (goal,), within)
        for i in sorted(open_ | {goal}):
            if i in kitchen or i in made:
                continue
            prods = self._producers.get(i, ())
            if prods:
                lb = max(lb, min(self.closure(self.ulm[u] | LM, within) for u in prods))
        if self.ranked == ("units",):
            lb = max(lb, self._levels.get(goal, 0))
        self._lower[goal] = lb
        return lb

    def first_lower(self, goal: int) -> int:
        """A lower bound on the first objective's solver weight of every tree for ``goal``."""
        weight = self.lower(goal)
        return weight if self.ranked[0] == "units" else weight // (len(self.problem.units) + 1)

    def witness(self, goal: int, target: int | None = None) -> Witness:
        """A lower bound on the weight of every tree for ``goal`` that anyone can check
        (:class:`Witness`), the first of these that reaches ``target`` (None: the first): the
        landmarks and landmark sets; a split over the producers of an object every tree needs,
        its cases split in turn (at most :data:`SPLIT_DEPTH` deep); for ``units``, the goal's
        derivation level."""
        LM = self.landmarks(goal)
        within = self._within(LM)
        _, made, open_, _, _ = within
        bound, sets = self._packed_bound(*self._open_groups(LM, (goal,), within))
        found = Witness(bound, tuple(sorted(LM)), tuple(sets))
        if target is None or bound >= target:
            return found
        kitchen = self.problem.kitchen
        objects = [i for i in sorted(open_ | {goal}) if i not in kitchen and i not in made and self._producers.get(i)]
        for depth in range(SPLIT_DEPTH):
            if depth == 0 and self.lower(goal) < target:
                continue  # the lower bound holds every split one deep
            for i in objects:
                split = self._split(i, LM, within, target, depth)
                if split is not None:
                    return replace(found, bound=target, cases=split)
        level = self._levels.get(goal)
        if level is not None and level >= target:
            return replace(found, bound=level, level=level)
        return found

    def _split(self, i: int, chain: frozenset[int], within: Within, target: int, depth: int) -> Split | None:
        """The split over the producers of object ``i`` of the trees that use ``chain``, every case
        weighing ``target`` at least, its cases split at most ``depth`` more deep; None: none."""
        cases: list[Case] = []
        for u in self._producers[i]:
            marks = chain | self.ulm[u]
            own, sets = self._packed_bound(*self._open_groups(marks, (), within))
            deeper = None
            if own < target:
                deeper = self._deeper(marks, within, target, depth - 1) if depth > 0 else None
                if deeper is None:
                    return None
            cases.append((u, tuple(sorted(marks - chain)), tuple(sets), deeper))
        return i, tuple(cases)

    def _deeper(self, marks: frozenset[int], within: Within, target: int, depth: int) -> Split | None:
        """A split of the trees that use ``marks`` over an object they need and do not make."""
        _, made, open_, _, _ = self._within(marks)
        kitchen = self.problem.kitchen
        for j in sorted(open_):
            if j in kitchen or j in made or not self._producers.get(j):
                continue
            split = self._split(j, marks, within, target, depth)
            if split is not None:
                return split
        return None

    def _packed_bound(self, weight: int, groups: set[tuple[int, ...]]) -> tuple[int, list[tuple[int, ...]]]:
        """``weight`` and the lightest weights of the pairwise disjoint groups packed from ``groups``, with them."""
        key = self._keyed(groups)
        sets = self._packed(groups)
        return weight + sum(key[g][1] for g in sets), sets

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
        # the bounds tree holds what every tree using one of its units uses: those units stay
        tree = set(self.tree(goal) or ())
        within = self._within(LM)
        _, made_in, _, open_groups, _ = within
        # LM's open objects with their groups' numbers (:meth:`_group_ids`)
        gid = self._group_ids()[0]
        lm_open = [(i, gid[i]) for i, _ in open_groups]
        ulm, w = self.ulm, self.w
        keep = []
        for u in units:
            if u in LM or u in tree:
                keep.append(u)
                continue
            marks = ulm.get(u)
            if marks is None:
                continue
            made_u, open_u, weight_u = self._unit_needs(u)
            shared = marks & LM
            weight = base + weight_u - (sum(w[v] for v in shared) if shared else 0)  # base + weight(marks - LM)
            if weight > ub:
                continue
            # the producer groups of what LM and the units every tree using u uses need and neither makes
            groups = {g for i, g in lm_open if i not in made_u}
            groups.update(g for i, g in open_u if i not in made_in)
            if self._packs_within(groups, ub - weight):
                keep.append(u)
        # only units still relevant and viable through kept producers
        producers: dict[int, list[int]] = {}
        for u in keep:
            for o in self.problem.products[u]:
                producers.setdefault(o, []).append(u)
        reached, _, _ = walk_back([goal], self.problem.kitchen, producers, self.problem.required)
        _, viable = self.problem.derivation_levels(sorted(reached))
        return sorted(viable)
