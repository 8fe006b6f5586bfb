"""The walk back from what a tree lacks: an object no unit makes, or a cycle of makers."""

from __future__ import annotations

import random
import re
from pathlib import Path

import pytest

from foon2asp.foon.model import Foon, FoonObject, Unit, leaves, made
from foon2asp.foon.parser import read_foon
from foon2asp.foon.problem import Problem
from foon2asp.tree.validate import check_order, find_missing_or_cycle, judge_alone, validate

#: object -> the units that make it; unit -> the inputs it lacks
MAKERS = {"g": [0], "x": [1], "y": [2]}
LACKS = {0: ["x"], 1: ["y"], 2: ["g"], 3: ["z"]}


def test_finds_a_cycle_of_makers():
    assert find_missing_or_cycle([("g", None)], MAKERS, LACKS.__getitem__) == ("cycle", [("g", 0), ("x", 1), ("y", 2)])


def test_finds_an_object_no_unit_makes():
    makers = {**MAKERS, "y": [3]}
    assert find_missing_or_cycle([("g", None)], makers, LACKS.__getitem__) == ("missing", ("z", 3))
    assert find_missing_or_cycle([("w", 5)], makers, LACKS.__getitem__) == ("missing", ("w", 5))


def test_nothing_found_when_every_maker_has_its_inputs():
    assert find_missing_or_cycle([("g", None)], MAKERS, lambda u: []) is None


# Judging a tree file on its own (foon2asp.tree.validate.judge_alone): kitchen = its leaves,
# goal = the products of its last unit; the verdict equals validate/check_order on random unit
# lists (out of order, repeated, with cycles and missing objects), and explains what it finds.


LLM = Path(__file__).resolve().parent.parent / "data" / "llm"


def o(label, *states, contains=(), inside=None):
    return FoonObject.make(label, states or ("s",), contains, inside)


def products(units):
    """What the units put out that counts as made in a tree (not bare; as Problem.products)."""
    return {x for u in units for x in u.outputs if not x.is_bare()}


def problem_of(units, kitchen, utensils=frozenset()):
    foon = Foon()
    ids = [foon.add_unit(u) for u in units]
    return Problem(foon, list(kitchen), {}, utensils), ids


def random_list(rng: random.Random, with_kitchen: bool):
    pool = [o(f"x{i}") for i in range(7)] + [FoonObject.make("knife")]
    units = []
    for _ in range(rng.randint(1, 8)):
        ins = rng.sample(pool, rng.randint(1, 3))
        outs = [x for x in rng.sample(pool, rng.randint(1, 2)) if x not in ins]
        if rng.random() < 0.2:
            outs.append(FoonObject.make("knife"))  # a bare output is not made
        units.append(Unit(rng.choice(["mix", "cut", "pour"]), tuple(ins), tuple(dict.fromkeys(outs))))
    if rng.random() < 0.3:
        units.append(rng.choice(units))  # a repeated unit
    rng.shuffle(units)
    kitchen = None
    if with_kitchen:
        # the leaves with some left out (missing objects) and some made objects added
        kitchen = [x for x in leaves(units) if rng.random() < 0.85] + rng.sample(pool, rng.randint(0, 2))
    return units, kitchen


