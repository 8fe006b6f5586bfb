"""The planning problem in integer form: required inputs, products, kitchen, least fixpoint.

The conventions of README.md hold here once for facts, search methods and validator: an
object is available iff it equals a kitchen item; the utensil rule (:func:`required_flags`);
an output that is bare is not a product (:func:`product_outputs`).  Levels, viable units,
the bounds' trees and the depth windows all come from :func:`least_fixpoint`
(docs/proofs/preparation.md, "The least fixpoint").
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

from foon2asp.foon.model import Foon, FoonObject, Unit
from foon2asp.foon.motioncost import MotionCosts

if TYPE_CHECKING:
    from foon2asp.foon.loaders import Dataset

#: unit id -> object ids (a list indexed by unit, or a mapping)
Table = Sequence[Sequence[int]] | Mapping[int, Sequence[int]]


def least_fixpoint(
    start: Collection[int], required: Table, products: Table, units: Iterable[int]
) -> tuple[dict[int, int], dict[int, int]]:
    """``(object_level, unit_level)`` of the objects and units derived from ``start``.

    A unit of ``units`` fires at level 1 + the greatest level of its ``required``
    inputs (objects of ``start`` have level 0); its ``products`` get the least level
    of their producers.  ``object_level`` holds the derived objects only (not those of
    ``start``), in the order derived; ``unit_level`` every unit that fires, in order.
    """
    waiting: dict[int, int] = {}
    users: dict[int, list[int]] = {}
    unit_level: dict[int, int] = {}
    queue: list[int] = []
    for u in units:
        need = 0
        for o in required[u]:
            if o not in start:
                need += 1
                if o in users:
                    users[o].append(u)
                else:
                    users[o] = [u]
        if need:
            waiting[u] = need
        else:
            unit_level[u] = 1
            queue.append(u)
    obj_level: dict[int, int] = {}
    for u in queue:  # the queue grows while it is read
        level = unit_level[u]
        for o in products[u]:
            if o not in obj_level and o not in start:
                obj_level[o] = level
                for v in users.get(o, ()):
                    waiting[v] -= 1
                    if not waiting[v]:
                        unit_level[v] = level + 1
                        queue.append(v)
    return obj_level, unit_level


class Implied(dict):
    """A dict of the derived objects that also answers ``value`` for every object of
    ``start`` without storing them: ``in``, ``get`` and ``[]`` see them; iteration and
    ``len`` give the stored entries only."""

    def __init__(self, stored: Mapping, start: Collection[int], value: Any) -> None:
        super().__init__(stored)
        self.start = start
        self.value = value

    def __contains__(self, obj: object) -> bool:
        return dict.__contains__(self, obj) or obj in self.start

    def __getitem__(self, obj: int) -> Any:
        if dict.__contains__(self, obj):
            return dict.__getitem__(self, obj)
        if obj in self.start:
            return self.value
        raise KeyError(obj)

    def get(self, obj, default=None):
        if dict.__contains__(self, obj):
            return dict.__getitem__(self, obj)
        return self.value if obj in self.start else default


UTENSIL_RULES = ("starter", "off")


#: success rate of a motion that motion.txt does not list
DEFAULT_RATE = 0.5


def required_flags(unit: Unit, utensils: frozenset[str], rule: str = "starter") -> list[bool]:
    """For each input of ``unit``: is it required?"""
    flags = []
    for obj in unit.inputs:
        skip = (
            rule == "starter"
            and obj.label in utensils
            and len(obj.ingredients) == 1
            and any(o.label == obj.ingredients[0] and o.container == obj.label for o in unit.inputs)
        )
        flags.append(not skip)
    return flags


def product_outputs(unit: Unit) -> list[FoonObject]:
    """The outputs of ``unit`` that count as made: the non-bare ones; a unit projected to
    hierarchy level 1 or 2 (:class:`foon2asp.foon.matching.LevelUnit`) lists its own."""
    made = getattr(unit, "made", None)
    if made is None:
        return [o for o in unit.outputs if not o.is_bare()]
    return [o for o in unit.outputs if o in made]


def walk_back(
    goals: Iterable[int],
    kitchen: frozenset[int],
    producers: dict[int, list[int]],
    required: list[tuple[int, ...]] | dict,
) -> tuple[set[int], set[int], bool]:
    """Backwards from ``goals`` through ``producers`` and their required inputs; kitchen
    items stop the walk.  Returns ``(units, objects, choice)``: the units and objects
    reached (goals included), and whether a non-kitchen object reached has two producers."""
    seen = set(goals)
    stack = list(seen)
    units: set[int] = set()
    choice = False
    while stack:
        o = stack.pop()
        if o in kitchen:
            continue
        makers = producers.get(o, ())
        if len(makers) > 1:
            choice = True
        for u in makers:
            if u in units:
                continue
            units.add(u)
            for i in required[u]:
                if i not in seen:
                    seen.add(i)
                    stack.append(i)
    return units, seen, choice


@dataclass
class Problem:
    """A FOON with kitchen, rates and the semantics above, as integer ids."""

    foon: Foon
    kitchen_items: list[FoonObject]
    motion_rates: dict[str, float] = field(default_factory=dict)
    utensils: frozenset[str] = frozenset()
    utensil_rule: str = "starter"
    #: the motion-cost table of the request being answered (``--motion-cost``; on the copy
    #: :meth:`foon2asp.api.KnowledgeBase.solving_problem` gives): every tree's measures then include its cost
    motion_costs: MotionCosts | None = None
    #: objects that count as available for viability though not kitchen items: what a
    #: substitute stands in for (foon2asp.foon.substitutes.with_substitutes); a tree may make them too
    substitutable: frozenset[int] = frozenset()

    def __post_init__(self) -> None:
        if self.utensil_rule not in UTENSIL_RULES:
            raise ValueError(f"unknown utensil rule {self.utensil_rule!r}")
        oid = self.foon.object_ids
        self.inputs: list[tuple[int, ...]] = []
        self.required: list[tuple[int, ...]] = []
        self.products: list[tuple[int, ...]] = []
        self.outputs: list[tuple[int, ...]] = []
        for unit in self.foon.units:
            ins = tuple(oid[o] for o in unit.inputs)
            flags = required_flags(unit, self.utensils, self.utensil_rule)
            self.inputs.append(ins)
            self.required.append(tuple(dict.fromkeys(i for i, f in zip(ins, flags) if f)))
            self.outputs.append(tuple(oid[o] for o in unit.outputs))
            self.products.append(tuple(dict.fromkeys(oid[o] for o in product_outputs(unit))))
        self.producers: dict[int, list[int]] = {}
        for u, prods in enumerate(self.products):
            for o in prods:
                self.producers.setdefault(o, []).append(u)
        # the FOON's own instances, so that looking an item up finds it by identity
        self.kitchen_items = [self.foon.objects[oid[o]] if o in oid else o for o in self.kitchen_items]
        self.kitchen: frozenset[int] = frozenset(oid[o] for o in self.kitchen_items if o in oid)
        self.rates: list[float] = [self.motion_rates.get(u.motion, DEFAULT_RATE) for u in self.foon.units]

    @classmethod
    def from_dataset(cls, data: Dataset, utensil_rule: str = "starter") -> Problem:
        return cls(data.foon, data.kitchen, data.motion, data.utensils, utensil_rule)

    def with_kitchen(self, kitchen: Iterable[int]) -> Problem:
        """The same problem with the kitchen ``kitchen`` (object ids).  The unit tables are
        shared, nothing cached is carried over; ``kitchen_items`` lists the original items
        kept, then the added objects in id order."""
        ids = frozenset(kitchen)
        view = self._view()
        view.kitchen = ids
        oid = self.foon.object_ids
        items = [o for o in self.kitchen_items if oid.get(o) in ids]
        view.kitchen_items = items + [self.objects[o] for o in sorted(ids - self.kitchen)]
        return view

    def with_substitutable(self, objects: Iterable[int]) -> Problem:
        """The same problem whose viability counts the objects ``objects`` (ids) as available
        by substitution (:attr:`substitutable`); nothing cached here is carried over."""
        view = self._view()
        view.substitutable = frozenset(objects)
        return view

    def _view(self) -> Problem:
        """A problem sharing this one's tables and kitchen, with no cached value."""
        view = Problem.__new__(Problem)
        cached = {name for name, value in vars(Problem).items() if isinstance(value, cached_property)}
        vars(view).update((name, value) for name, value in vars(self).items() if name not in cached)
        view.kitchen_items = list(self.kitchen_items)
        return view

    @property
    def units(self) -> list[Unit]:
        return self.foon.units

    @property
    def objects(self) -> list[FoonObject]:
        return self.foon.objects

    def unknown_motions(self) -> list[str]:
        return sorted({u.motion for u in self.foon.units} - set(self.motion_rates))

    @cached_property
    def kitchen_set(self) -> frozenset[FoonObject]:
        """The kitchen items as a set (read by the independent validator)."""
        return frozenset(self.kitchen_items)

    @cached_property
    def derivable(self) -> frozenset[int]:
        """Objects derivable from the kitchen using any units (least fixpoint)."""
        return frozenset(self.derivation_levels()[0])

    def derivation_levels(self, units: list[int] | None = None) -> tuple[dict[int, int], dict[int, int]]:
        """``(object_level, unit_level)`` of :func:`least_fixpoint` from the kitchen (and what
        substitutes stand in for), kitchen objects at level 0; only ``units`` when given."""
        pool = range(len(self.units)) if units is None else units
        start = self.kitchen | self.substitutable if self.substitutable else self.kitchen
        derived, unit_level = least_fixpoint(start, self.required, self.products, pool)
        if units is not None:  # a few units: the kitchen's level-0 entries are implied, not copied
            return Implied(derived, start, 0), unit_level
        obj_level = dict.fromkeys(start, 0)
        obj_level.update(derived)
        return obj_level, unit_level

    @cached_property
    def viable_units(self) -> frozenset[int]:
        """Units that fire in the kitchen's least fixpoint; no tree can use any other unit."""
        return frozenset(self.derivation_levels()[1])

    @cached_property
    def viable_producers(self) -> dict[int, list[int]]:
        """Object -> its producers that are viable (fire in the kitchen's least fixpoint)."""
        viable = self.viable_units
        out: dict[int, list[int]] = {}
        for obj, units in self.producers.items():
            keep = [u for u in units if u in viable]
            if keep:
                out[obj] = keep
        return out

    def units_for(self, goals: Iterable[int]) -> tuple[int, ...]:
        """The units a tree for any of ``goals`` can use (sorted): :func:`walk_back` through
        the viable producers; exactly the encoding's candidate units
        (docs/proofs/preparation.md, "Relevance")."""
        goals = list(goals)
        if "viable_units" in vars(self):
            units, _, _ = walk_back(goals, self.kitchen, self.viable_producers, self.required)
            return tuple(sorted(units))
        # viability computed on the goals' relevant part alone: every unit that makes an input of a
        # relevant unit is relevant, so a relevant unit fires there exactly when it fires in the FOON
        relevant, objects, _ = walk_back(goals, self.kitchen, self.producers, self.required)
        fires = self.derivation_levels(sorted(relevant))[1]
        producers = {o: [u for u in self.producers.get(o, ()) if u in fires] for o in objects}
        units, _, _ = walk_back(goals, self.kitchen, producers, self.required)
        return tuple(sorted(units))

    def relevant_units(self, goal: int) -> list[int]:
        """Units that can contribute to ``goal`` (backwards from it, kitchen items stop)."""
        return sorted(walk_back([goal], self.kitchen, self.producers, self.required)[0])
