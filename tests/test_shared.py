"""The universal FOON in ../shared/foon: all 25 goals, every tree validated."""

from __future__ import annotations

import pytest

from foon2asp.foon.goals import goal_id
from foon2asp.methods.plan import session_of as Session
from foon2asp.tree.validate import check_order, validate

EXPECTED_SIZES = {"greek salad": 25, "macaroni": 5, "carrot salad": 19}
UNREACHABLE = {"whipped cream", "fried rice"}


@pytest.fixture(scope="module")
def results(shared_problem):
    data, problem = shared_problem
    session = Session(problem)
    out = []
    for obj, line in data.goals:
        g = goal_id(problem, obj, "goal_nodes.json", line)
        out.append((obj, g, session.solve(g)))
    return problem, out


def test_all_goals_solved(results):
    problem, out = results
    assert len(out) == 25
    statuses = {obj.label: tree.status for obj, _, tree in out}
    assert {k for k, v in statuses.items() if v == "unreachable"} == UNREACHABLE
    assert all(v == "optimal" for k, v in statuses.items() if k not in UNREACHABLE)


def test_known_sizes(results):
    _, out = results
    sizes = {obj.label: len(tree.units) for obj, _, tree in out}
    for label, size in EXPECTED_SIZES.items():
        assert sizes[label] == size


def test_every_tree_valid_ordered_and_locally_minimal(results):
    problem, out = results
    for obj, g, tree in out:
        if tree.status != "optimal":
            continue
        assert validate(problem, g, tree.units).valid, obj
        assert check_order(problem, g, tree.units) is None, obj
        assert tree.cost["units"] == len(tree.units)
        # dropping any one unit breaks the tree
        for u in tree.units:
            rest = [x for x in tree.units if x != u]
            assert not validate(problem, g, rest).valid, (obj, u)


def test_unreachable_goals_are_not_derivable_with_all_units(results):
    problem, out = results
    fired = validate(problem, 0, list(range(len(problem.units)))).order  # every unit that can ever fire
    for obj, g, tree in out:
        by_validator = validate(problem, g, fired).valid
        assert by_validator == (g in problem.derivable)
        assert by_validator == (obj.label not in UNREACHABLE), obj
        if not by_validator:
            assert tree.units == []