@pytest.mark.parametrize("with_kitchen", [False, True])
def test_verdict_equals_the_validator_on_random_lists(with_kitchen):
    rng = random.Random(5 if with_kitchen else 3)
    seen = {"valid": 0, "invalid": 0, "out of order": 0, "cycle": 0, "missing": 0}
    for _ in range(400):
        units, kitchen = random_list(rng, with_kitchen)
        verdict = judge_alone(units, kitchen=kitchen)
        problem, ids = problem_of(units, verdict.kitchen)
        if not verdict.goals:
            assert not verdict.valid and not verdict.in_order and verdict.problem.startswith("no goal: no unit makes")
            continue
        validations = [validate(problem, g, ids) for g in verdict.goals]
        orders = [check_order(problem, g, ids) for g in verdict.goals]
        assert verdict.valid == all(v.valid for v in validations)
        assert verdict.in_order == all(p is None for p in orders)
        assert {ids[k - 1] for k in verdict.stuck} == set(validations[0].stuck)
        assert (verdict.problem is None) == (verdict.valid and verdict.in_order)
        if verdict.blocked is not None:
            # check_order names the same step and the same object
            m = re.match(r"step (\d+) \(unit \d+\) needs (.+), which is not had yet", orders[0] or "")
            assert m and int(m[1]) == verdict.blocked.step and m[2] == str(verdict.blocked.waits_for)
            assert verdict.blocked.unit == units[verdict.blocked.step - 1]
            if verdict.blocked.made_by is not None:
                assert verdict.blocked.made_by > verdict.blocked.step
                assert verdict.blocked.waits_for in products([units[verdict.blocked.made_by - 1]])
            else:
                assert verdict.blocked.waits_for not in products(units[verdict.blocked.step :])
        had = problem.derivable
        if verdict.cycle:
            # a real cycle: each unit makes its object and needs the next one, none of them is ever had
            for i, (obj, step) in enumerate(verdict.cycle):
                nxt = verdict.cycle[(i + 1) % len(verdict.cycle)][0]
                assert obj in products([units[step - 1]]) and nxt in units[step - 1].inputs
                assert problem.foon.object_ids[obj] not in had
            assert verdict.problem.startswith("circular support: ")
        if verdict.missing is not None:
            assert verdict.missing not in verdict.kitchen and verdict.missing not in products(units)
            assert verdict.missing in units[verdict.needed_by - 1].inputs
            assert verdict.problem.startswith("missing input: ")
        if verdict.stuck:
            assert bool(verdict.cycle) != (verdict.missing is not None), "a stuck unit has exactly one explanation"
        if not with_kitchen:
            assert verdict.missing is None, "with the leaves as kitchen every input is had or made"
        seen["valid" if verdict.valid else "invalid"] += 1
        seen["out of order"] += verdict.valid and not verdict.in_order
        seen["cycle"] += bool(verdict.cycle)
        seen["missing"] += verdict.missing is not None
    assert seen["valid"] > 30 and seen["invalid"] > 30 and seen["out of order"] > 10 and seen["cycle"] > 10
    assert (seen["missing"] > 30) == with_kitchen


def test_a_given_goal_and_utensils():
    cup = FoonObject.make("cup", ingredients=["tea"])
    tea = FoonObject.make("tea", container="cup")
    units = [
        Unit("pour", (FoonObject.make("kettle", ["hot"]), FoonObject.make("cup", ["empty"])), (tea, cup)),
        Unit("drink", (tea, cup), (o("me", "happy"),)),
    ]
    verdict = judge_alone(units, goal=o("me", "happy"), utensils=frozenset({"cup"}))
    assert verdict.valid and verdict.in_order and verdict.goals == (o("me", "happy"),)
    # a goal no unit makes
    verdict = judge_alone(units, goal=o("cake"))
    assert not verdict.valid and not verdict.in_order and verdict.unmade == [o("cake")]
    assert verdict.problem == "goal cake, s is not made by these units"
    # the starter rule: the cup holding tea is not required when the tea in the cup is an input too
    only = [Unit("drink", (tea, cup), (o("me", "happy"),))]
    assert judge_alone(only, kitchen=[tea], utensils=frozenset({"cup"})).valid
    assert not judge_alone(only, kitchen=[tea]).valid


def test_cycle_and_order_messages():
    a, b, c, goal = o("a"), o("b"), o("c"), o("goal")
    units = [
        Unit("mix", (o("k"), b), (a,)),
        Unit("cut", (a,), (b,)),
        Unit("pour", (a, o("k")), (goal,)),
    ]
    v = judge_alone(units)
    assert not v.valid and v.stuck == [1, 2, 3] and v.goals == (goal,)
    assert v.cycle == [(b, 2), (a, 1)]
    assert v.problem == (
        "circular support: [b, s] is made by step 2 (cut), which needs [a, s]; "
        "[a, s] is made by step 1 (mix), which needs [b, s]"
    )
    assert v.blocked is not None and v.blocked.step == 1 and v.blocked.waits_for == b and v.blocked.made_by == 2
    late = [Unit("cut", (c,), (goal,)), Unit("mix", (o("k"),), (c,))]
    v = judge_alone(late)
    assert v.valid and not v.in_order and v.goals == (c,)  # the last unit's product is the goal
    v = judge_alone(late, goal=goal)
    assert v.valid and not v.in_order
    assert v.problem == "step 1 (cut) cannot fire in the order given: it waits for c, s, which only step 2 (mix) makes"


