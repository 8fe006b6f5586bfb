"""Canonical trees (foon2asp.asp.canonical): the same tree among equal optima in every grounding, command and worker, against brute force."""

from __future__ import annotations

import json
import random

import pytest

from foon2asp.asp.options import AspOptions
from foon2asp.asp.session import Session
from foon2asp.batch.results import read_results
from foon2asp.methods.bounds import Bounds
from foon2asp.methods.runner import GoalRunner, solve_goals
from helpers import brute_force, build, goal_id
from helpers import run_cli as run


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
        if upper is None or bounds.lower(g) < upper or not tree.proven_by == "clingo":
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
