"""The kitchen of a FOON that comes without one (``--kitchen leaves``): its leaves.

The leaves are every input no unit makes; a unit makes its outputs that are not bare
and not among its own inputs (docs/proofs/preparation.md, "Leaves").
"""

from __future__ import annotations

from collections.abc import Iterable

from foon2asp.foon.model import Foon, FoonObject, Unit

#: the kitchen named this (``--kitchen leaves``, ``load(kitchen="leaves")``) is the FOON's leaves
LEAVES = "leaves"


def made(units: Iterable[Unit]) -> set[FoonObject]:
    """The objects some unit of ``units`` makes (outputs that are not bare and not its own inputs)."""
    return {o for u in units for o in u.outputs if not o.is_bare() and o not in u.inputs}


def leaves(foon: Foon | Iterable[Unit]) -> list[FoonObject]:
    """Every input of a unit of ``foon`` (a FOON or units) that no unit makes, each once,
    in the order they first appear."""
    units = list(foon.units if isinstance(foon, Foon) else foon)
    makes = made(units)
    return list(dict.fromkeys(o for u in units for o in u.inputs if o not in makes))
