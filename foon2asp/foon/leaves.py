"""The kitchen of a FOON that comes without one (``--kitchen leaves``): its leaves.

Merged generated trees have no ``kitchen.json``: what one starts from is
every object the units use that no unit makes.  A unit *makes* its outputs
that have states, ingredients or a container (a bare output, ``knife`` put
down after use, is not made, as :class:`foon2asp.foon.problem.Problem` has
it) and that are not among its own inputs: a unit that needs ``stove, on``
and puts it out again keeps the stove on, it does not make it, so ``stove,
on`` is a leaf.  Objects that only ever come out of units are never needed
and are left out.
"""

from __future__ import annotations

from collections.abc import Iterable

from foon2asp.foon.model import Foon, FoonObject, Unit


def made(units: Iterable[Unit]) -> set[FoonObject]:
    """The objects some unit of ``units`` makes (outputs that are not bare and not its own inputs)."""
    return {o for u in units for o in u.outputs if not o.is_bare() and o not in u.inputs}


def leaves(foon: Foon | Iterable[Unit]) -> list[FoonObject]:
    """Every input of a unit of ``foon`` (a FOON or units) that no unit makes, each once,
    in the order they first appear."""
    units = list(foon.units if isinstance(foon, Foon) else foon)
    makes = made(units)
    return list(dict.fromkeys(o for u in units for o in u.inputs if o not in makes))
