"""Objectives: their order and the facts they read (input nodes, motion costs, greedy ranks, human order).

Objectives are lexicographic (``objective(Name,Priority)``, docs/objectives.md), with
``units`` always the last tie-breaker.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from foon2asp.asp.facts import unit_ids
from foon2asp.errors import InputError
from foon2asp.foon.motioncost import DEFAULT_COST, motion_key, scaled
from foon2asp.foon.problem import Problem
from foon2asp.tree.weights import HEURISTICS, UNIT_WEIGHTS, total


def ranked(options) -> tuple[str, ...]:
    """The objective list the solver optimises: the user's, then ``units`` as tie-breaker."""
    if options.heuristic:
        return ()
    objective = tuple(dict.fromkeys(options.objective))
    return objective if "units" in objective else (*objective, "units")


def objective_facts(objective: Iterable[str]) -> str:
    """``objective(Name,P).``: the objectives in order, most important first with the highest
    priority P (n down to 1); the one place these facts are written."""
    names = list(dict.fromkeys(objective))
    return "".join(f"objective({name},{len(names) - i}).\n" for i, name in enumerate(names))


def input_node_facts(problem: Problem, units: Iterable[int] | None = None) -> str:
    """``input_nodes(U,N).``: N input nodes as the FOON lists them."""
    ids = unit_ids(problem, units)
    return "".join(f"input_nodes({u},{len(problem.inputs[u])}).\n" for u in ids)


def motion_cost_weights(problem: Problem, costs: dict[str, int], units: Iterable[int] | None = None) -> dict[int, int]:
    """Unit -> the integer weight of its motion (``costs``: motion -> cost in hundredths; default 1)."""
    ids = unit_ids(problem, units)
    default = scaled(DEFAULT_COST)
    keyed = {motion_key(m): w for m, w in costs.items()}
    return {u: keyed.get(problem.units[u].motion, default) for u in ids}


def motion_cost_facts(problem: Problem, options, units: Iterable[int] | None = None) -> str:
    """``motion_cost(U,C).``: C is the cost of U's motion in hundredths."""
    if options.motion_costs is None:
        raise InputError("the objective 'cost' needs a motion-cost table (--motion-cost FILE)")
    weights = motion_cost_weights(problem, options.motion_costs, units)
    bad = [w for w in weights.values() if not isinstance(w, int) or w < 0]
    if bad:
        raise ValueError(f"motion-cost weights must be integers >= 0, not {bad[0]!r}")
    return "".join(f"motion_cost({u},{w}).\n" for u, w in weights.items())


def greedy_key(problem: Problem, heuristic: str, unit: int) -> tuple[float, int]:
    """The order of producers for greedy retrieval (smaller first): the heuristic's score
    (:data:`foon2asp.tree.weights.HEURISTICS`, as the search baselines score), highest first,
    ties in FOON file order."""
    if heuristic not in HEURISTICS:
        raise ValueError(f"unknown heuristic {heuristic!r}")
    return (-HEURISTICS[heuristic](problem, unit), unit)


def rank_facts(problem: Problem, heuristic: str, units: Iterable[int] | None = None) -> str:
    """``rank(O,U,R).``: U is the producer of O (among ``units``) that greedy retrieval tries R-th."""
    ids = unit_ids(problem, units)
    producers: dict[int, list[int]] = {}
    for u in ids:
        for o in problem.products[u]:
            producers.setdefault(o, []).append(u)
    out = []
    for o, us in producers.items():
        us.sort(key=lambda u: greedy_key(problem, heuristic, u))
        out += [f"rank({o},{u},{r}).\n" for r, u in enumerate(us)]
    return "".join(out)


def human_order_facts(problem: Problem, units: Iterable[int] | None = None) -> str:
    """``human_unit(P,U).``: the units with a positive success weight, heaviest first."""
    ids = unit_ids(problem, units)
    weight = UNIT_WEIGHTS["success"]
    weighted = [(weight(problem, u), u) for u in ids]
    order = sorted(((-w, u) for w, u in weighted if w > 0))
    return "".join(f"human_unit({p},{u}).\n" for p, (_, u) in enumerate(order, 1))


def success_product(problem: Problem, units: Iterable[int], human: Iterable[int] = ()) -> float:
    """The real product of the motion success rates; human steps count as 1.0."""
    skip = set(human)
    product = math.prod(problem.rates[u] for u in units if u not in skip)
    return float(f"{product:.6g}")


def neglog_sum(problem: Problem, units: Iterable[int], human: Iterable[int] = ()) -> int:
    """The integer success cost the solver minimises (sum of the neglog weights)."""
    skip = set(human)
    return total(problem, "success", (u for u in units if u not in skip))
