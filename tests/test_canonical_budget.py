"""The search for the canonical tree is bounded by clasp conflicts and runs in the goal's
canonical session, so the tree depends only on the input also when the budget runs out.

On the ``small`` preset the search for the smallest optimal tree of some goals needs millions
of conflicts; there the answer must still be optimal (against the reference search of
test_session.py), the same from every path (a fresh session on the goal's part, a session that
solved other goals first, one grounding for all goals, the batch runner in both groundings,
with and without shortcuts), and say that the budget ran out.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from foon2asp.asp import canonical
from foon2asp.asp.objectives import ranked
from foon2asp.asp.options import AspOptions
from foon2asp.asp.session import Session
from foon2asp.methods.bounds import Bounds
from foon2asp.methods.runner import GoalRunner, solve_goals
from foon2asp.tree.validate import validate
from synth import preset
from test_session import reference


@pytest.fixture(scope="module")
def small():
    return preset("small").problem()


def _budget_goal(problem, objective: str) -> int:
    """A goal of ``problem`` whose canonical search runs out of budget (fresh session)."""
    options = AspOptions(objective=(objective,))
    for g in sorted(problem.derivable - problem.kitchen, reverse=True):
        tree = canonical_session(problem, options, g).solve(g)
        if tree.stats.get("canonical_search") == "budget":
            return g
    raise AssertionError("no goal of the small preset exhausts the canonical budget")


@pytest.mark.parametrize("objective", ["units"])
def test_the_tree_is_the_same_from_every_path_when_the_budget_runs_out(small, objective, monkeypatch):
    monkeypatch.setattr(canonical, "CONFLICTS", 40)  # small enough that some goal of each objective runs out
    problem = small
    goal = _budget_goal(problem, objective)
    options = AspOptions(objective=(objective,))
    fresh = canonical_session(problem, options, goal).solve(goal)
    assert fresh.status == "optimal" and fresh.stats["canonical_search"] == "budget"
    assert validate(problem, goal, fresh.units).valid
    want = sorted(fresh.units)
    # the optimum, against the reference search written without the solver
    opt = reference(problem, goal, objective)
    assert opt is not None and fresh.extra["asp_cost"][0] == round(opt)
    # a session for many goals that solved others first hands the goal to its canonical session
    others = sorted(problem.derivable - problem.kitchen)[:5]
    shared = Session(problem, replace_units(options, problem.units_for([*others, goal])))
    for g in others:
        shared.solve(g)
    again = shared.solve(goal)
    assert again.stats.get("canonical_session") is True
    assert sorted(again.units) == want
    # the goal runner's paths answer on the goal's prepared part: the bounds tree when it is
    # optimal, else the first optimum found there; the same tree on every path, of the same cost
    bounds = Bounds(problem, ranked(options))
    best = bounds.tree(goal)
    first = GoalRunner("asp", problem, options)(goal)
    assert first.extra["asp_cost"] == fresh.extra["asp_cost"] and validate(problem, goal, first.units).valid
    want = sorted(first.units)
    if best is not None and bounds.cost(best) == fresh.extra["asp_cost"]:
        assert want == sorted(best)
    trees = [
        t for order in (1, -1) for t in solve_goals(problem, [*others, goal][::order], "asp", options) if t.goal == goal
    ]
    for grounding in ("whole", "per-goal"):
        for shortcuts in (True, False):
            trees.append(GoalRunner("asp", problem, options, grounding, shortcuts=shortcuts)(goal))
    for tree in trees:
        assert tree.status == "optimal" and tree.extra["asp_cost"] == fresh.extra["asp_cost"]
        assert sorted(tree.units) == want


def replace_units(options: AspOptions, units) -> AspOptions:
    from dataclasses import replace

    return replace(options, units=tuple(units))


def test_a_larger_budget_ends_at_a_smaller_or_equal_tree(small, monkeypatch):
    """The budget only cuts the search short: with more conflicts the tree is never larger in
    the order of unit ids, and the cost stays the same."""
    problem = small
    goal = _budget_goal(problem, "units")
    options = AspOptions()
    bounded = canonical_session(problem, options, goal).solve(goal)
    monkeypatch.setattr(canonical, "CONFLICTS", 4 * canonical.CONFLICTS)
    tree = canonical_session(problem, options, goal).solve(goal)
    assert tree.extra["asp_cost"] == bounded.extra["asp_cost"]
    n = len(problem.units)

    def key(units):
        return [0 if u in set(units) else 1 for u in range(n)]

    assert key(tree.units) <= key(bounded.units)


def canonical_session(problem, options: AspOptions, goal: int) -> Session:
    """A fresh session as the canonical one of ``goal`` is built (asp.canonical.canonical_problem)."""
    view, part = canonical.canonical_problem(problem, [goal])
    return Session(view, replace(options, units=part), goal=goal)
