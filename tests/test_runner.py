"""Every registered method through the goal runner (methods/runner.py), every tree judged
by the independent validator (tree/validate.py): on the demo data and on a synthetic preset."""

from __future__ import annotations

import json
import random

import pytest

from conftest import DEMO
from foon2asp import methods
from foon2asp.analysis.compare import judge
from foon2asp.asp.objectives import motion_cost_weights, ranked
from foon2asp.asp.options import AspOptions
from foon2asp.batch.pool import BatchSpec, Worker
from foon2asp.errors import InputError
from foon2asp.foon.loaders import Dataset
from foon2asp.foon.problem import Problem
from foon2asp.methods.registry import effective_options
from foon2asp.methods.runner import solve_goals
from foon2asp.tree.tasktree import TaskTree, measures
from foon2asp.tree.validate import validate
from foon2asp.tree.weights import total
from synth import preset

CASES = ("demo", "tiny", "small")


@pytest.fixture(scope="module", params=CASES)
def case(request) -> tuple[str, Problem, list[int]]:
    """The case's name, problem and goals: every object of the demo data, the preset's goals."""
    if request.param == "demo":
        problem = Problem.from_dataset(Dataset.load(DEMO))
        return request.param, problem, list(range(len(problem.objects)))
    syn = preset(request.param)
    problem = syn.problem()
    return request.param, problem, [problem.foon.object_ids[g] for g in syn.goals]


@pytest.fixture(scope="module")
def options(case) -> AspOptions:
    """The default options with a motion-cost table (in hundredths), which the objective
    ``cost`` needs and every other objective ignores: seeded random costs, but on the
    small preset every motion costs 1 (with random costs the proof of one of its goals
    takes from seconds to minutes)."""
    name, problem, _ = case
    rng = random.Random(11)
    motions = sorted({u.motion for u in problem.units})
    return AspOptions(motion_costs={m: 100 if name == "small" else rng.randint(0, 300) for m in motions})


def derivable(problem: Problem, goal: int) -> bool:
    """By the validator alone: fire every unit that can fire, then is the goal had?"""
    fired = validate(problem, goal, list(range(len(problem.units)))).order
    return validate(problem, goal, fired).valid


def kind(name: str) -> str:
    """``exact`` (an ASP optimum), ``greedy`` (an ASP first model) or ``search``."""
    if methods.get(name).kind != "asp":
        return "search"
    return "greedy" if effective_options(name, AspOptions()).heuristic else "exact"


def objective_of(name: str) -> str:
    """The first objective an exact ASP method optimises."""
    return ranked(effective_options(name, AspOptions()))[0]


def value(problem: Problem, objective: str, goals, units: list[int], options: AspOptions) -> int:
    """The tree's value under ``objective``: the depth, or the sum of unit weights the solver minimises."""
    if objective == "depth":
        return measures(problem, goals, units)["depth"]
    if objective == "cost":
        assert options.motion_costs is not None
        weights = motion_cost_weights(problem, options.motion_costs)
        return sum(weights[u] for u in units)
    return total(problem, objective, units)


@pytest.fixture(scope="module")
def trees(case, options) -> dict[str, list[TaskTree]]:
    """Each method's trees for the case's goals, through the one entry point."""
    _, problem, goals = case
    return {name: list(solve_goals(problem, goals, name, options)) for name in methods.names()}


def test_every_method_answers_every_goal_and_the_validator_agrees(case, trees):
    _, problem, goals = case
    for name, answers in trees.items():
        assert [t.goal for t in answers] == goals, name
        for tree in answers:
            made = derivable(problem, tree.goal)
            checked = validate(problem, tree.goal, tree.units) if tree.has_tree else None
            # compare's and batch's "valid" is exactly what the validator says
            assert judge(problem, tree).extra["valid"] == (checked is not None and checked.valid), (name, tree.goal)
            if kind(name) == "search":
                assert tree.status in ("found", "not-found"), (name, tree.goal)
                assert tree.has_tree or not tree.units
                continue
            # an ASP method has a tree exactly for the goals that can be made, and it is valid
            assert tree.has_tree == made, (name, tree.goal, tree.status)
            assert checked is None or checked.valid, (name, tree.goal, checked.reason)
            assert tree.status in (("optimal",) if kind(name) == "exact" else ("optimal", "found", "ranked")) or (
                tree.status == "unreachable" and not made
            ), (name, tree.goal, tree.status)
            if tree.has_tree:
                assert tree.cost == measures(problem, tree.goal, tree.units), (name, tree.goal)
            if tree.status == "optimal" and tree.bound is not None:
                # a proven answer's bound is its own cost, on whatever path it was found
                assert tree.gap == 0.0 and all(tree.bound[k] == tree.cost[k] for k in tree.bound if k in tree.cost)


def test_every_optimum_is_no_worse_than_any_valid_tree_of_another_method(case, trees, options):
    _, problem, goals = case
    for name, answers in trees.items():
        if kind(name) != "exact":
            continue
        objective = objective_of(name)
        for i, tree in enumerate(answers):
            if not tree.has_tree:
                continue
            best = value(problem, objective, tree.goal, tree.units, options)
            for other, theirs in trees.items():
                rival = theirs[i]
                if rival.has_tree and validate(problem, rival.goal, rival.units).valid:
                    assert best <= value(problem, objective, rival.goal, rival.units, options), (name, other, tree.goal)


def test_meals_through_the_runner(case, trees, options):
    """A meal of two goals: one valid tree for both from every ASP method, between the
    single optima (at least the larger, at most their sum; for depth: the larger)."""
    _, problem, goals = case
    meal = tuple(g for g in goals if g not in problem.kitchen and derivable(problem, g))[:2]
    assert len(meal) == 2
    for name in methods.names():
        if kind(name) == "search":
            with pytest.raises(InputError, match="meals"):
                next(solve_goals(problem, [meal], name, options))
            continue
        together, *singles = solve_goals(problem, [meal, *meal], name, options)
        assert together.has_tree and together.meal == meal, name
        assert all(validate(problem, g, together.units).valid for g in meal), name
        assert [t.goal for t in singles] == list(meal)
        if kind(name) != "exact":
            continue
        objective = objective_of(name)
        got = value(problem, objective, meal, together.units, options)
        alone = [value(problem, objective, t.goal, t.units, options) for t in singles]
        assert max(alone) <= got <= (max(alone) if objective == "depth" else sum(alone)), (name, got, alone)


@pytest.mark.parametrize("grounding", ["whole", "per-goal"])
def test_batch_workers_build_the_same_runner(case, trees, options, grounding):
    """A batch worker's lines (either grounding) have the trees' status and the validator's "valid"."""
    _, problem, goals = case
    index = {json.dumps(u.to_json(), sort_keys=True): i for i, u in enumerate(problem.units)}
    names = methods.names()
    worker = Worker(BatchSpec(problem, names, options, grounding))
    for name in names:
        for goal, tree in zip(goals, trees[name]):
            record = json.loads(worker.run(goal, name))
            units = [index[json.dumps(u, sort_keys=True)] for u in record["units"]]
            assert record["status"] == tree.status, (name, goal, grounding)
            assert record["valid"] == (tree.has_tree and validate(problem, goal, units).valid), (name, goal)
            if kind(name) == "exact":
                # the canonical tree, whichever grounding and whichever units were grounded
                assert sorted(units) == sorted(tree.units), (name, goal, grounding)
