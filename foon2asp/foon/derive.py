"""The least fixpoint with levels: what a set of units derives from a set of objects.

Levels, viable units, the bounds' trees and the depth windows all come from
:func:`least_fixpoint` (docs/proofs/preparation.md, "The least fixpoint").
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
