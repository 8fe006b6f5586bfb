"""The canonical optimal tree: among several optimal trees, one that depends only on the input.

Which optimal model clingo reports first depends on its search history: the
grounding (whole or per goal), the goals solved before on the same control,
the number of threads.  Once the optimum cost ``C`` of a goal is proven,
:func:`canonicalise` replaces the tree by the *lexicographically smallest*
optimal tree: order the goal's candidate units by FOON id (the same set in
every grounding: the goal's relevant, viable units) and compare two trees at
the smallest unit in which they differ -- the tree holding it is smaller.

It asks clingo, on the same grounding and with the same externals on, for an
optimal tree (``opt-mode=enum,C``: cost at most ``C``) smaller than the current
one -- a constraint guarded by a fresh external, with one chain of auxiliary
atoms "agrees with the current tree on all units up to u" -- and repeats with
each smaller tree found.  When the tree is the only optimal one (the usual
case), this costs one satisfiability check under the cost bound.  The answer
then depends only on the input and the options, whatever the grounding,
thread count, goal order or process; with a time limit, the search may stop
early (the tree is optimal but possibly not the smallest one).
"""

from __future__ import annotations

import time
from collections.abc import Iterable

import clingo

from foon2asp.asp.control import Answer, Control, deferred_signals


def _literals(control: Control, units: Iterable[int]) -> dict[int, int]:
    atoms = control.ctl.symbolic_atoms
    out = {}
    for u in units:
        atom = atoms[clingo.Function("use", [clingo.Number(u)])]
        if atom is not None:
            out[u] = atom.literal
    return out


def _smaller_than(control: Control, order: list[int], lits: dict[int, int], tree: set[int]) -> int:
    """A guard external that, when on, allows only trees smaller than ``tree`` (see the module doc)."""
    with deferred_signals(), control.backend() as backend:
        guard = backend.add_atom()
        backend.add_external(guard, clingo.TruthValue.False_)
        smaller = backend.add_atom()
        agree: int | None = None  # "agrees with tree on every unit so far" (None: true)
        last = max((u for u in order if u not in tree), default=None)
        for u in order:
            if last is None or u > last:
                break
            lit = lits[u]
            prefix = [] if agree is None else [agree]
            if u not in tree:
                backend.add_rule([smaller], prefix + [lit])
            nxt = backend.add_atom()
            backend.add_rule([nxt], prefix + [lit if u in tree else -lit])
            agree = nxt
        backend.add_rule([], [guard, -smaller])
    return guard


def canonicalise(
    control: Control,
    candidates: Iterable[int],
    answer: Answer,
    deadline: float | None = None,
) -> tuple[Answer, bool]:
    """The smallest optimal tree (``answer`` has the proven optimum cost), and whether that is proven.

    The externals of the goal must be on; they are left as they are.  The
    solver configuration (opt-mode, models, projection) is restored afterwards.
    """
    if not answer.cost:
        return answer, True  # no cost terms: every tree is optimal; the empty tree is the smallest
    lits = _literals(control, candidates)
    order = sorted(lits)
    if not any(u not in answer.units for u in order):
        return answer, True  # the tree uses every candidate: nothing is smaller
    conf = control.ctl.configuration.solve
    saved = (conf.opt_mode, conf.models, conf.project)
    conf.opt_mode = "enum," + ",".join(str(c) for c in answer.cost)
    conf.models = "1"
    conf.project = "no"
    best = answer
    complete = False
    found: list[Answer] = []

    def record(model: clingo.Model) -> None:
        units, human = [], []
        for s in model.symbols(shown=True):
            if s.name == "use" and len(s.arguments) == 1:
                units.append(s.arguments[0].number)
            elif s.name == "human" and len(s.arguments) == 1:
                human.append(s.arguments[0].number)
        found[:] = [Answer(tuple(sorted(units)), tuple(model.cost), True, tuple(sorted(human)))]

    try:
        while True:
            tree = set(best.units)
            if all(u in tree for u in order):
                complete = True
                break
            guard = _smaller_than(control, order, lits, tree)
            found.clear()
            remaining = None if deadline is None else max(0.0, deadline - time.perf_counter())
            try:
                control.assign({guard: True})  # type: ignore[dict-item]
                result = control.solve(record, remaining)
            finally:
                with deferred_signals():
                    control.ctl.release_external(guard)
            if found and tuple(found[0].units) != tuple(best.units):
                best = found[0]
                continue
            complete = result.finished and result.unsatisfiable is True
            break
    finally:
        conf.opt_mode, conf.models, conf.project = saved
    return best, complete
