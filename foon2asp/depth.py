"""Depth bounds by multi-shot solving on one clingo Control.

``encodings/depth.lp`` has a ``#program step(t)`` part: round ``t`` of the
used units (``had_at(O,t)``), an external ``query(t)`` (the goal must be had
after ``t`` rounds) and an external ``within(t)`` (round ``t`` counts towards
the depth cost).  The loop lives here, in Python (``python -m clingo`` would
ignore an embedded incmode script): steps are grounded once, on demand, and
kept for all later goals of the session.

* depth first (``--objective depth[,…]``): raise the bound t = 1, 2, … until
  the goal is derivable; every smaller bound was proven unsatisfiable, so t is
  the minimum depth; the same solve optimises the remaining objectives
  (at least units) within it.
* depth later in the list (``--objective units,depth``): solve with the depth
  cost switched off; the depth d of that tree bounds the depth of the
  lexicographic optimum (which is optimal on the earlier objectives too), so
  a second solve with bound d and the depth cost on is the proven optimum.
  When d is already the least bound the grounder allows for the goal, no
  tree is shallower and the first tree is the optimum (no second solve).
* ``--max-depth N`` alone: one solve with query(N): units (etc.) within N.

The depth of a tree is the level of the goal in
:meth:`Problem.derivation_levels` over the tree's units, which is what
:func:`foon2asp.tree.measures` reports; ``had_at(O,t)`` is "level of O <= t".
"""

from __future__ import annotations

from typing import Callable

import clingo

from .errors import InputError


def ensure_steps(session, bound: int) -> None:
    """Ground ``step(1)`` … ``step(bound)`` on the session's Control (once each)."""
    done = getattr(session, "depth_steps", 0)
    if bound <= done:
        return
    parts = [("step", [clingo.Number(t)]) for t in range(done + 1, bound + 1)]
    try:
        session.ctl.ground(parts)
    except RuntimeError:
        raise InputError(session._message("grounding the depth steps")) from None
    session.depth_steps = bound


def bound_externals(bound: int, count_depth: bool) -> dict[clingo.Symbol, bool]:
    """The externals for depth bound ``bound``: query(bound), and within(1..bound) when the
    depth cost is counted."""
    out = {clingo.Function("query", [clingo.Number(bound)]): True}
    if count_depth:
        out.update({clingo.Function("within", [clingo.Number(t)]): True for t in range(1, bound + 1)})
    return out


def depth_mode(options, ranked: tuple[str, ...]) -> str:
    """``first`` | ``later`` (depth is an objective at that place) | ``bound`` (only --max-depth) | ``none``."""
    if "depth" in ranked:
        return "first" if ranked[0] == "depth" else "later"
    return "bound" if options.max_depth is not None else "none"


def grounded(session, goal: int, bound: int) -> bool:
    """Did the grounder instantiate ``had_at(goal,bound)``?  If not, no set of units makes
    the goal within ``bound`` rounds: the bound is refuted without solving."""
    atom = session.ctl.symbolic_atoms[clingo.Function("had_at", [clingo.Number(goal), clingo.Number(bound)])]
    return atom is not None


def solve_depth(
    session,
    goal: int,
    shot: Callable[[dict, str | None], object],
    tree_depth: Callable[[object], int],
    mode: str,
    state: dict,
    single: bool = True,
):
    """Run the depth strategy ``mode`` for ``goal`` with ``shot(externals, solve_mode)``.

    ``shot`` solves once with the given externals switched on (``solve_mode``
    None: as configured; "opt": one optimum; "first": the first model) and
    returns a result with ``answers``, ``unsat`` and ``finished``;
    ``tree_depth(answer)`` is the depth of an answer's tree.  ``state``
    persists across calls for the same goal: ``bound`` is the least bound not
    yet refuted, ``refuted`` lists ``(bound, how)`` with how = "grounder" (the
    goal atom was not even instantiated) or "solver" (unsatisfiable).
    ``single``: one optimum is wanted (not all trees of the optimal cost).
    Returns ``(result, bound)``.
    """
    max_depth = session.options.max_depth
    if mode == "bound":
        ensure_steps(session, max_depth)
        return shot(bound_externals(max_depth, False), None), max_depth
    limit = {}
    if max_depth is not None:
        ensure_steps(session, max_depth)
        limit = bound_externals(max_depth, False)
    if mode == "later":
        # the tree optimal without the depth cost bounds the optimum's depth
        first = shot(limit, "opt")
        if not first.answers:
            return first, max_depth
        bound = tree_depth(first.answers[0])
        if single:
            # no tree is shallower than the grounder's first bound for the goal: a tree
            # already that shallow is optimal for depth too (and for what follows)
            ensure_steps(session, bound - 1)
            if bound <= 1 or not grounded(session, goal, bound - 1):
                state["shortcut"] = True
                return first, bound
        ensure_steps(session, bound)
        return shot(bound_externals(bound, True), None), bound
    # depth first: raise the bound 1, 2, ... until the goal is derivable within it
    refuted = state.setdefault("refuted", [])
    bound = state.get("bound", 1)
    ceiling = None  # the depth of some remaining tree, once a bound fails
    while True:
        if max_depth is not None and bound > max_depth:
            return shot(limit, "first"), max_depth  # unsatisfiable: nothing within --max-depth
        ensure_steps(session, bound)
        if not grounded(session, goal, bound):
            refuted.append((bound, "grounder"))
            bound += 1
            if bound > len(session.problem.units) + 1:  # never: reach(G) was checked first
                return shot(limit, "first"), None
            continue
        result = shot(bound_externals(bound, True), None)
        if result.answers or not result.finished:
            state["bound"] = bound
            return result, bound
        refuted.append((bound, "solver"))
        if ceiling is None or bound >= ceiling:
            # constraints or excluded trees removed the shallow trees: any remaining
            # tree bounds the search (none left: done)
            feasible = shot(limit, "first")
            if not feasible.answers:
                return feasible, max_depth
            ceiling = tree_depth(feasible.answers[0])
        bound += 1
        state["bound"] = bound
