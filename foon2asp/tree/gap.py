"""Lower bounds and gaps: how far an unproven answer may be from the optimum.

Why a level's bound is shown only once the levels above it are closed:
docs/proofs/preparation.md, "Bounds and gaps".
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from decimal import Decimal

from foon2asp.foon.motioncost import SCALE as COST_SCALE
from foon2asp.foon.motioncost import as_number
from foon2asp.foon.problem import Problem
from foon2asp.tree.tasktree import TaskTree
from foon2asp.tree.weights import SCALE, UNIT_WEIGHTS, unit_weight

#: the level of the solver's cost vector above the objectives when substitutes are used
SUBSTITUTIONS = "substitutions"
#: the level below the objectives when a person may take steps (fewest human steps)
HUMAN = "human"


def levels(ranked: Sequence[str], substitutes: bool = False, human: bool = False) -> tuple[str, ...]:
    """The names of the solver's priority levels, highest first, for the ranked objective list."""
    return ((SUBSTITUTIONS,) if substitutes else ()) + tuple(ranked) + ((HUMAN,) if human else ())


def value(name: str, weight: int) -> int | float:
    """A solver weight of level ``name`` in the units of a tree's cost."""
    if name == "success":
        return float(f"{math.exp(-weight / SCALE):.6g}")
    if name == "cost":
        return as_number(Decimal(weight) / COST_SCALE)
    return weight


def weights(problem: Problem, tree: TaskTree, names: Sequence[str]) -> list[int] | None:
    """The solver's weight of ``tree`` on each level: its ``asp_cost`` when it has one for
    these levels, else computed from its units (None when a level cannot be)."""
    cost = tree.asp_cost
    if cost is not None and len(cost) == len(names):
        return [int(c) for c in cost]
    out = []
    for name in names:
        if name in UNIT_WEIGHTS or (name == "cost" and problem.motion_costs is not None):
            weight = unit_weight(problem, name)
            out.append(sum(weight(u) for u in tree.units))
        elif name == "depth" and tree.cost.get("depth") is not None:
            out.append(int(tree.cost["depth"]))
        else:
            return None
    return out


def gap_of(upper: Sequence[int], lower: Sequence[int] | None, first: int = 0, floor: int | None = None) -> float | None:
    """The relative gap on level ``first`` between an answer of weights ``upper`` and the lower
    bound ``lower`` (per level, possibly shorter) raised to ``floor``; None while the levels
    above ``first`` are not closed (their bound is below the answer's weight)."""
    best = list(lower or ()) + [0] * (len(upper) - len(lower or ()))
    if any(best[k] < upper[k] for k in range(first)):
        return None
    low = max(best[first], floor or 0) if first < len(best) else floor or 0
    top = upper[first] if first < len(upper) else 0
    return 0.0 if top <= 0 else round(max(0.0, (top - low) / top), 6)


def first_level(names: Sequence[str]) -> int:
    """The index of the first objective among the levels ``names`` (after the substitutions)."""
    return next((k for k, n in enumerate(names) if n != SUBSTITUTIONS), 0)


def settle(
    problem: Problem,
    tree: TaskTree,
    names: Sequence[str],
    lower: Sequence[int] | None = None,
    floor: int | None = None,
) -> TaskTree:
    """Set ``tree.bound`` (per level, in the units of ``cost``) and ``tree.gap`` from the solver's
    lower bound ``lower`` (per level of ``names``, possibly shorter) and ``floor`` (on the first
    objective's weight); a ``feasible`` answer the bound meets on every level becomes ``optimal``."""
    shown = [n for n in names if n != HUMAN]
    if not shown or tree.status in ("found", "not-found", "unreachable", "infeasible"):
        return tree
    first = first_level(names)
    if tree.status in ("optimal", "ranked") and tree.has_tree:
        used = sum(s.get("cost", 1) for s in tree.substitutions or ())  # the substitutions level
        tree.bound = {n: tree.cost.get(n, used if n == SUBSTITUTIONS else 0) for n in shown}
        tree.gap = 0.0
        return tree
    upper = weights(problem, tree, names) if tree.has_tree else None
    best = list(lower or ())
    best += [0] * (len(names) - len(best))
    if floor is not None and first == 0:
        best[0] = max(best[0], floor)
    bound: dict = {}
    closed = True
    for k, name in enumerate(names):
        if name != HUMAN:
            bound[name] = value(name, best[k] if closed else 0)
        closed = closed and upper is not None and best[k] >= upper[k]
    if closed and tree.status == "feasible":
        # the bound meets the answer on every level: it is optimal, proven by the bound
        tree.status = "optimal"
        tree.stats["proof"] = "lower bound"
        tree.note = tree.fallback = None
        return settle(problem, tree, names)
    tree.bound = bound
    if upper is not None:
        found = gap_of(upper, best, first)
        tree.gap = 1.0 if found is None else found
    return tree


def gap_text(tree: TaskTree) -> str:
    """``units 65, lower bound 54, gap 17%`` for an unproven answer with a bound ('' otherwise)."""
    if tree.bound is None or tree.gap is None or tree.status in ("optimal", "ranked"):
        return ""
    name = next((n for n in tree.bound if n != SUBSTITUTIONS), None)
    if name is None:
        return ""
    have = tree.cost.get(name)
    words = "upper bound" if name == "success" else "lower bound"
    head = f"{name} {number(have)}, " if have is not None else ""
    pct = 100 * tree.gap
    percent = f"{pct:.0f}%" if pct >= 1 or pct == 0 else f"{pct:.2g}%"
    return f"{head}{words} {number(tree.bound[name])}, gap {percent}"


def number(value: object) -> str:
    """A measure as every text output prints it: integers in full, other numbers to 4
    significant digits, ``-`` for none."""
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)
