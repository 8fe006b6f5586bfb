"""What preparation hands clingo for one goal: the part to search and what is known of it.

Python prepares a goal in polynomial time (:mod:`foon2asp.methods.bounds`,
:mod:`foon2asp.asp.dominance`): the goal's relevant part without the units no
optimal tree needs, the landmark units every tree uses, a valid tree (the
bounds tree) and lower bounds.  A :class:`Preparation` carries them to a
:class:`~foon2asp.asp.session.Session`, which grounds ``encodings/prepared.lp``
over the candidates instead of ``tree.lp`` and writes the rest as facts:
``landmark/1`` and ``hint/1`` (the tree clingo tries first under
``--heuristic=Domain``).  The search for the optimum stays clingo's.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Preparation:
    """The prepared part of one goal."""

    goal: int
    #: the units clingo may use (sorted): every optimal tree's units are among them
    candidates: tuple[int, ...]
    #: units every tree for the goal uses
    landmarks: tuple[int, ...] = ()
    #: a valid tree to try first (a hint only: clingo decides)
    hint: tuple[int, ...] = ()
    #: the hint's cost vector as the solver weighs it, when the hint may be the answer:
    #: an optimum of that cost is answered with the hint (None: the hint is a hint only)
    known: tuple[int, ...] | None = None
    #: a lower bound on the first objective's weight (the landmarks), for bounds and gaps
    floor: int | None = None
    #: does a model of this cost vector meet the lower bound (so it is optimal)?
    meets: Callable[[tuple[int, ...]], bool] | None = None

    def facts(self) -> str:
        """``landmark/1``, ``hint/1`` and ``candidate/1`` facts."""
        lines = [f"candidate({u})." for u in self.candidates]
        lines += [f"landmark({u})." for u in self.landmarks]
        lines += [f"hint({u})." for u in self.hint]
        return "\n".join(lines) + "\n"
