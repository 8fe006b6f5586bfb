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
satisfiability check under the cost bound.  With a time limit, the search may
stop early: the tree is then optimal but possibly not the smallest one.
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from typing import Any

import clingo

from foon2asp.asp.control import Answer, Control, read_model

LEX_ON = clingo.Function("lex_on", [])


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


def canonicalise(control: Control, answer: Answer, deadline: float | None = None) -> tuple[Answer, bool]:
    """The smallest optimal tree (``answer`` has the proven optimum cost), and whether that is proven.

    The externals of the goal must be on; they are left as they are.  The
    solver configuration (opt-mode, models, projection) is restored afterwards.
    """
    if not answer.cost:
        return answer, True  # no cost terms: every tree is optimal
    if control.ctl.symbolic_atoms[LEX_ON] is None:
        return answer, False  # the session was grounded without encodings/canonical.lp
    conf: Any = control.ctl.configuration.solve
    saved = (conf.opt_mode, conf.models, conf.project)
    conf.opt_mode = "enum," + ",".join(str(c) for c in answer.cost)
    conf.models = "1"
    conf.project = "no"
    best = answer
    complete = False
    found: list[Answer] = []

    def record(model: clingo.Model) -> None:
        found[:] = [read_model(model, proven=True)]

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
            result = control.solve(record, remaining)
            if found and found[0].units != best.units:
                best = found[0]
                continue
            complete = result.finished and result.unsatisfiable is True
            break
    finally:
        off = {_cur(u): False for u in on}
        off[LEX_ON] = False
        control.assign(off)
        conf.opt_mode, conf.models, conf.project = saved
    return best, complete
