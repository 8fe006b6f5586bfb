"""``--grounding auto``: whether a batch grounds the whole FOON once or each goal's part.

:func:`choose_grounding` judges the FOON by its viable units and a sample of
the goals' relevant parts (:class:`foon2asp.methods.runner.Parts`).
"""

from __future__ import annotations

import statistics

from foon2asp.foon.problem import Problem
from foon2asp.methods.runner import GROUNDINGS, Parts

#: --grounding: "auto" picks whole or per-goal with :func:`choose_grounding`
GROUNDING_CHOICES = ("auto", *GROUNDINGS)
#: auto: per-goal when the median relevant part is below this share of the viable units ...
AUTO_PART_SHARE = 0.10
#: ... or when there are more viable units than this (the whole grounding's memory)
AUTO_MAX_WHOLE = 50_000
#: ... judged on this many goals, spread over the list
AUTO_SAMPLE = 50


def choose_grounding(problem: Problem, goals: list[int], parts: Parts | None = None) -> tuple[str, str]:
    """``(grounding, reason)`` for ``--grounding auto``.

    ``per-goal`` when the FOON has more than :data:`AUTO_MAX_WHOLE` viable
    units (one grounding of everything costs minutes and gigabytes there), or
    when the median relevant part of a sample of the goals
    (:meth:`Parts.relevant`) is under :data:`AUTO_PART_SHARE` of the viable
    units (each small grounding is then cheap, and one big one would be
    searched for every goal); ``whole`` otherwise (the parts overlap most of
    the FOON, so grounding each of them again would repeat the same work).
    """
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
