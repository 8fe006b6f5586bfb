"""The canonical optimal tree: among several optimal trees, one that depends only on the input.

Which optimal model clingo reports first depends on its search history: the
grounding (whole or per goal), the goals solved before on the same control,
the number of threads.  Once the optimum cost ``C`` of a goal is proven,
:func:`canonicalise` replaces the tree by the *lexicographically smallest*
optimal tree: order the units by FOON id and compare two trees at the
smallest unit in which they differ -- the tree holding it is smaller.  Only
the goal's candidate units can ever differ, and they are the same in every
grounding, so the result does not depend on the grounding.

``encodings/canonical.lp`` is grounded once with the session (a chain of
auxiliary atoms over the grounded units in id order, :func:`chain_facts`).
:func:`canonicalise` switches ``lex_cur(U)`` on for the units of the current
tree and ``lex_on`` on, and asks, on the same grounding and with the goal's
externals still on, for a tree of cost at most ``C`` (``opt-mode=enum,C``); each
tree found is smaller and becomes the current one, until none is left.  When
the tree is the only optimal one (the usual case), this costs one
satisfiability check under the cost bound.

*Bounded, and still deterministic.*  Proving that no smaller optimal tree
exists can cost far more than proving the optimum (on FOONs with real choice,
seconds to minutes against tenths of a second), so the search is bounded by a
budget of clasp conflicts (:data:`CONFLICTS`), not by time.  It runs only in
the goal's *canonical session* (:func:`canonical_problem`: a fresh grounding of
the goal's part, solved from scratch), where clasp is deterministic, so the
tree it ends with -- the smallest optimal tree when the search completes
within the budget, else the smallest one it reached -- depends only on the
input and the options.  A session that is not the goal's canonical session
hands the goal to one (:meth:`foon2asp.asp.session.Session.solve`).  A wall
time limit that cuts the search short leaves an optimal tree that may not be
the canonical one (marked in the tree's stats).
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from typing import Any

import clingo

from foon2asp.asp.control import Answer, Control, read_model
from foon2asp.foon.problem import Problem

LEX_ON = clingo.Function("lex_on", [])

#: the budget of the search for a smaller optimal tree, in clasp conflicts (about 0.7 s on a
#: 2,850-unit part; measured in BENCHMARKS.md, "Canonical trees")
CONFLICTS = 5000


def canonical_problem(problem: Problem, goals: Iterable[int]) -> tuple[Problem, tuple[int, ...]]:
    """What the canonical session of ``goals`` grounds: ``(view, units)``, the goals' part
    (sorted) and the problem with the kitchen cut down to the goals and the part's required
    inputs (so the facts are the same whichever view of the problem the caller holds)."""
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
    control: Control, answer: Answer, deadline: float | None = None, conflicts: int | None = None
) -> tuple[Answer, bool]:
    """The smallest optimal tree (``answer`` has the proven optimum cost), and whether that is proven.

    At most ``conflicts`` clasp conflicts in all (None: :data:`CONFLICTS`) and, with a
    ``deadline``, no longer than that: the smallest tree found so far otherwise.
    The externals of the goal must be on; they are left as they are.  The
    solver configuration (opt-mode, models, projection, limit) is restored afterwards.
    """
    if not answer.cost:
        return answer, True  # no cost terms: every tree is optimal
    if control.ctl.symbolic_atoms[LEX_ON] is None:
        return answer, False  # the session was grounded without encodings/canonical.lp
    conf: Any = control.ctl.configuration.solve
    saved = (conf.opt_mode, conf.models, conf.project, conf.solve_limit)
    conf.opt_mode = "enum," + ",".join(str(c) for c in answer.cost)
    conf.models = "1"
    conf.project = "no"
    best = answer
    complete = False
    found: list[Answer] = []

    def record(model: clingo.Model) -> None:
        found[:] = [read_model(model, proven=True)]

    if conflicts is None:
        conflicts = CONFLICTS
    on: set[int] = set()
    try:
        while True:
            tree = set(best.units)
            switch = {_cur(u): True for u in tree - on}
            switch.update({_cur(u): False for u in on - tree})
            switch[LEX_ON] = True
            control.assign(switch)
            on = tree
            found.clear()
            remaining = None if deadline is None else max(0.0, deadline - time.perf_counter())
            if conflicts <= 0:
                break
            conf.solve_limit = str(conflicts)
            result = control.solve(record, remaining)
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
        conf.opt_mode, conf.models, conf.project, conf.solve_limit = saved
    return best, complete
