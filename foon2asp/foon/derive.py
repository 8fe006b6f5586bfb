"""The least fixpoint with levels: what a set of units derives from a set of objects.

One function, :func:`least_fixpoint`, over integer ids: the derivation levels of
:class:`foon2asp.foon.problem.Problem`, its viable units, the trees the bounds trim
(:mod:`foon2asp.methods.bounds`), the goals the generator picks
(the synthetic FOONs of bench/synth.py) and the depth windows of the round-by-round driver
(:mod:`foon2asp.asp.multishot.depth`) all come from it.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence
from typing import Any

#: unit id -> object ids (a list indexed by unit, or a mapping)
Table = Sequence[Sequence[int]] | Mapping[int, Sequence[int]]


def least_fixpoint(
    start: Collection[int], required: Table, products: Table, units: Iterable[int]
) -> tuple[dict[int, int], dict[int, int]]:
    """``(object_level, unit_level)`` of the objects and units derived from ``start``.

    A unit of ``units`` fires at level 1 + the greatest level of its ``required``
    inputs (objects of ``start`` have level 0); its ``products`` get the unit's level
    (the least over their producers).  ``object_level`` holds the derived objects only,
    in the order they were derived (the objects of ``start`` are not in it);
    ``unit_level`` holds every unit that fires, in the order they fire.

    Breadth first: units fire in the order they become ready, so levels never
    decrease along the queue, and a unit's level is one more than that of the input
    that made it ready (the last of its inputs derived, so the highest).
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
    """A dict of the derived objects that also answers for every object of ``start`` (the
    kitchen) with ``value``, without storing them: ``in``, ``get`` and ``[]`` see them;
    iteration and ``len`` give the stored entries only.  A large FOON's kitchen has hundreds
    of thousands of items; a derivation over a goal's few units should not copy them."""

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
