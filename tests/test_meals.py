"""Meals: one tree for several goals, proven optimal, against brute force and the single optima."""

from __future__ import annotations

import itertools
import json
import math
import random

import pytest
from click.testing import CliRunner

from foon2asp.analysis import queries
from foon2asp.analysis.compare import compare_meal
from foon2asp.asp.options import AspOptions
from foon2asp.cli import main
from foon2asp.foon import goals as goals_mod
from foon2asp.methods.plan import session_of as Session
from foon2asp.methods.runner import GoalRunner
from foon2asp.tree.tasktree import measures
from foon2asp.tree.validate import validate
from helpers import build, goal_id

OBJECTIVES = {
    ("units",): lambda p, t: (len(t),),
    ("success",): lambda p, t: (round(sum(-math.log(p.rates[u]) for u in t), 6), len(t)),
    ("inputs",): lambda p, t: (sum(len(p.inputs[u]) for u in t), len(t)),
    ("depth",): None,  # filled below (needs the meal)
    ("success", "units"): lambda p, t: (round(sum(-math.log(p.rates[u]) for u in t), 6), len(t)),
}


def meal_brute(problem, meal):
    """Every set of units valid for every goal of ``meal`` (the independent validator)."""
    n = len(problem.units)
    assert n <= 14
    out = []
    for k in range(n + 1):
        for subset in itertools.combinations(range(n), k):
            if all(validate(problem, g, list(subset)).valid for g in meal):
                out.append(subset)
    return out


def key_for(objective, problem, meal):
    if objective == ("depth",):
        return lambda t: (measures(problem, meal, list(t))["depth"], len(t))
    f = OBJECTIVES[objective]
    return lambda t: f(problem, t)


def random_problem(seed):
    rng = random.Random(seed)
    names = ["k1", "k2", "a", "b", "c", "g", "h"]
    units = [
        (
            rng.choice(["pour", "mix", "cut"]),
            rng.sample(names, rng.randint(1, 3)),
            rng.sample(names[2:], rng.randint(1, 2)),
        )
        for _ in range(rng.randint(4, 10))
    ]
    return build(units, kitchen=["k1", "k2"], rates={"pour": 0.9, "mix": 0.4, "cut": 0.7})


@pytest.mark.parametrize("seed", range(30))
@pytest.mark.parametrize("objective", list(OBJECTIVES))
def test_meal_tree_is_the_brute_force_optimum(seed, objective):
    p = random_problem(seed)
    labels = [lab for lab in ("g", "h", "c") if any(o.label == lab for o in p.objects)]
    if len(labels) < 2:
        return
    meal = tuple(goal_id(p, lab) for lab in labels[:2])
    key = key_for(objective, p, meal)
    trees = meal_brute(p, meal)
    session = Session(p, AspOptions(objective=objective))
    tree = session.solve(meal)
    if not trees:
        assert tree.status == "unreachable"
        assert tree.reason is not None
        return
    assert tree.status == "optimal", tree
    assert tree.goals == meal and tree.goal == meal[0]
    assert all(validate(p, g, tree.units).valid for g in meal)
    assert key(tuple(tree.units))[0] == min(key(t) for t in trees)[0]
    # a meal is never larger than the single optima together
    singles = [session.solve(g) for g in meal]
    assert all(s.status == "optimal" for s in singles)
    assert len(tree.units) <= sum(len(s.units) for s in singles)
    # nor than the union of the single trees (itself a tree for the meal)
    assert len(tree.units) <= len(set().union(*(s.units for s in singles)))


def test_shared_steps_counted_once():
    # a sauce both dishes need; two ways to make it
    p = build(
        [
            ("mix", ["k1", "k2"], ["sauce"]),
            ("cut", ["k1"], ["x"]),
            ("pour", ["x"], ["y"]),
            ("pour", ["y"], ["sauce"]),
            ("mix", ["sauce", "k2"], ["d1"]),
            ("cut", ["sauce", "k1"], ["d2"]),
        ],
        kitchen=["k1", "k2"],
        rates={"mix": 0.2, "cut": 0.9, "pour": 0.9},
    )
    meal = (goal_id(p, "d1"), goal_id(p, "d2"))
    tree = Session(p).solve(meal)
    assert tree.status == "optimal" and sorted(tree.units) == [0, 4, 5]
    # success: the likelier 3-unit route to the sauce, still made once
    best = Session(p, AspOptions(objective=("success",))).solve(meal)
    assert sorted(best.units) == [1, 2, 3, 4, 5]


def test_meal_with_depth_bound_and_models(demo_problem):
    data, p = demo_problem
    meal = (goals_mod.resolve_label(data, p, "tomato salad"), goals_mod.resolve_label(data, p, "scrambled egg"))
    free = Session(p).solve(meal)
    assert free.status == "optimal"
    alone = [Session(p).solve(g) for g in meal]
    assert free.cost["units"] == sum(t.cost["units"] for t in alone) == 8  # nothing to share here
    deep = Session(p, AspOptions(objective=("depth",))).solve(meal)
    assert deep.cost["depth"] == max(Session(p, AspOptions(objective=("depth",))).solve(g).cost["depth"] for g in meal)
    assert deep.cost["depth"] == 4
    bounded = Session(p, AspOptions(max_depth=3)).solve(meal)
    assert bounded.status == "unreachable"  # the salad needs 4 rounds
    assert "depth <= 3" in bounded.reason and "tomato salad" in bounded.reason
    assert "scrambled egg" not in bounded.reason
    assert Session(p, AspOptions(max_depth=4)).solve(meal).cost["units"] == 8
    two = Session(p, AspOptions(models=2)).solve(meal)
    alts = [two] + two.alternatives
    assert len(alts) == 2 and alts[0].units != alts[1].units
    assert all(validate(p, g, t.units).valid for t in alts for g in meal)


