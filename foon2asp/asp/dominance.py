"""Dominated units: producers no canonical optimal tree needs (``encodings/dominance.lp``).

A unit ``V`` dominates ``U`` when it can replace ``U`` in any tree at no greater cost and
comes first in FOON id order or costs less (docs/proofs/preparation.md, "Dominance").
"""

from __future__ import annotations

from collections.abc import Iterable

from foon2asp.foon.problem import Problem
from foon2asp.tree.weights import UNIT_WEIGHTS

#: objectives under which dominance is known to keep the optimum (the cost tests of :func:`dominance_facts`)
SUPPORTED = frozenset({"units", "success", "inputs", "depth"})


def applies(options, ranked: Iterable[str]) -> bool:
    """Does a session with ``options`` (objectives ``ranked``) forbid dominated units?"""
    alternatives = options.models > 1 or options.all_optimal
    extras = options.programs or options.heuristic or options.human_steps is not None
    return not (alternatives or extras) and set(ranked) <= SUPPORTED


class Dominators:
    """The units that dominate each unit, for one problem and ranked objectives, among
    ``producers`` (object -> its producers in id order; default: the viable producers)."""

    def __init__(
        self, problem: Problem, ranked: Iterable[str] = ("units",), producers: dict[int, list[int]] | None = None
    ):
        self.problem = problem
        self.producers = problem.viable_producers if producers is None else producers
        self._weights = [UNIT_WEIGHTS[n] for n in sorted(set(ranked)) if n in UNIT_WEIGHTS]
        self._unit: dict[int, tuple[frozenset[int], frozenset[int], tuple[int, ...]]] = {}
        self._of: dict[int, list[tuple[int, tuple[int, ...]]]] = {}

    def _facts(self, u: int) -> tuple[frozenset[int], frozenset[int], tuple[int, ...]]:
        """``u``'s required inputs and products that are not kitchen items, and its weights."""
        if u not in self._unit:
            problem, kitchen = self.problem, self.problem.kitchen
            required = frozenset(i for i in problem.required[u] if i not in kitchen)
            products = frozenset(o for o in problem.products[u] if o not in kitchen)
            self._unit[u] = required, products, tuple(w(problem, u) for w in self._weights)
        return self._unit[u]

    def of(self, u: int) -> list[tuple[int, tuple[int, ...]]]:
        """``(V, extra)`` for each unit ``V`` that dominates ``u`` when none of ``extra`` is relevant."""
        if u in self._of:
            return self._of[u]
        required, products, weight = self._facts(u)
        found = []
        seen: set[int] = set()
        for o in sorted(products):
            for v in self.producers.get(o, ()):
                if v == u or v in seen:
                    continue
                seen.add(v)
                required_v, products_v, weight_v = self._facts(v)
                if not required_v <= required:
                    continue
                if any(a > b for a, b in zip(weight_v, weight, strict=True)):
                    continue
                if v > u and not any(a < b for a, b in zip(weight_v, weight, strict=True)):
                    continue
                found.append((v, tuple(sorted(products - products_v))))
        self._of[u] = found
        return found

    def dominated(self, goal: int, units: Iterable[int]) -> set[int]:
        """The units of ``units`` that a unit among them dominates for ``goal`` (every product
        not made by the dominating unit irrelevant: not the goal, no required input of ``units``)."""
        pool = set(units)
        relevant = {goal}.union(*(self.problem.required[u] for u in pool))
        return {u for u in pool if any(v in pool and relevant.isdisjoint(extra) for v, extra in self.of(u))}


def dominance_pairs(
    problem: Problem, units: Iterable[int], ranked: Iterable[str] = ("units",)
) -> list[tuple[int, int, tuple[int, ...]]]:
    """``(V, U, extra)``: among ``units``, ``V`` dominates ``U`` when none of the products
    ``extra`` (made by ``U``, not by ``V``) is relevant."""
    kitchen = problem.kitchen
    pool = sorted(set(units))
    producers: dict[int, list[int]] = {}
    for u in pool:
        for o in problem.products[u]:
            if o not in kitchen:
                producers.setdefault(o, []).append(u)  # in id order
    dominators = Dominators(problem, ranked, producers)
    return [(v, u, extra) for u in pool for v, extra in dominators.of(u)]


def dominance_facts(problem: Problem, units: Iterable[int], ranked: Iterable[str] = ("units",)) -> str:
    """``dom(V,U).`` and ``dom_extra(V,U,O).`` for :func:`dominance_pairs`."""
    out = []
    for v, u, extra in dominance_pairs(problem, units, ranked):
        out.append(f"dom({v},{u}).\n")
        out += [f"dom_extra({v},{u},{o}).\n" for o in extra]
    return "".join(out)
