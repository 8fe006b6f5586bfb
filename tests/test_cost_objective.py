"""The objective ``cost`` (encodings/cost.lp): the least summed motion cost, exact in
hundredths, alone and lexicographically with the others, against brute force over every
unit subset the independent validator accepts."""

from __future__ import annotations

from decimal import Decimal

import pytest

from foon2asp.asp.multishot.driver import alternatives
from foon2asp.asp.objectives import motion_cost_facts, motion_cost_weights
from foon2asp.asp.options import OBJECTIVES
from foon2asp.asp.session import AspOptions, Session
from foon2asp.errors import InputError
from foon2asp.foon.motioncost import DEFAULT_COST, parse_motion_costs, unit_weights
from foon2asp.tree.tasktree import measures
from foon2asp.tree.validate import validate
from helpers import against_brute_force, brute_force, build, goal_part
from test_objectives import random_foon

#: a table in the issue's style (0-1, two decimals, a zero) for the random FOONs' motions
#: m1..m4 (test_objectives.random_foon); "m3" is left out: it costs 1
TABLE_TEXT = '{"m1": 0.9, "m2": 0.15, "m4": 0}'


def exact_cost(problem, units, table) -> Decimal:
    """The summed cost of the units' motions, computed in decimals from the table alone."""
    return sum((table.costs.get(problem.units[u].motion, DEFAULT_COST) for u in units), Decimal(0))


def key_of(problem, goal, units, objective, table):
    m = measures(problem, goal, list(units))
    parts = {"units": m["units"], "inputs": m["inputs"], "cost": exact_cost(problem, units, table)}
    names = list(objective) + ([] if "units" in objective else ["units"])
    return tuple(parts[n] for n in names)


def goals_of(problem) -> list[int]:
    return [i for i, o in enumerate(problem.objects) if o.label.startswith("o")]


def options_for(problem, objective, table, **more) -> AspOptions:
    weights, _ = unit_weights(table, [u.motion for u in problem.units])
    return AspOptions(objective=objective, motion_costs=weights, **more)


@pytest.fixture(scope="module")
def table():
    return parse_motion_costs(TABLE_TEXT, "costs.json")


def test_cost_is_an_objective():
    assert OBJECTIVES["cost"] == "cost"


@pytest.mark.parametrize("seed", range(10))
def test_cost_equals_brute_force(seed, table):
    problem = random_foon(seed)
    valid = {g: brute_force(problem, g) for g in goals_of(problem)}
    for objective in [("cost",), ("cost", "units"), ("units", "cost"), ("cost", "inputs"), ("inputs", "cost")]:
        session = Session(problem, options_for(problem, objective, table))
        for g, trees in valid.items():
            tree = session.solve(g)
            if not trees:
                assert tree.status == "unreachable", (seed, objective, g)
                continue
            top = min(key_of(problem, g, t, objective, table) for t in trees)
            assert tree.status == "optimal"
            assert validate(problem, g, tree.units).valid
            assert key_of(problem, g, tree.units, objective, table) == top, (seed, objective, g)
            # the solver's cost at the cost objective's priority is the exact sum in hundredths
            at = objective.index("cost")
            assert Decimal(tree.extra["asp_cost"][at]) / 100 == top[at]


@pytest.mark.parametrize("seed", range(20, 24))
def test_cost_all_optimal_trees(seed, table):
    """Every optimal tree under cost (then units), as brute force finds them."""
    problem = random_foon(seed, 9)
    session = Session(problem, options_for(problem, ("cost",), table, all_optimal=True))
    for g, trees, found in against_brute_force(problem, goals_of(problem), lambda g: alternatives(session.solve(g))):
        top = min(key_of(problem, g, t, ("cost",), table) for t in trees)
        best = sorted(t for t in trees if key_of(problem, g, t, ("cost",), table) == top)
        assert sorted(tuple(sorted(t.units)) for t in found) == best


def test_zero_costs_keep_the_tree_irredundant(table):
    """A free motion must not let superfluous units in: units breaks the tie."""
    problem = build(
        [("m4", ["k0"], ["a"]), ("m4", ["a"], ["b"]), ("m1", ["k0"], ["b"]), ("m4", ["b"], ["goal"])], ["k0"]
    )
    g = problem.foon.object_ids[problem.objects[-1]]
    tree = Session(problem, options_for(problem, ("cost",), table)).solve(g)
    assert tree.extra["asp_cost"] == [0, 3]
    assert sorted(tree.units) == [0, 1, 3]


def test_units_first_then_cost(table):
    """units,cost takes the fewest units, and the cheaper of two trees of that size."""
    problem = build(
        [("m1", ["k0"], ["a"]), ("m1", ["a"], ["goal"]), ("m2", ["k1"], ["c"]), ("m2", ["c"], ["goal"])],
        ["k0", "k1"],
    )
    g = problem.foon.object_ids[problem.objects[2]]
    assert problem.objects[g].label == "goal"
    for objective, expected in ((("units", "cost"), [2, 3]), (("cost",), [2, 3]), (("units",), [0, 1])):
        tree = Session(problem, options_for(problem, objective, table)).solve(g)
        assert sorted(tree.units) == expected, objective


def test_demo_goals_against_brute_force(demo_problem):
    """The demo data with a table that leaves some motions out, on each goal's part."""
    data, problem = demo_problem
    motions = sorted({u.motion for u in problem.units})
    listed = motions[::2]
    text = "\n".join(f"{m}\t{(k * 0.37) % 1:.2f}" for k, m in enumerate(listed, 1)) + "\n"
    table = parse_motion_costs(text, "costs.txt")
    weights, warning = unit_weights(table, motions)
    assert warning is not None and all(m in warning for m in motions if m not in listed)
    checked = 0
    for goal_obj, _ in data.goals:
        g = problem.foon.object_ids[goal_obj]
        part = goal_part(problem, g)
        if part is None:
            continue
        sub, sg = part
        tree = Session(sub, AspOptions(objective=("cost",), motion_costs=weights)).solve(sg)
        top = min(key_of(sub, sg, t, ("cost",), table) for t in brute_force(sub, sg))
        assert key_of(sub, sg, tree.units, ("cost",), table) == top
        checked += 1
    assert checked >= 2


def test_facts_are_integers_per_unit(table):
    problem = random_foon(3)
    weights, _ = unit_weights(table, [u.motion for u in problem.units])
    text = motion_cost_facts(problem, AspOptions(objective=("cost",), motion_costs=weights), [0, 2])
    expected = {0: int(table.cost(problem.units[0].motion) * 100), 2: int(table.cost(problem.units[2].motion) * 100)}
    assert text == "".join(f"motion_cost({u},{w}).\n" for u, w in expected.items())
    # a motion the weights do not list weighs the default cost
    assert set(motion_cost_weights(problem, {}, [0, 1]).values()) == {100}


def test_cost_needs_a_table():
    problem = random_foon(1)
    with pytest.raises(InputError, match="motion-cost table"):
        Session(problem, AspOptions(objective=("cost",)))
    with pytest.raises(ValueError, match=">= 0"):
        Session(problem, AspOptions(objective=("cost",), motion_costs={"m1": -5}))
