"""Sessions: on FOONs with real choice (bench/synth.py presets) the answers are proven optima.

The optima are checked against references written without the solver: a depth-first search
over trees with one producer per needed object (pruned by the cost so far and a packing
bound), itself checked against tests/helpers.brute_force on small parts, and for depth the
goal's level in the least fixpoint of the kitchen.  A restricted grounding gives the same
answers as the whole one, and a search cut short still reports a valid tree.
"""

from __future__ import annotations

import math

import pytest

from foon2asp.api import KnowledgeBase
from foon2asp.asp.facts import neglog_weight
from foon2asp.asp.options import AspOptions
from foon2asp.bounds.upper import cheapest_tree
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.problem import Problem
from foon2asp.methods.plan import session_of as Session
from foon2asp.tree.validate import validate
from helpers import best, goal_part
from synth import preset

WEIGHT = {"units": lambda problem, u: 1, "success": lambda problem, u: neglog_weight(problem.rates[u])}


_REFERENCE: dict[tuple[int, int, str], tuple[Problem, float | None]] = {}


def reference(problem: Problem, goal: int, objective: str) -> float | None:
    """The least total weight of a well-founded tree for ``goal`` (None: no tree), by search."""
    key = (id(problem), goal, objective)
    # the entry keeps its problem: an id can be reused once a problem is gone
    kept = _REFERENCE.get(key)
    if kept is None or kept[0] is not problem:
        kept = _REFERENCE[key] = (problem, _search(problem, goal, objective))
    return kept[1]


def _search(problem: Problem, goal: int, objective: str) -> float | None:
    w = WEIGHT[objective]
    kitchen = problem.kitchen
    maxprod = max(len(p) for p in problem.products)
    cheapest = {o: min(w(problem, u) for u in us) for o, us in problem.producers.items()}
    start = cheapest_tree(problem, [goal], objective=objective)
    if start is None:
        return None
    found = [sum(w(problem, u) for u in start)]

    def search(made: frozenset, units: frozenset, cost: float, todo: set) -> None:
        todo = {o for o in todo if o not in made}
        if not todo:
            if validate(problem, goal, sorted(units)).valid:
                found[0] = min(found[0], cost)
            return
        # each open object needs a unit; one unit makes at most maxprod of them
        if cost + sum(cheapest.get(o, math.inf) for o in todo) / maxprod >= found[0]:
            return
        o = min(todo, key=lambda o: (len(problem.producers.get(o, ())), o))
        for u in problem.producers.get(o, ()):
            if u not in units:
                needs = {i for i in problem.required[u] if i not in kitchen}
                search(made | set(problem.products[u]), units | {u}, cost + w(problem, u), todo | needs)

    search(frozenset(), frozenset(), 0, {goal})
    return found[0]


def min_depth(problem: Problem, goal: int) -> int | None:
    return problem.derivation_levels()[0].get(goal)


@pytest.fixture(scope="module")
def tiny() -> KnowledgeBase:
    syn = preset("tiny")
    return KnowledgeBase(syn.dataset(), syn.problem())


@pytest.fixture(scope="module")
def small() -> KnowledgeBase:
    syn = preset("small")
    return KnowledgeBase(syn.dataset(), syn.problem())


def test_the_reference_agrees_with_brute_force_on_small_parts(tiny):
    p = tiny.problem
    checked = 0
    for g in tiny.goal_ids("all-objects"):
        found = goal_part(p, g)
        if found is None:
            continue
        sub, sg = found
        for objective, key in (("units", lambda m: m["units"]), ("depth", lambda m: m["depth"])):
            want, _ = best(sub, sg, key)
            got = reference(sub, sg, objective) if objective != "depth" else min_depth(sub, sg)
            assert got == want, (g, objective)
        checked += 1
    assert checked >= 10


@pytest.mark.parametrize("name", ["tiny", "small"])
def test_default_answers_are_optimal_and_match_the_reference(name, tiny, small):
    kb = tiny if name == "tiny" else small
    p = kb.problem
    goals = kb.goal_ids("all")
    for objective in ("units", "success", "depth"):
        trees = kb.solve(goals, objective=objective, time_limit=60)
        for g, t in zip(goals, trees):
            if objective == "depth":
                want = min_depth(p, g)
            else:
                want = reference(p, g, objective)
            if want is None:
                assert t.status == "unreachable", (name, objective, g)
                continue
            assert t.status == "optimal", (name, objective, g, t.status)
            assert validate(p, g, t.unit_ids).valid
            if objective == "depth":
                assert t.cost["depth"] == want, (name, g)
            else:
                assert sum(WEIGHT[objective](p, u) for u in t.unit_ids) == want, (name, objective, g)


def test_cheapest_tree_is_valid_and_an_upper_bound(small):
    p = small.problem
    for g in small.goal_ids("all"):
        units = cheapest_tree(p, [g])
        want = reference(p, g, "units")
        if want is None:
            assert units is None
            continue
        assert units is not None and validate(p, g, units).valid
        assert len(units) >= want


def test_a_time_out_still_reports_a_valid_tree():
    """usc finds no tree before its proof; on a hard goal cut short the answer is a
    cheapest-first tree marked feasible (or the optimum, should the machine be fast)."""
    syn = preset("hard-4k")
    p = syn.problem()
    g = p.foon.object_ids[syn.goals[8]]  # optimum about 50 units in a part of ~2,900
    tree = Session(p, AspOptions(time_limit=1, units=p.units_for([g]))).solve(g)
    assert tree.status in ("feasible", "optimal")
    assert validate(p, g, tree.units).valid
    if tree.status == "feasible" and tree.fallback is not None:
        assert tree.fallback == "cheapest-first" and tree.note is not None
        assert len(tree.units) < 200


def test_no_fallback_under_user_constraints():
    """A user program may rule out the cheapest-first tree: then no tree is made up (a tree
    clingo found is its own, so it satisfies the program)."""
    syn = preset("hard-4k")
    p = syn.problem()
    g = p.foon.object_ids[syn.goals[8]]
    user = ("user", "% a user program (it could forbid anything)\n")
    tree = Session(p, AspOptions(programs=[user], time_limit=1, units=p.units_for([g]))).solve(g)
    assert tree.status in ("unknown", "optimal", "feasible")
    assert tree.fallback is None


def test_restricted_session_same_status_and_size(shared_problem):
    """The 25 goals on the goals' units (as solve grounds them) and on every unit."""
    data, problem = shared_problem
    goals = goals_mod.resolve(data, problem, None, "all")
    small = Session(problem, AspOptions(units=problem.units_for(goals)))
    full = Session(problem, AspOptions(units=tuple(range(len(problem.units)))))
    sizes = {}
    for g in goals:
        a, b = small.solve(g), full.solve(g)
        assert a.status == b.status
        assert len(a.units) == len(b.units)
        if a.status == "optimal":
            assert validate(problem, g, a.units).valid
        sizes[problem.objects[g].label] = (a.status, len(a.units))
    assert sizes["greek salad"] == ("optimal", 25)
    assert sizes["whipped cream"][0] == "unreachable"
