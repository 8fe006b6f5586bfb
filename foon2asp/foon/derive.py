"""The least fixpoint with levels: what a set of units derives from a set of objects.

One function, :func:`least_fixpoint`, over integer ids: the derivation levels of
:class:`foon2asp.foon.problem.Problem`, its viable units, the trees the bounds trim
(:mod:`foon2asp.methods.bounds`), the goals the generator picks
(:mod:`foon2asp.foon.synth`) and the depth windows of the round-by-round driver
(:mod:`foon2asp.asp.multishot.depth`) all come from it.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence

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
    ``unit_level`` holds every unit that fires.
    """
    waiting: dict[int, int] = {}
    users: dict[int, list[int]] = {}
    obj_level: dict[int, int] = {}
    unit_level: dict[int, int] = {}
    frontier: list[int] = []
    for u in units:
        need = [o for o in required[u] if o not in start]
        waiting[u] = len(need)
        for o in need:
            users.setdefault(o, []).append(u)
        if not need:
            frontier.append(u)
    level = 0
    while frontier:
        level += 1
        new_objects = []
        for u in frontier:
            unit_level[u] = level
            for o in products[u]:
                if o not in obj_level and o not in start:
                    obj_level[o] = level
                    new_objects.append(o)
        frontier = []
        for o in new_objects:
            for u in users.get(o, ()):
                waiting[u] -= 1
                if waiting[u] == 0:
                    frontier.append(u)
    return obj_level, unit_level
