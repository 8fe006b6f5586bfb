"""The problem in integer form: the units a tree for some goals can use."""

from __future__ import annotations

from dataclasses import replace

import clingo

from foon2asp.asp import encodings
from foon2asp.asp.facts import facts
from foon2asp.foon import goals as goals_mod


def _units_for_by_definition(problem, goals):
    """The encoding's candidate units for the goals, as clingo grounds them on the whole FOON."""
    ctl = clingo.Control()
    ctl.add("base", [], facts(problem) + encodings.encoding("tree") + "".join(f"goal({g}).\n" for g in goals))
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


def test_unit_id_finds_the_equal_unit(shared_problem):
    _, problem = shared_problem
    for uid in (0, len(problem.units) // 2, len(problem.units) - 1):
        unit = problem.units[uid]
        # an equal unit with its objects in another order is the same unit
        turned = replace(unit, inputs=unit.inputs[::-1], outputs=unit.outputs[::-1])
        assert problem.foon.unit_id(turned) == uid
    unit = problem.units[0]
    assert problem.foon.unit_id(replace(unit, motion=unit.motion + " twice")) is None
