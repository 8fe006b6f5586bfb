"""The problem in integer form: the units a tree for some goals can use."""

from __future__ import annotations

import math
import random
from dataclasses import replace

import clingo
import pytest

from foon2asp.asp import encoding_files
from foon2asp.asp.facts import facts
from foon2asp.asp.multishot.depth import Levels
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.problem import Problem, least_fixpoint
from foon2asp.tree.weights import UNIT_WEIGHTS, lexicographic, neglog_weight, total
from synth import preset


def _units_for_by_definition(problem, goals):
    """The encoding's candidate units for the goals, as clingo grounds them on the whole FOON."""
    ctl = clingo.Control()
    ctl.load(encoding_files.part("tree"))
    ctl.add("base", [], facts(problem) + "".join(f"goal({g}).\n" for g in goals))
    ctl.ground([("base", [])])
    return tuple(sorted(a.symbol.arguments[0].number for a in ctl.symbolic_atoms.by_signature("candidate", 1)))


def test_units_for_matches_its_definition(shared_problem):
    data, problem = shared_problem
    goals = goals_mod.resolve(data, problem, None, "all")
    expected = _units_for_by_definition(problem, goals)
    assert problem.units_for(goals) == expected
    assert 0 < len(expected) < len(problem.units)
    # one goal at a time as well
    for g in goals[:5]:
        assert problem.units_for([g]) == _units_for_by_definition(problem, [g])
    # a subset of the units relevant to the goals that fire in the kitchen's fixpoint
    _, unit_level = problem.derivation_levels()
    relevant = {u for g in goals for u in problem.relevant_units(g)}
    assert set(expected) <= {u for u in relevant if u in unit_level}


def test_units_for_on_a_fresh_view_equals_the_whole_foons_viability():
    """A view with no viability computed finds the part on the goals' relevant units alone: the
    same units as the FOON's viable producers give and as clingo grounds, for cut-down kitchens."""
    problem = preset("small").problem()
    rng = random.Random(7)
    kitchen = sorted(problem.kitchen)
    goals = sorted(problem.derivable - problem.kitchen)
    checked = 0
    for _ in range(40):
        view = problem.with_kitchen(rng.sample(kitchen, k=len(kitchen) * 19 // 20))
        goal = rng.choice(goals)
        fast = view.units_for([goal])
        assert "viable_units" not in vars(view)
        assert fast == _units_for_by_definition(view, [goal])
        _ = view.viable_units  # now by the whole FOON's fixpoint
        assert view.units_for([goal]) == fast
        checked += bool(fast)
    assert checked >= 10


def test_unit_id_finds_the_equal_unit(shared_problem):
    _, problem = shared_problem
    for uid in (0, len(problem.units) // 2, len(problem.units) - 1):
        unit = problem.units[uid]
        # an equal unit with its objects in another order is the same unit
        turned = replace(unit, inputs=unit.inputs[::-1], outputs=unit.outputs[::-1])
        assert problem.foon.unit_id(turned) == uid
    unit = problem.units[0]
    assert problem.foon.unit_id(replace(unit, motion=unit.motion + " twice")) is None


# The least fixpoint (foon/problem.py), Problem.with_kitchen and the unit weights (tree/weights.py),
# each against a naive computation.


@pytest.fixture(scope="module")
def tiny() -> Problem:
    return preset("tiny").problem()


def naive_levels(problem: Problem, kitchen: frozenset[int], units: list[int]) -> tuple[dict, dict]:
    """Round by round: every unit whose required inputs are all had fires; level = round."""
    have = dict.fromkeys(kitchen, 0)
    fired: dict[int, int] = {}
    level = 0
    while True:
        level += 1
        ready = [u for u in units if u not in fired and all(i in have for i in problem.required[u])]
        if not ready:
            return {o: t for o, t in have.items() if o not in kitchen}, fired
        for u in ready:
            fired[u] = level
        for u in ready:
            for o in problem.products[u]:
                have.setdefault(o, level)


def test_least_fixpoint_matches_rounds(tiny):
    rng = random.Random(5)
    everything = list(range(len(tiny.units)))
    for _ in range(40):
        units = rng.sample(everything, rng.randint(0, len(everything)))
        kitchen = frozenset(rng.sample(sorted(tiny.kitchen), rng.randint(0, len(tiny.kitchen))))
        assert least_fixpoint(kitchen, tiny.required, tiny.products, units) == naive_levels(tiny, kitchen, units)
    objects, fired = tiny.derivation_levels()
    want_objects, want_fired = naive_levels(tiny, tiny.kitchen, everything)
    assert objects == {**dict.fromkeys(tiny.kitchen, 0), **want_objects} and fired == want_fired
    assert tiny.viable_units == frozenset(want_fired)


def test_depth_levels_are_the_problems(tiny):
    levels = Levels.from_problem(tiny, range(len(tiny.units)))
    objects, fired = tiny.derivation_levels()
    assert levels.unit_level == fired
    assert levels.object_level == {o: t for o, t in objects.items() if o not in tiny.kitchen}


def test_with_kitchen_is_the_problem_built_with_that_kitchen(tiny):
    assert tiny.derivable and tiny.viable_units  # cached on the original before the views are made
    rng = random.Random(7)
    for _ in range(10):
        kitchen = frozenset(rng.sample(range(len(tiny.objects)), rng.randint(0, 30)))
        view = tiny.with_kitchen(kitchen)
        built = Problem(tiny.foon, [tiny.objects[o] for o in sorted(kitchen)], tiny.motion_rates, tiny.utensils)
        assert view.kitchen == built.kitchen == kitchen
        assert set(view.kitchen_items) == set(built.kitchen_items)
        assert view.derivable == built.derivable
        assert view.viable_units == built.viable_units
        assert view.viable_producers == built.viable_producers
        assert view.derivation_levels() == built.derivation_levels()
    assert tiny.with_kitchen(tiny.kitchen).derivable == tiny.derivable


def test_lexicographic_weights_order_as_objective_then_units(tiny):
    rng = random.Random(3)
    everything = list(range(len(tiny.units)))
    sets = [rng.sample(everything, rng.randint(0, 12)) for _ in range(200)]
    for objective in UNIT_WEIGHTS:
        w = lexicographic(tiny, objective)
        for a, b in zip(sets, sets[1:]):
            pair_a = (total(tiny, objective, a), len(a))
            pair_b = (total(tiny, objective, b), len(b))
            assert (sum(w[u] for u in a) < sum(w[u] for u in b)) == (pair_a < pair_b), objective
    assert total(tiny, "success", [0, 1]) == sum(round(-1000 * math.log(tiny.rates[u])) for u in (0, 1))
    assert total(tiny, "inputs", everything) == sum(len(i) for i in tiny.inputs)
    assert total(tiny, "units", everything) == len(everything)
    assert neglog_weight(1.0) == 0 and neglog_weight(0.0001) == round(-1000 * math.log(0.001))
