"""The canonical optimal tree: among several optimal trees, one that depends only on the input.

The lexicographically smallest optimal tree (units in FOON id order), searched with
``encodings/canonical.lp`` on the same grounding within a budget of clasp conflicts
(docs/proofs/solving.md).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import clingo

from foon2asp.asp.control import Control, remaining
from foon2asp.foon.problem import Problem
from foon2asp.tree.tasktree import TaskTree

LEX_ON = clingo.Function("lex_on", [])

#: the budget of the search for a smaller optimal tree, in clasp conflicts (BENCHMARKS.md,
#: "Canonical trees")
CONFLICTS = 5000


def canonical_problem(problem: Problem, goals: Iterable[int]) -> tuple[Problem, tuple[int, ...]]:
    """What the canonical session of ``goals`` grounds: the problem with the kitchen cut down to
    the goals and the part's required inputs, and the goals' part (sorted)."""
    goals = list(goals)
    part = problem.units_for(goals)
    keep = set(goals).union(*(problem.required[u] for u in part))
    kitchen = frozenset(o for o in problem.kitchen if o in keep)
    if kitchen == problem.kitchen:
        return problem, part
    return problem.with_kitchen(kitchen), part


def chain_facts(units: Iterable[int]) -> str:
    """``lex_first/1`` and ``lex_next/2``: the units in id order."""
    order = sorted(set(units))
    if not order:
        return ""
    lines = [f"lex_first({order[0]}).\n"]
    lines += [f"lex_next({a},{b}).\n" for a, b in zip(order, order[1:])]
    return "".join(lines)


def _cur(u: int) -> clingo.Symbol:
    return clingo.Function("lex_cur", [clingo.Number(u)])


def canonicalise(
    control: Control, answer: TaskTree, deadline: float | None = None, conflicts: int | None = None
) -> tuple[TaskTree, bool]:
    """The smallest optimal tree (``answer``, a tree read from a model, has the proven optimum
    cost; the result is ``answer`` or another model's tree), and whether that is proven within
    ``conflicts`` (None: :data:`CONFLICTS`) and the ``deadline``."""
    if not answer.asp_cost:
        return answer, True
    if not control.has_atom(LEX_ON):
        return answer, False  # the session was grounded without encodings/canonical.lp
    best = answer
    complete = False
    found: list[TaskTree] = []

    def record(model: clingo.Model) -> None:
        found[:] = [TaskTree.from_model(model, proven=True)]

    if conflicts is None:
        conflicts = CONFLICTS
    on: set[int] = set()
    conf: Any = control.ctl.configuration.solve
    enum = ",".join(["enum", *map(str, answer.asp_cost)])
    try:
        with control.configured(opt_mode=enum, models="1", project="no", solve_limit=conf.solve_limit):
            while True:
                tree = set(best.units)
                switch = {_cur(u): True for u in tree - on}
                switch.update({_cur(u): False for u in on - tree})
                switch[LEX_ON] = True
                control.assign(switch)
                on = tree
                found.clear()
                if conflicts <= 0:
                    break
                conf.solve_limit = str(conflicts)
                result = control.solve(record, remaining(deadline))
                conflicts -= control.stats().get("conflicts", conflicts)
                if found and found[0].units != best.units:
                    best = found[0]
                    continue
                complete = result.finished and result.unsatisfiable is True
                break
    finally:
        off = {_cur(u): False for u in on}
        off[LEX_ON] = False
        control.assign(off)
    return best, complete
