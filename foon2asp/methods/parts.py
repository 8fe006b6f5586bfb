"""A problem's viable units and each goal's relevant part, computed once, and the batch grounding.

:class:`Parts` keeps what the routes of the goal runner read (viable units, relevant parts,
bounds, dominators); :func:`choose_grounding` picks ``batch --grounding auto``.
"""

from __future__ import annotations

import statistics

from foon2asp.asp.dominance import Dominators
from foon2asp.bounds.lower import Bounds
from foon2asp.foon.problem import Problem, walk_back
from foon2asp.tree.tasktree import Goals, meal_of
from foon2asp.tree.weights import lexicographic

GROUNDINGS = ("whole", "per-goal")

#: FOONs with more viable units than this build a goal's bounds on its part first (Parts.bounds_for)
PART_BOUNDS_MIN = 20_000
#: ... when the part is less than 1/PART_BOUNDS_SHARE of them
PART_BOUNDS_SHARE = 4

#: how many goals' relevant parts Parts keeps
RELEVANT_KEPT = 64


class Parts:
    """Viable units and per-goal relevant parts of one problem (computed once)."""

    def __init__(self, problem: Problem):
        self.problem = problem
        self.viable: frozenset[int] = problem.viable_units
        self.producers: dict[int, list[int]] = problem.viable_producers
        self._bounds: dict[tuple[str, ...], Bounds] = {}
        #: units covered so far by bounds built on goals' parts
        self._part_bounds_spent: dict[tuple[str, ...], int] = {}
        self._weights: dict[tuple[str, ...], list[int]] = {}
        self._dominators: dict[tuple[str, ...], Dominators] = {}
        #: the relevant parts of the goals asked lately
        self._relevant: dict[tuple[int, ...], tuple[list[int], set[int], bool]] = {}

    def dominators(self, ranked_objectives: tuple[str, ...]) -> Dominators:
        """The dominators for these objectives, built once."""
        if ranked_objectives not in self._dominators:
            self._dominators[ranked_objectives] = Dominators(self.problem, ranked_objectives)
        return self._dominators[ranked_objectives]

    def bounds(self, ranked_objectives: tuple[str, ...]) -> Bounds:
        """The bounds for these ranked objectives, built once."""
        if ranked_objectives not in self._bounds:
            self._bounds[ranked_objectives] = Bounds(self.problem, ranked_objectives)
        return self._bounds[ranked_objectives]

    def bounds_for(self, ranked_objectives: tuple[str, ...], units: list[int]) -> Bounds:
        """The bounds for a goal whose relevant part is ``units``: on the part alone while that is
        cheaper, then the whole FOON's (both give the same answers)."""
        whole = self._bounds.get(ranked_objectives)
        size = len(self.viable)
        if whole is None and size > PART_BOUNDS_MIN and PART_BOUNDS_SHARE * len(units) < size:
            spent = self._part_bounds_spent.get(ranked_objectives, 0) + len(units)
            if spent <= size:
                self._part_bounds_spent[ranked_objectives] = spent
                if ranked_objectives not in self._weights:
                    self._weights[ranked_objectives] = lexicographic(self.problem, ranked_objectives[0])
                return Bounds(self.problem, ranked_objectives, units, self._weights[ranked_objectives])
        return self.bounds(ranked_objectives)

    def relevant(self, goal: Goals) -> tuple[list[int], set[int], bool]:
        """``(units, objects, choice)`` of the goal's (or meal's) relevant part: the candidate units,
        the goal and the required inputs reached, whether some object has several producers."""
        key = meal_of(goal)
        if key not in self._relevant:
            if len(self._relevant) >= RELEVANT_KEPT:
                self._relevant.clear()
            found, reached, choice = walk_back(key, self.problem.kitchen, self.producers, self.problem.required)
            self._relevant[key] = (sorted(found), reached, choice)
        units, objects, choice = self._relevant[key]
        return list(units), set(objects), choice


#: --grounding: "auto" picks whole or per-goal with :func:`choose_grounding`
GROUNDING_CHOICES = ("auto", *GROUNDINGS)
#: auto: per-goal when the median relevant part is below this share of the viable units ...
AUTO_PART_SHARE = 0.10
#: ... or when there are more viable units than this (the whole grounding's memory)
AUTO_MAX_WHOLE = 50_000
#: ... judged on this many goals, spread over the list
AUTO_SAMPLE = 50


def choose_grounding(problem: Problem, goals: list[int], parts: Parts | None = None) -> tuple[str, str]:
    """``(grounding, reason)`` for ``--grounding auto``: ``per-goal`` for a large FOON or small
    parts (:data:`AUTO_MAX_WHOLE`, :data:`AUTO_PART_SHARE`), else ``whole``."""
    parts = parts if parts is not None else Parts(problem)
    viable = len(parts.viable)
    if viable > AUTO_MAX_WHOLE:
        return "per-goal", f"{viable:,} viable units (more than {AUTO_MAX_WHOLE:,})"
    if not goals:
        return "whole", "no goals"
    step = max(1, len(goals) // AUTO_SAMPLE)
    sample = goals[::step][:AUTO_SAMPLE]
    median = statistics.median(len(parts.relevant(g)[0]) for g in sample)
    share = median / max(1, viable)
    if share < AUTO_PART_SHARE:
        return "per-goal", f"median relevant part {median:g} of {viable:,} viable units ({share:.1%}, under 10 %)"
    return "whole", f"median relevant part {median:g} of {viable:,} viable units ({share:.1%}, 10 % or more)"
