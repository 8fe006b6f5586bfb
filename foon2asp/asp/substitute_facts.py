"""Substitutes in the solver: candidate facts, the problem a session solves, the report.

The candidates become ``substitute(N,K,C)`` facts; ``encodings/substitutes.lp`` chooses
among them, the least summed cost ranked above every objective (docs/vocabulary.md).
"""

from __future__ import annotations

from collections.abc import Iterable

import clingo

from foon2asp.asp import encoding_files
from foon2asp.asp.control import Control
from foon2asp.asp.facts import OPTIONAL, fact_objects, facts, unit_ids
from foon2asp.foon.model import FoonObject
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import StandIn, Substitute, candidates, with_substitutes


def numbered(cands: list[StandIn]) -> dict[FoonObject, int]:
    """The number ``K`` of each kitchen item that stands in for something, in candidate order."""
    out: dict[FoonObject, int] = {}
    for c in cands:
        out.setdefault(c.used, len(out))
    return out


def substitute_facts(
    problem: Problem,
    substitutes: Iterable[Substitute],
    units: Iterable[int] | None = None,
    limit: int | None = None,
    cands: list[StandIn] | None = None,
) -> str:
    """``substitute(N,K,C).`` for the objects of the facts of ``units`` (None: all), and
    ``max_substitutions(M).`` with a ``limit``; ``cands``: the candidates, when known."""
    if cands is None:
        cands = candidates(problem, substitutes)
    objects = fact_objects(problem, unit_ids(problem, units))
    number = numbered(cands)
    lines = [f"substitute({c.needed},{number[c.used]},{c.cost}).\n" for c in cands if c.needed in objects]
    if limit is not None:
        lines.append(f"max_substitutions({int(limit)}).\n")
    return "".join(lines)


def applies(options) -> bool:
    """Does a session with ``options`` solve with substitutes?"""
    return bool(getattr(options, "substitutes", ()))


def prepare(problem: Problem, options) -> Problem:
    """The problem a session with ``options`` solves: with substitutes, the one whose viability
    counts what they stand in for (which options combine with them: foon2asp.methods.plan.check)."""
    if not applies(options):
        return problem
    return with_substitutes(problem, options.substitutes)


def report(
    problem: Problem, goals: Iterable[int], units: Iterable[int], substitutes: Iterable[Substitute]
) -> list[dict]:
    """The substitutions the tree of ``units`` for ``goals`` uses, as ``{"needed", "used"}`` texts
    in object id order: the cheapest that let exactly these units make the goals."""
    substitutes = tuple(substitutes)
    units = sorted(set(units))
    goals = list(dict.fromkeys(goals))
    cands = candidates(problem, substitutes)
    objects = fact_objects(problem, units)
    if not any(c.needed in objects for c in cands):
        return []
    number = numbered(cands)
    used_of = {k: obj for obj, k in number.items()}
    program = [
        facts(problem, units=units, leave_out=OPTIONAL),
        "".join(f"goal({g}).\n" for g in goals),
        substitute_facts(problem, substitutes, units, cands=cands),
    ]
    control = Control(["--opt-mode=opt"])
    control.load(encoding_files.entry("find_substitutions"))  # exactly the tree's units
    control.add_all([("substitutions of a tree", "\n".join(program))])
    control.ground()
    chosen: list[tuple[int, int]] = []

    def record(model: clingo.Model) -> None:
        chosen[:] = [
            (s.arguments[0].number, s.arguments[1].number) for s in model.symbols(shown=True) if s.name == "subst"
        ]

    control.solve(record, None)
    return [{"needed": problem.objects[n].text, "used": used_of[k].text} for n, k in sorted(chosen)]