def test_unreachable_goal_is_named(demo_problem):
    data, p = demo_problem
    meal = (goals_mod.resolve_label(data, p, "tomato salad"), goals_mod.resolve_label(data, p, "whipped cream"))
    tree = Session(p).solve(meal)
    assert tree.status == "unreachable"
    assert "whipped cream" in tree.reason and "tomato" not in tree.reason
    assert [o["label"] for o in tree.unreachable_goals] == ["whipped cream"]


def test_batch_runner_per_goal_grounding_takes_meals(demo_problem):
    data, p = demo_problem
    meal = (goals_mod.resolve_label(data, p, "tomato salad"), goals_mod.resolve_label(data, p, "scrambled egg"))
    whole = GoalRunner("asp", p, AspOptions())(meal)
    part = GoalRunner("asp", p, AspOptions(), grounding="per-goal")(meal)
    assert whole.status == part.status == "optimal"
    assert whole.cost["units"] == part.cost["units"] == 8
    with pytest.raises(Exception, match="ASP method"):
        GoalRunner("ids", p, AspOptions())(meal)


@pytest.mark.parametrize(
    "pair,together,apart", [(("shrimp mango salad", "vinaigrette"), 42, 51), (("carrot salad", "coleslaw"), 33, 37)]
)
def test_shared_foon_pairs(shared_problem, pair, together, apart):
    data, p = shared_problem
    meal = tuple(goals_mod.resolve_label(data, p, lab) for lab in pair)
    session = Session(p, AspOptions(units=p.units_for(meal)))
    tree = session.solve(meal)
    assert tree.status == "optimal" and tree.cost["units"] == together
    assert all(validate(p, g, tree.units).valid for g in meal)
    assert sum(session.solve(g).cost["units"] for g in meal) == apart
    row = compare_meal(p, list(meal))
    assert row.total()["units"] == apart and row.meal.cost["units"] == together and row.meal.valid


def test_cli_solve_together_json_and_text(shared_foon_dir):
    args = ["solve", "--data", shared_foon_dir, "--goal", "carrot salad", "--goal", "coleslaw", "--together"]
    out = CliRunner().invoke(main, [*map(str, args), "--format", "json"])
    assert out.exit_code == 0, out.output
    (result,) = json.loads(out.stdout)
    assert "goal" not in result and [g["label"] for g in result["goals"]] == ["carrot salad", "coleslaw"]
    assert result["status"] == "optimal" and result["cost"]["units"] == 33 and len(result["units"]) == 33
    text = CliRunner().invoke(main, list(map(str, args))).stdout
    assert text.startswith("Meal of 2 goals:\n  + carrot salad") and "\n  + coleslaw" in text
    foon = CliRunner().invoke(main, [*map(str, args), "--format", "foon"]).stdout
    assert foon.startswith("# meal for carrot salad") and " + coleslaw" in foon.splitlines()[0]


def test_cli_compare_and_missing_together(shared_foon_dir):
    args = ["--data", str(shared_foon_dir), "--goal", "shrimp mango salad", "--goal", "vinaigrette", "--together"]
    out = CliRunner().invoke(main, ["compare", *args, "--format", "json"])
    assert out.exit_code == 0, out.output
    row = json.loads(out.stdout)
    assert row["meal"]["cost"]["units"] == 42 and row["sum_of_singles"]["units"] == 51
    args = ["--data", str(shared_foon_dir), "--goal", "fried rice", "--goal", "whipped cream", "--together"]
    out = CliRunner().invoke(main, ["missing", *args, "--format", "json"])
    (res,) = json.loads(out.stdout)
    assert res["status"] == "optimal" and len(res["missing"]) == 3  # one for whipped cream, two for fried rice
    assert [g["label"] for g in res["goals"]] == ["fried rice", "whipped cream"]


def test_missing_together_matches_singles(demo_problem):
    data, p = demo_problem
    meal = (goals_mod.resolve_label(data, p, "whipped cream"), goals_mod.resolve_label(data, p, "tomato salad"))
    together = queries.missing(p, meal)
    alone = [queries.missing(p, g) for g in meal]
    assert together.status == "optimal"
    assert len(together.missing) <= sum(len(r.missing) for r in alone)
    extended = p.with_kitchen(p.kitchen.union(together.missing))
    assert all(validate(extended, g, together.units).valid for g in meal)


def test_cli_together_rejects_search_methods():
    out = CliRunner().invoke(
        main,
        [
            "solve",
            "--data",
            "demo",
            "--goal",
            "tomato salad",
            "--goal",
            "scrambled egg",
            "--together",
            "--method",
            "ids",
        ],
    )
    assert out.exit_code == 2 and "ASP method" in out.stderr
