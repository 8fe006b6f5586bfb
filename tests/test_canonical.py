"""Canonical trees (foon2asp.asp.canonical): the same tree among equal optima in every grounding, command and worker, against brute force.

The search for the canonical tree is bounded by clasp conflicts: on the ``small`` preset the
smallest optimal tree of some goals needs millions of conflicts, and the answer must still be
optimal (against the reference search of test_session.py), the same from every path, and say
that the budget ran out.
"""

from __future__ import annotations

import json
import random
from dataclasses import replace

import pytest

from foon2asp.asp import canonical
from foon2asp.asp.objectives import ranked
from foon2asp.asp.options import AspOptions
from foon2asp.batch.results_file import read_results
from foon2asp.bounds.lower import Bounds
from foon2asp.methods.plan import session_of as Session
from foon2asp.methods.runner import GoalRunner, solve_goals
from foon2asp.tree.validate import validate
from helpers import brute_force, build, goal_id
from helpers import run_cli as run
from synth import preset
from test_session import reference


def canonical_brute(problem, goal):
    trees = brute_force(problem, goal)
    top = min(len(t) for t in trees)
    n = len(problem.units)
    return min((t for t in trees if len(t) == top), key=lambda t: [0 if u in t else 1 for u in range(n)])


def random_foon(seed: int):
    rng = random.Random(seed)
    kitchen = ["k0", "k1", "k2", "k3"]
    objects = list(kitchen)
    units = []
    for i in range(rng.randint(4, 9)):
        ins = rng.sample(objects, rng.randint(1, min(2, len(objects))))
        out = f"o{rng.randint(0, 4)}"
        units.append((f"m{i}", ins, [out]))
        if out not in objects:
            objects.append(out)
    return build(units, kitchen)


@pytest.mark.parametrize("seed", range(12))
def test_canonical_tree_is_the_smallest_optimal_tree_in_every_grounding(seed):
    problem = random_foon(seed)
    goals = sorted({goal_id(problem, f"o{k}") for k in range(5) if f"o{k}" in {o.label for o in problem.objects}})
    for g in goals:
        if not brute_force(problem, g):
            continue
        want = canonical_brute(problem, g)
        trees = {
            "session": Session(problem, AspOptions()).solve(g),
            "driver": Session(problem, AspOptions(models=2)).solve(g),
        }
        for name, tree in trees.items():
            assert tuple(sorted(tree.units)) == want, (name, seed, g)
        # the goal runner's canonical tree: the bounds tree when it is optimal, else the smallest optimal one
        bounds_tree = Bounds(problem).tree(g)
        if bounds_tree is not None and len(bounds_tree) == len(want):
            want = bounds_tree
        for grounding in ("whole", "per-goal"):
            for shortcuts in (True, False):
                tree = GoalRunner("asp", problem, AspOptions(), grounding, shortcuts=shortcuts)(g)
                assert tuple(sorted(tree.units)) == want, (grounding, shortcuts, seed, g)


def test_same_trees_from_solve_batch_workers_and_groundings(shared_foon_dir, tmp_path):
    res = run("solve", "--data", shared_foon_dir, "--goals", "all", "--format", "json")
    assert res.exit_code == 0
    solved = {
        json.dumps(r["goal"], sort_keys=True): sorted(
            u["id"] if "id" in u else json.dumps(u, sort_keys=True) for u in r["units"]
        )
        for r in json.loads(res.output)
    }
    for extra in ([], ["--workers", "2"], ["--grounding", "per-goal"], ["--no-shortcuts"]):
        out = tmp_path / f"b{len(extra)}{'-'.join(extra)}.jsonl"
        res = run("batch", "--data", shared_foon_dir, "--goals", "all", "--output", out, "--no-progress", *extra)
        assert res.exit_code == 0, res.stderr
        batch = {
            json.dumps(r["goal"], sort_keys=True): sorted(
                u["id"] if "id" in u else json.dumps(u, sort_keys=True) for u in r["units"]
            )
            for r in read_results(out)
        }
        assert batch == solved, extra


def test_a_goal_the_bounds_decide_gets_the_same_tree_everywhere(shared_problem, shared_foon_dir, tmp_path):
    """A goal whose bounds tree is optimal but not the smallest optimal tree: solve, batch
    (both groundings, with and without shortcuts, two workers) and the library all give the
    bounds tree, the canonical one."""
    _, problem = shared_problem
    runner = GoalRunner("asp", problem, AspOptions(), "per-goal")
    bounds = Bounds(problem)
    goal = None
    for g in sorted(problem.derivable):
        tree = runner(g)
        upper = bounds.upper(g)
        if upper is None or bounds.lower(g) < upper or tree.proven_by not in ("clingo", "bounds"):
            continue
        smallest = Session(problem, AspOptions()).solve(g)
        if sorted(smallest.units) != sorted(tree.units):
            goal = g
            break
    assert goal is not None, "no goal where the bounds tree differs from the smallest optimal tree"
    want = list(bounds.tree(goal))
    assert len(want) == len(smallest.units)
    trees = [next(iter(solve_goals(problem, [goal], "asp", AspOptions())))]
    trees += [GoalRunner("asp", problem, AspOptions(), gr, sc)(goal) for gr in ("whole", "per-goal") for sc in (1, 0)]
    for tree in trees:
        assert tree.status == "optimal" and sorted(tree.units) == want
    label = problem.objects[goal].to_json()
    key = json.dumps(label, sort_keys=True)
    res = run("solve", "--data", shared_foon_dir, "--goal", f"#{goal}", "--format", "json")
    assert res.exit_code == 0, res.stderr
    solved = json.loads(res.output)
    solved = solved[0] if isinstance(solved, list) else solved
    for extra in ([], ["--workers", "2", "--no-shortcuts"], ["--grounding", "per-goal"]):
        out = tmp_path / f"b{len(extra)}.jsonl"
        res = run("batch", "--data", shared_foon_dir, "--goal", f"#{goal}", "--output", out, "--no-progress", *extra)
        assert res.exit_code == 0, res.stderr
        (record,) = [r for r in read_results(out) if json.dumps(r["goal"], sort_keys=True) == key]
        assert record["units"] == solved["units"], extra
        assert len(record["units"]) == len(want)


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
    assert opt is not None and fresh.asp_cost[0] == round(opt)
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
    assert first.asp_cost == fresh.asp_cost and validate(problem, goal, first.units).valid
    want = sorted(first.units)
    if best is not None and bounds.cost(best) == fresh.asp_cost:
        assert want == sorted(best)
    trees = [
        t for order in (1, -1) for t in solve_goals(problem, [*others, goal][::order], "asp", options) if t.goal == goal
    ]
    for grounding in ("whole", "per-goal"):
        for shortcuts in (True, False):
            trees.append(GoalRunner("asp", problem, options, grounding, shortcuts=shortcuts)(goal))
    for tree in trees:
        assert tree.status == "optimal" and tree.asp_cost == fresh.asp_cost
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
    assert tree.asp_cost == bounded.asp_cost
    n = len(problem.units)

    def key(units):
        return [0 if u in set(units) else 1 for u in range(n)]

    assert key(tree.units) <= key(bounded.units)


def canonical_session(problem, options: AspOptions, goal: int) -> Session:
    """A fresh session as the canonical one of ``goal`` is built (asp.canonical.canonical_problem)."""
    view, part = canonical.canonical_problem(problem, [goal])
    return Session(view, replace(options, units=part), goal=goal)