def test_leaves():
    knife = FoonObject.make("knife")
    units = [
        Unit("peel", (o("banana", "whole"), knife), (o("banana", "peeled"), knife, FoonObject.make("peel"))),
        Unit("slice", (o("banana", "peeled"), knife), (o("banana", "sliced"),)),
    ]
    # a bare output is not made: the knife stays a leaf; an object only ever put out is no leaf
    assert leaves(units) == [o("banana", "whole"), knife]
    foon = Foon()
    for u in units:
        foon.add_unit(u)
    assert leaves(foon) == leaves(units)
    # an object a unit needs and puts out again is kept, not made: it is a leaf
    stove = o("stove", "on")
    heat = Unit("heat", (o("pan", "empty"), stove), (o("pan", "hot"), stove))
    assert leaves([heat]) == [o("pan", "empty"), stove] and made([heat]) == {o("pan", "hot")}
    assert judge_alone([heat]).valid


def test_demo_candidates_on_their_own():
    verdicts = {}
    for path in sorted(LLM.glob("smoothie-*.json")):
        units = read_foon(path).units
        verdicts[path.name] = (units, judge_alone(units))
    smoothie = FoonObject.make("smoothie", ["blended"], container="glass")
    assert all(v.goals == (smoothie,) for _, v in verdicts.values())
    assert [n for n, (_, v) in verdicts.items() if v.valid and v.in_order] == [
        "smoothie-1.json",
        "smoothie-3.json",
        "smoothie-4.json",
    ]
    units, v = verdicts["smoothie-2.json"]
    assert v.valid and not v.in_order
    assert v.blocked.step == 3 and v.blocked.made_by == 4
    assert v.blocked.waits_for == FoonObject.make("blender", ingredients=["banana"])
    assert FoonObject.make("blueberry", ["fresh"]) in verdicts["smoothie-3.json"][1].kitchen


def test_leaves_of_demo_data(demo_problem):
    data, problem = demo_problem
    kitchen = leaves(problem.foon)
    makes = made(problem.units)
    inputs = {x for u in problem.units for x in u.inputs}
    assert set(kitchen) == inputs - makes
    with_leaves = Problem(problem.foon, kitchen, problem.motion_rates, problem.utensils)
    everything = list(range(len(problem.units)))
    for goal_obj, _ in data.goals:
        g = problem.foon.object_ids[goal_obj]
        # what the leaves let one make, as the independent validator replays every unit that fires
        order = validate(with_leaves, g, everything).order
        had = set(kitchen) | {x for u in order for x in with_leaves.units[u].outputs if not x.is_bare()}
        assert (g in with_leaves.derivable) == (goal_obj in had)
        # every goal the kitchen file lets one make can be made from the leaves too
        if g in problem.derivable:
            assert g in with_leaves.derivable, goal_obj
    # the kitchen file's "stove, on" is kept on by the unit that heats the pan: a leaf
    assert FoonObject.make("stove", ["on"]) in kitchen
    # the demo kitchen's items that are used and not made are all leaves
    assert {k for k in data.kitchen if k in inputs and k not in makes} <= set(kitchen)


def test_leaves_of_two_merged_foon_111_files(shared_111_dir):
    from foon2asp.foon.parser import read_foons

    paths = sorted(shared_111_dir.glob("*.txt"))[:2]
    foon = read_foons(paths)
    kitchen = leaves(foon)
    makes = made(foon.units)
    assert kitchen and set(kitchen).isdisjoint(makes)
    assert set(kitchen) == {x for u in foon.units for x in u.inputs} - makes
    problem = Problem(foon, kitchen)
    # each recipe's last unit makes its dish; from the merged leaves every such dish can be made
    from foon2asp.foon.parser import read_foon

    for path in paths:
        last = read_foon(path).units[-1]
        dishes = [problem.foon.object_ids[x] for x in last.outputs if not x.is_bare()]
        assert dishes and all(d in problem.derivable for d in dishes), path.name
        for d in dishes:
            order = validate(problem, d, list(range(len(foon.units)))).order
            assert order  # some units fire from the leaves alone
