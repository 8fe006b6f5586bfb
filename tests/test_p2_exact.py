"""The branch and bound of foon2asp.methods.exact: the optimum and the canonical tree without the solver.

Checked against brute force (every subset judged by the independent validator) on small random
FOONs with real choice, cycles and units with several products, against the solver without
shortcuts on a synthetic FOON, and the fallback to the solver when the search runs out of nodes.
"""

from __future__ import annotations

import functools
import importlib
import itertools
import random

import pytest

from foon2asp.asp.options import AspOptions
from foon2asp.foon.synth import preset
from foon2asp.methods import exact
from foon2asp.methods.bounds import Bounds
from foon2asp.methods.runner import GoalRunner, Parts
from helpers import brute_force, build

RANKED = [("units",), ("success", "units"), ("inputs", "units")]


@functools.cache
def random_foon(seed: int):
    """Up to 12 units over 7 made objects: several producers each, units with two products,
    inputs made elsewhere (so cycles), and some units that never fire."""
    rng = random.Random(seed)
    kitchen = ["k0", "k1", "k2"]
    made = [f"o{i}" for i in range(7)]
    units = []
    for i in range(rng.randint(8, 12)):
        outs = rng.sample(made, 2 if rng.random() < 0.3 else 1)
        pool = kitchen + [m for m in made if m not in outs] + ["never"] * (rng.random() < 0.1)
        ins = rng.sample(pool, rng.randint(1, 3))
        units.append((f"m{i % 5}", ins, outs))
    rates = {f"m{i}": r for i, r in enumerate((0.9, 0.5, 0.7, 0.3, 0.95))}
    return build(units, kitchen, rates)


@functools.cache
def all_trees(seed: int, goal: int) -> list[tuple[int, ...]]:
    return brute_force(random_foon(seed), goal)


def lex_smallest(trees, n):
    """The tree holding the smallest unit in which two trees differ is the smaller."""
    return min(trees, key=lambda t: [0 if u in t else 1 for u in range(n)])


def canonical(bounds: Bounds, trees) -> tuple[int, ...]:
    weight = {t: bounds.weight(t) for t in trees}
    opt = min(weight.values())
    return tuple(lex_smallest([t for t in trees if weight[t] == opt], len(bounds.problem.units)))


@pytest.mark.parametrize("seed", range(60))
def test_canonical_tree_equals_brute_force(seed):
    problem = random_foon(seed)
    parts = Parts(problem)
    for ranked in RANKED:
        bounds = Bounds(problem, ranked)
        for goal in range(len(problem.objects)):
            if goal in problem.kitchen or goal not in problem.derivable:
                continue
            trees = all_trees(seed, goal)
            assert trees
            opt = min(bounds.weight(t) for t in trees)
            tree = bounds.tree(goal)
            want = tree if bounds.weight(tree) == opt else canonical(bounds, trees)
            units, _, _ = parts.relevant(goal)
            for pool in (units, range(len(problem.units))):
                assert exact.canonical_tree(bounds, goal, pool) == want, (seed, ranked, goal)
            # on the part pruned by the bounds too (every optimal tree survives it)
            assert exact.canonical_tree(bounds, goal, bounds.keep(goal, units)) == want, (seed, ranked, goal)


def test_random_foons_need_the_search():
    """The FOONs above have goals the bounds do not decide, with and without an optimal bounds tree."""
    kinds = set()
    for seed in range(60):
        problem = random_foon(seed)
        for ranked in RANKED:
            bounds = Bounds(problem, ranked)
            for goal in sorted(problem.derivable - problem.kitchen):
                if not bounds.proven(goal):
                    opt = min(bounds.weight(t) for t in all_trees(seed, goal))
                    kinds.add(bounds.upper(goal) == opt)
    assert kinds == {True, False}


@pytest.mark.parametrize("seed", range(40))
def test_search_finds_the_optimum_and_every_optimal_tree(seed):
    """``Search.run`` lowers the target to the brute-force optimum, finds nothing below the optimum,
    and with ``every`` and the target one above the optimum returns the smallest optimal tree."""
    problem = random_foon(seed)
    for ranked in RANKED:
        bounds = Bounds(problem, ranked)
        for goal in sorted(problem.derivable - problem.kitchen):
            trees = all_trees(seed, goal)
            weights = sorted({bounds.weight(t) for t in trees})
            opt = weights[0]
            part = exact.Part(bounds, goal, range(len(problem.units)))
            start = part.mask(bounds.landmarks(goal))
            lighter, target = exact.Search(part).run(start, weights[-1] + 1)
            assert lighter is not None and target == opt == part.weight(lighter)
            assert exact.Search(part).run(start, opt)[0] is None
            best = [t for t in trees if bounds.weight(t) == opt]
            smallest, _ = exact.Search(part).run(start, opt + 1, every=True)
            assert smallest is not None
            assert part.ids(smallest) == tuple(lex_smallest(best, len(problem.units))), (seed, goal)


