"""Dominated units: producers no canonical optimal tree needs (``encodings/dominance.lp``).

A unit ``V`` *dominates* a unit ``U`` when

* ``V < U`` (FOON id order, the order of canonical trees: foon2asp.asp.canonical),
  or ``V`` costs strictly less than ``U`` in some ranked objective (below),
* every required input of ``V`` that is not a kitchen item is a required input of ``U``,
* ``V`` makes every product of ``U`` that is relevant to the goal (the products of
  ``U`` that ``V`` does not make are listed as ``dom_extra(V,U,O)``; the solver
  checks that none of them is ``relevant/1``, which depends on the goal), and
* ``V`` costs no more than ``U`` in every ranked objective: the same for
  ``units`` and ``depth`` (``V`` fires no later than ``U``), at most the success
  weight for ``success``, at most the input nodes for ``inputs``.

Then in a tree that uses ``U``, ``U`` can be replaced by ``V`` (``V`` fires
whenever ``U`` does and makes what ``U`` made for the tree): the tree stays valid
and costs no more; if ``V`` is in the tree already, dropping ``U`` is cheaper.
So an optimal tree using ``U`` gives an optimal tree without it that is smaller
in the canonical order (``V < U``; when ``V`` is cheaper, no optimal tree uses
``U`` at all), and the canonical optimal tree never uses a dominated unit: forbidding them changes neither the optimum nor the canonical tree, only
removes interchangeable alternatives the proof of optimality would otherwise
have to rule out one by one.

Only valid when every answer is an optimal tree with nothing else asked of it:
:func:`applies` leaves it out with user programs, extra encodings, human steps,
several trees per goal or all optimal trees (those may need a dominated unit).
"""

from __future__ import annotations

from collections.abc import Iterable

from foon2asp.foon.problem import Problem
from foon2asp.tree.weights import UNIT_WEIGHTS

#: objectives under which dominance is known to keep the optimum (the cost tests of :func:`dominance_facts`)
SUPPORTED = frozenset({"units", "success", "inputs", "depth"})


def applies(options, ranked: Iterable[str]) -> bool:
    """Does a session with ``options`` (objectives ``ranked``) forbid dominated units?"""
    return bool(
        not options.programs
        and not options.encodings
        and not options.heuristic
        and options.human_steps is None
        and options.models <= 1
        and not options.all_optimal
        and set(ranked) <= SUPPORTED
    )


def dominance_pairs(
    problem: Problem, units: Iterable[int], ranked: Iterable[str] = ("units",)
) -> list[tuple[int, int, tuple[int, ...]]]:
    """``(V, U, extra)`` for each unit ``V`` of ``units`` that dominates a unit ``U`` of
    ``units`` when none of the products ``extra`` (made by ``U``, not by ``V``) is relevant."""
    ranked = set(ranked)
    kitchen = problem.kitchen
    pool = sorted(set(units))
    required = {u: frozenset(i for i in problem.required[u] if i not in kitchen) for u in pool}
    products = {u: frozenset(o for o in problem.products[u] if o not in kitchen) for u in pool}
    producers: dict[int, list[int]] = {}
    for u in pool:
        for o in products[u]:
            producers.setdefault(o, []).append(u)  # in id order
    # the ranked objectives that weigh units differently (units weighs them all 1; depth is not a sum)
    weight = {n: {u: UNIT_WEIGHTS[n](problem, u) for u in pool} for n in ranked if n in UNIT_WEIGHTS}
    pairs = []
    for u in pool:
        seen: set[int] = set()
        for o in sorted(products[u]):
            for v in producers[o]:
                if v == u or v in seen:
                    continue
                seen.add(v)
                if not required[v] <= required[u]:
                    continue
                if any(w[v] > w[u] for w in weight.values()):
                    continue
                if v > u and not any(w[v] < w[u] for w in weight.values()):
                    continue
                pairs.append((v, u, tuple(sorted(products[u] - products[v]))))
    return pairs


def dominance_facts(problem: Problem, units: Iterable[int], ranked: Iterable[str] = ("units",)) -> str:
    """``dom(V,U).`` and ``dom_extra(V,U,O).`` for :func:`dominance_pairs` (read by dominance.lp)."""
    out = []
    for v, u, extra in dominance_pairs(problem, units, ranked):
        out.append(f"dom({v},{u}).\n")
        out += [f"dom_extra({v},{u},{o}).\n" for o in extra]
    return "".join(out)
