"""The tree encoding on small hand-made FOONs, checked against brute force and the validator."""

from __future__ import annotations

import random

import pytest

from foon2asp.methods.plan import session_of as Session
from foon2asp.tree.validate import check_order, validate
from helpers import best, brute_force, build, goal_id, obj


def solve(problem, goal):
    tree = Session(problem).solve(goal)
    if tree.units:
        assert validate(problem, goal, tree.units).valid
        assert check_order(problem, goal, tree.units) is None  # decoded in executable order
    return tree


def test_cycle_is_rejected_even_when_cheaper():
    # G <- U0(X); X <- U1(G): a 2-unit "tree" that rests on itself.
    # The honest way: K -> A -> B -> G takes 3 units.
    p = build(
        [("f", ["x"], ["g"]), ("f", ["g"], ["x"]), ("f", ["k"], ["a"]), ("f", ["a"], ["b"]), ("f", ["b"], ["g"])],
        ["k"],
    )
    g = goal_id(p, "g")
    tree = solve(p, g)
    assert tree.status == "optimal"
    assert sorted(tree.units) == [2, 3, 4]
    assert not validate(p, g, [0, 1]).valid
    size, trees = best(p, g, lambda m: m["units"])
    assert size == 3 and trees == [(2, 3, 4)]


def test_cheaper_producer_chosen():
    p = build(
        [("long", ["a"], ["g"]), ("f", ["k"], ["a0"]), ("f", ["a0"], ["a"]), ("short", ["b"], ["g"])],
        ["k", "b"],
    )
    tree = solve(p, goal_id(p, "g"))
    assert tree.status == "optimal" and tree.units == [3]
    assert tree.cost["units"] == 1


@pytest.mark.parametrize(
    "units, kitchen",
    [
        ([("f", ["z"], ["g"])], ["k"]),  # z is nowhere
        ([("f", ["x"], ["g"]), ("f", ["g"], ["x"])], ["k"]),  # only a cycle
        ([("f", ["x", "k"], ["g"]), ("f", ["g", "k"], ["x"]), ("f", ["k"], ["y"])], ["k"]),
    ],
)
def test_unreachable(units, kitchen):
    p = build(units, kitchen)
    g = goal_id(p, "g")
    assert brute_force(p, g) == []
    tree = solve(p, g)
    assert tree.status == "unreachable" and tree.units == []


def test_goal_in_kitchen_needs_no_units():
    p = build([("f", ["k"], ["g"])], ["k", "g"])
    tree = solve(p, goal_id(p, "g"))
    assert tree.status == "optimal" and tree.units == []


def test_shared_intermediate_counted_once():
    # g needs a and b; both need c; c costs two units
    p = build(
        [
            ("f", ["k"], ["c0"]),
            ("f", ["c0"], ["c"]),
            ("f", ["c"], ["a"]),
            ("f", ["c"], ["b"]),
            ("f", ["a", "b"], ["g"]),
        ],
        ["k"],
    )
    tree = solve(p, goal_id(p, "g"))
    assert tree.cost["units"] == 5


def test_bare_output_is_not_a_product():
    knife = obj("knife")
    p = build([("wash", [obj("sponge", "wet")], [knife]), ("cut", [knife, "k"], ["g"])], [obj("sponge", "wet"), "k"])
    assert solve(p, goal_id(p, "g")).status == "unreachable"


def test_utensil_rule():
    bowl = obj("bowl", contains=["tomato"])
    tomato = obj("tomato", inside="bowl")
    units = [("mix", [bowl, tomato], [obj("salad", "mixed")]), ("put", ["k"], [tomato])]
    starter = build(units, ["k"], utensils=["bowl"])
    g = goal_id(starter, obj("salad", "mixed"))
    assert solve(starter, g).units == [1, 0]
    off = build(units, ["k"], utensils=["bowl"], utensil_rule="off")
    assert solve(off, g).status == "unreachable"


def random_problem(rng: random.Random, n_objects=8, n_units=10):
    names = [f"o{i}" for i in range(n_objects)]
    units = []
    for _ in range(n_units):
        ins = rng.sample(names, rng.randint(1, 3))
        outs = rng.sample(names, rng.randint(1, 2))
        units.append((rng.choice(["a", "b", "c"]), ins, outs))
    kitchen = rng.sample(names, 3)
    return build(units, kitchen, rates={"a": 0.9, "b": 0.5, "c": 0.2})


def test_random_foons_against_brute_force():
    rng = random.Random(20261123)
    checked = reachable = 0
    for _ in range(60):
        p = random_problem(rng)
        session = Session(p)  # one grounding, many goals
        for g in range(len(p.objects)):
            if g in p.kitchen:
                continue
            size, _ = best(p, g, lambda m: m["units"])
            tree = session.solve(g)
            fresh = Session(p).solve(g)
            assert fresh.status == tree.status
            if size == float("inf"):
                assert tree.status == "unreachable"
            else:
                reachable += 1
                assert tree.status == "optimal"
                assert len(tree.units) == size == len(fresh.units)
                assert validate(p, g, tree.units).valid
                assert check_order(p, g, tree.units) is None
            checked += 1
    assert checked > 200 and reachable > 50