def test_runner_answers_by_branch_and_bound_and_falls_back_to_maxsat_and_the_solver():
    """Goals the bounds do not decide are answered by the search (``"shortcut": "branch-and-bound"``);
    with no nodes to search, MaxSAT on the pruned part (``"shortcut": "maxsat"``), and with MaxSAT
    off too, the solver on the pruned part: all three give the same trees."""
    searched = proven = solved = 0
    for seed, grounding in itertools.product(range(30), ("per-goal", "whole")):
        problem = random_foon(seed)
        for ranked in RANKED:
            options = AspOptions(objective=(ranked[0],))
            fast = GoalRunner("asp", problem, options, grounding)
            sat = GoalRunner("asp", problem, options, grounding)
            sat.search_nodes = 0
            slow = GoalRunner("asp", problem, options, grounding)
            slow.search_nodes = 0
            slow.maxsat = False
            for goal in sorted(problem.derivable - problem.kitchen):
                a, m, b = fast(goal), sat(goal), slow(goal)
                assert a.status == m.status == b.status == "optimal"
                assert sorted(a.units) == sorted(m.units) == sorted(b.units), (seed, ranked, goal)
                assert a.extra["asp_cost"] == m.extra["asp_cost"] == b.extra["asp_cost"]
                assert a.cost == m.cost == b.cost
                assert a.bound == m.bound == b.bound and a.gap == m.gap == b.gap == 0.0
            assert fast.counts["solver"] == fast.counts["maxsat"] == sat.counts["solver"] == 0
            searched += fast.counts["branch-and-bound"]
            proven += sat.counts["maxsat"]
            solved += slow.counts["solver"]
            assert slow.counts["branch-and-bound"] == sat.counts["branch-and-bound"] == slow.counts["maxsat"] == 0
    assert searched > 0 and searched == proven == solved


def test_synthetic_foon_equals_the_solver():
    """On the ``small`` synthetic preset (parts of a few hundred units, cycles): every tree the
    search settles is the solver's (on the pruned part: the runner without search nodes and
    without MaxSAT) and MaxSAT's (without search nodes)."""
    problem = preset("small").problem()
    parts = Parts(problem)
    bounds = parts.bounds(("units",))
    solver = GoalRunner("asp", problem, AspOptions(), "per-goal")
    solver.search_nodes = 0
    solver.maxsat = False
    sat = GoalRunner("asp", problem, AspOptions(), "per-goal")
    sat.search_nodes = 0
    settled = complete = 0
    for goal in sorted(problem.derivable - problem.kitchen)[::3]:
        units, _, choice = parts.relevant(goal)
        if not choice or bounds.proven(goal):
            continue
        tree = exact.canonical_tree(bounds, goal, units, 5000)
        if tree is None:
            continue  # left to the solver (slow on these parts)
        settled += 1
        answer = solver(goal)
        assert answer.status == "optimal" and answer.stats.get("shortcut") is None, goal
        assert answer.extra["asp_cost"] == bounds.cost(tree), goal
        if answer.stats.get("canonical_search") is None:
            # the solver's search for the smallest optimal tree ended within its budget
            assert tuple(sorted(answer.units)) == tree, goal
            complete += 1
        proven = sat(goal)
        assert proven.status == "optimal" and proven.stats["shortcut"] == "maxsat", goal
        assert proven.extra["asp_cost"] == bounds.cost(tree), goal
        if proven.stats.get("canonical_search") is None:
            assert tuple(sorted(proven.units)) == tree, goal
        # without search nodes the runner's canonical step still settles it by the branch and bound
        again = GoalRunner("asp", problem, AspOptions(), "per-goal", shortcuts=False)(goal)
        assert tuple(sorted(again.units)) == tree, goal
    assert settled >= 20 and complete >= 5


def test_large_parts_get_fewer_nodes(monkeypatch):
    """The node budget shrinks with the part (WORK_LIMIT): with no work allowed, nothing is settled."""
    checked = 0
    for seed in range(20):
        problem = random_foon(seed)
        bounds = Bounds(problem)
        parts = Parts(problem)
        for goal in sorted(problem.derivable - problem.kitchen):
            units, _, choice = parts.relevant(goal)
            if not choice or bounds.proven(goal):
                continue
            assert exact.canonical_tree(bounds, goal, units) is not None
            with monkeypatch.context() as patch:
                patch.setattr(exact, "WORK_LIMIT", 0)
                assert exact.canonical_tree(bounds, goal, units) is None
            checked += 1
    assert checked


@pytest.mark.parametrize("ranked", [("units",), ("success", "units"), ("inputs", "units")])
def test_bounds_on_a_goals_part_equal_the_whole_foons(ranked, monkeypatch):
    """A goal's bounds depend on its relevant part only: built on the part (as the runner
    does on large FOONs, Parts.bounds_for) they equal the whole FOON's, and so do the trees."""
    problem = preset("small").problem()
    parts = Parts(problem)
    whole = parts.bounds(ranked)
    goals = sorted(problem.derivable - problem.kitchen)[::5]
    for goal in goals:
        units, _, _ = parts.relevant(goal)
        part = Bounds(problem, ranked, units)
        assert part.lower(goal) == whole.lower(goal), goal
        assert part.first_lower(goal) == whole.first_lower(goal), goal
        assert part.tree(goal) == whole.tree(goal), goal
        assert part.proven(goal) == whole.proven(goal), goal
        assert part.landmarks(goal) == whole.landmarks(goal), goal
        assert part.keep(goal, units) == whole.keep(goal, units), goal
    runner_module = importlib.import_module("foon2asp.methods.runner")  # the package re-exports a function of that name
    options = AspOptions(objective=ranked)
    plain = GoalRunner("asp", problem, options, "per-goal")
    expected = [(t.status, t.units, t.bound) for t in map(plain, goals[:40])]
    monkeypatch.setattr(runner_module, "PART_BOUNDS_MIN", 0)
    monkeypatch.setattr(runner_module, "PART_BOUNDS_SHARE", 0)
    by_part = GoalRunner("asp", problem, options, "per-goal")
    assert [(t.status, t.units, t.bound) for t in map(by_part, goals[:40])] == expected
    assert by_part.parts._part_bounds_spent.get(ranked, 0) > 0
