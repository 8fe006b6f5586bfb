"""What a goal's answer can depend on, for front ends that offer it as choices: the motions and
kitchen items of the goal's relevant part; and the knowledge base without some kitchen items."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace

from foon2asp.api.kb import GoalLike, KnowledgeBase
from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject


@dataclass(frozen=True)
class GoalPart:
    """The units a tree for one goal can use (its relevant part), as choices: their motions and
    the kitchen items they need."""

    goal: FoonObject
    #: how many units a tree for the goal can use
    units: int
    #: the motions of those units, sorted
    motions: tuple[str, ...]
    #: the kitchen items those units need, in id order
    kitchen: tuple[FoonObject, ...]


def relevant_part(kb: KnowledgeBase, goal: GoalLike) -> GoalPart:
    """The relevant part of ``goal`` (a label, an object's text, ``#ID``, ...) in ``kb``: the units
    a tree for it can use (docs/proofs/preparation.md, "Relevance"), their motions and kitchen items."""
    problem = kb.problem
    gid = kb.object_id(goal)
    units = problem.units_for([gid])
    motions = sorted({problem.units[u].motion for u in units})
    needed = sorted({o for u in units for o in problem.required[u] if o in problem.kitchen})
    return GoalPart(problem.objects[gid], len(units), tuple(motions), tuple(problem.objects[o] for o in needed))


def without_kitchen_items(kb: KnowledgeBase, items: Iterable[GoalLike]) -> KnowledgeBase:
    """``kb`` with the kitchen items ``items`` (texts, ``#ID``s, ids or objects) taken out of its
    kitchen; ``kb`` itself is unchanged.  An item not in the kitchen is an :class:`InputError`."""
    problem = kb.problem
    gone = set()
    for item in items:
        oid = kb.object_id(item)
        if oid not in problem.kitchen:
            raise InputError(f"{problem.objects[oid]} is not a kitchen item")
        gone.add(oid)
    if not gone:
        return kb
    smaller = problem.with_kitchen(problem.kitchen - gone)
    data = replace(kb.data, kitchen=[o for o in kb.data.kitchen if problem.foon.object_ids.get(o) not in gone])
    return KnowledgeBase(data, smaller, kb.warnings, kb.projection)
