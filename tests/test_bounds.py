"""The bounds of foon2asp.bounds.lower never cut off the optimum, and batch answers stay exact.

Checked against brute force (every subset judged by the independent validator) on small random
FOONs with real choice and cycles, and against the solver without shortcuts on ../shared/foon.
"""

from __future__ import annotations

import random

import pytest

from foon2asp.asp.facts import neglog_weight
from foon2asp.asp.options import AspOptions
from foon2asp.bounds.lower import Bounds
from foon2asp.methods.runner import GoalRunner, Parts, solve_goals
from foon2asp.tree.validate import validate
from helpers import brute_force, build

RANKED = [("units",), ("success", "units"), ("inputs", "units")]


def choice_foon(seed: int):
    """A random FOON with several producers per object, shared inputs and back edges."""
    rng = random.Random(seed)
    kitchen = ["k0", "k1", "k2"]
    made = [f"o{i}" for i in range(6)]
    units = []
    for i in range(rng.randint(7, 12)):
        out = rng.choice(made)
        pool = kitchen + [m for m in made if m != out]
        ins = rng.sample(pool, rng.randint(1, 3))
        units.append((f"m{i % 4}", ins, [out]))
    rates = {f"m{i}": r for i, r in enumerate((0.9, 0.5, 0.7, 0.3))}
    return build(units, kitchen, rates)


def proven(bounds, goal) -> bool:
    """Is the bounds tree of ``goal`` optimal (lower bound == upper bound)?"""
    upper = bounds.upper(goal)
    return upper is not None and bounds.lower(goal) >= upper


def key_of(problem, ranked):
    def key(units):
        if ranked[0] == "success":
            return (sum(neglog_weight(problem.rates[u]) for u in units), len(units))
        if ranked[0] == "inputs":
            return (sum(len(problem.inputs[u]) for u in units), len(units))
        return (len(units),)

    return key


def lex_smallest(trees, n):
    return min(trees, key=lambda t: [0 if u in t else 1 for u in range(n)])


@pytest.mark.parametrize("seed", range(30))
def test_bounds_bracket_the_brute_force_optimum(seed):
    problem = choice_foon(seed)
    for ranked in RANKED:
        bounds = Bounds(problem, ranked)
        key = key_of(problem, ranked)
        for goal in range(len(problem.objects)):
            if goal in problem.kitchen:
                continue
            trees = brute_force(problem, goal)
            tree = bounds.tree(goal)
            if not trees:
                assert tree is None and not proven(bounds, goal)
                continue
            assert tree is not None and validate(problem, goal, list(tree)).valid
            weight = {t: bounds.weight(t) for t in trees}
            opt = min(weight.values())
            assert bounds.lower(goal) <= opt <= bounds.upper(goal), (seed, ranked, goal)
            # the combined weight orders trees as the ranked objectives do
            best = [t for t in trees if weight[t] == opt]
            assert {key(t) for t in best} == {min(key(t) for t in trees)}
            if proven(bounds, goal):
                assert bounds.weight(tree) == opt
            # every tree holds the landmarks; every optimal tree survives the pruning
            landmarks = bounds.landmarks(goal)
            assert all(landmarks <= set(t) for t in trees)
            part = sorted({u for t in trees for u in t})
            keep = set(bounds.keep(goal, part))
            assert all(set(t) <= keep for t in best), (seed, ranked, goal)


@pytest.mark.parametrize("seed", range(30))
def test_runner_answers_equal_the_canonical_tree(seed):
    """Every path (shortcuts, pruned solve, no shortcuts, solve_goals, either grounding) gives
    the canonical tree: the bounds tree when it is optimal, else the smallest optimal tree."""
    problem = choice_foon(seed)
    n = len(problem.units)
    for ranked in RANKED:
        options = AspOptions(objective=(ranked[0],))
        bounds = Bounds(problem, ranked)
        runners = [
            GoalRunner("asp", problem, options, grounding, shortcuts)
            for grounding in ("whole", "per-goal")
            for shortcuts in (True, False)
        ]
        for goal in range(len(problem.objects)):
            if goal in problem.kitchen:
                continue
            trees = brute_force(problem, goal)
            answers = [r(goal) for r in runners] + list(solve_goals(problem, [goal], "asp", options))
            if not trees:
                assert {a.status for a in answers} == {"unreachable"}
                continue
            weight = {t: bounds.weight(t) for t in trees}
            opt = min(weight.values())
            tree = bounds.tree(goal)
            want = tree if bounds.weight(tree) == opt else lex_smallest([t for t in trees if weight[t] == opt], n)
            for answer in answers:
                assert answer.status == "optimal"
                assert tuple(sorted(answer.units)) == want, (seed, ranked, goal, answer.stats)


def test_bounds_tree_depends_only_on_the_goals_part(shared_problem):
    _, shared_problem = shared_problem
    parts = Parts(shared_problem)
    whole = Bounds(shared_problem)
    goals = sorted(g for g in shared_problem.derivable if g not in shared_problem.kitchen)[::40]
    for goal in goals:
        units, _, _ = parts.relevant(goal)
        alone = Bounds(shared_problem, ("units",), units)
        assert alone.tree(goal) == whole.tree(goal)
        assert alone.lower(goal) == whole.lower(goal)
        assert proven(alone, goal) == proven(whole, goal)


@pytest.mark.parametrize("objective", ["units", "success"])
def test_shared_foon_sample_equals_the_solver_without_shortcuts(shared_problem, objective):
    _, problem = shared_problem
    goals = list(range(len(problem.objects)))[::7]
    options = AspOptions(objective=(objective,))
    fast = GoalRunner("asp", problem, options, "per-goal")
    slow = GoalRunner("asp", problem, options, "whole", shortcuts=False)
    for goal in goals:
        a, b = fast(goal), slow(goal)
        assert a.status == b.status, goal
        assert a.asp_cost == b.asp_cost, goal
        assert sorted(a.units) == sorted(b.units), goal  # the canonical tree, either way
        if a.status == "optimal":
            assert validate(problem, goal, a.units).valid
    assert fast.counts["only-tree"] > 0 and fast.counts["prepared"] < slow.counts["prepared"]
    assert slow.counts["only-tree"] == 0
