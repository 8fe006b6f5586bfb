"""What the library knows by name: the methods, objectives, utensil rules, batch groundings and
object filters, for front ends that offer them as choices (and the precision of motion costs)."""

from __future__ import annotations

from foon2asp import methods as methods_mod
from foon2asp.analysis.compare import DEFAULT_METHODS
from foon2asp.asp.options import OBJECTIVES as _OBJECTIVES
from foon2asp.foon.goals import OBJECT_FILTERS as _OBJECT_FILTERS
from foon2asp.foon.motioncost import PRECISION_TEXT
from foon2asp.foon.problem import UTENSIL_RULES as _UTENSIL_RULES
from foon2asp.methods.parts import GROUNDING_CHOICES
from foon2asp.methods.registry import Method

#: objective names, for ``objective=`` (lexicographic lists of them)
OBJECTIVES: tuple[str, ...] = tuple(_OBJECTIVES)
#: how exact motion costs are (``motion_cost=``), in words
MOTION_COST_PRECISION: str = PRECISION_TEXT
#: ``utensil_rule=`` of :func:`foon2asp.api.load`: when a utensil holding one ingredient is not a required input
UTENSIL_RULES: tuple[str, ...] = tuple(_UTENSIL_RULES)
#: ``grounding=`` of a batch: ``auto`` chooses ``whole`` or ``per-goal``
GROUNDINGS: tuple[str, ...] = tuple(GROUNDING_CHOICES)
#: the methods :meth:`KnowledgeBase.compare` runs by default
COMPARE_METHODS: tuple[str, ...] = tuple(DEFAULT_METHODS)
#: ``only=`` of :meth:`KnowledgeBase.find_objects`
OBJECT_FILTERS: tuple[str, ...] = tuple(_OBJECT_FILTERS)


def methods() -> list[Method]:
    """Every registered method (``.name``, ``.kind``: ``asp`` or ``search``, ``.description``), in order."""
    return [methods_mod.get(name) for name in methods_mod.names()]


def method(name: str) -> Method:
    """The registered method ``name`` (an unknown name is an InputError listing the known ones)."""
    return methods_mod.get(name)
