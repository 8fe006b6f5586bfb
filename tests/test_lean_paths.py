"""The faster common paths give the same answers: restricted groundings, facts
left out when no program reads them, the parser's fast line split, JSON lists."""

from __future__ import annotations

import json
import re

import clingo
import pytest

from foon2asp.asp import encodings
from foon2asp.asp.facts import OPTIONAL, facts
from foon2asp.asp.session import AspOptions, Session
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.parser import parse_text
from foon2asp.tree.serialize import json_list
from foon2asp.tree.validate import validate
from helpers import best, build, goal_id


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


def test_restricted_session_same_status_and_size(shared_problem):
    """The 25 goals on the goals' units (as solve grounds them) and on every unit."""
    data, problem = shared_problem
    goals = goals_mod.resolve(data, problem, None, "all")
    small = Session(problem, AspOptions(units=problem.units_for(goals)))
    full = Session(problem, AspOptions(units=tuple(range(len(problem.units)))))
    sizes = {}
    for g in goals:
        a, b = small.solve(g), full.solve(g)
        assert a.status == b.status
        assert len(a.units) == len(b.units)
        if a.status == "optimal":
            assert validate(problem, g, a.units).valid
        sizes[problem.objects[g].label] = (a.status, len(a.units))
    assert sizes["greek salad"] == ("optimal", 25)
    assert sizes["whipped cream"][0] == "unreachable"


def test_facts_leave_out_only_what_is_named(shared_problem):
    _, problem = shared_problem
    units = list(range(40))
    full = facts(problem, units=units)
    lean = facts(problem, units=units, leave_out=OPTIONAL)
    preds = lambda text: {m.group(1) for m in re.finditer(r"^([a-z_]+)\(", text, re.M)}  # noqa: E731
    assert preds(full) - preds(lean) == set(OPTIONAL)
    assert preds(lean) == {"unit", "required", "product", "object", "kitchen"}
    # what stays is exactly the same lines
    kept = [line for line in full.splitlines() if line.split("(")[0] not in OPTIONAL]
    assert kept == lean.splitlines()
    with pytest.raises(ValueError):
        facts(problem, leave_out=["required"])


def test_constraint_on_labels_still_sees_labels():
    # two producers of the goal: the cheaper one uses "knife"; forbidding that label
    # (a program over label/2 and input/2, left out of lean facts) must take the other
    units = [("cut", ["knife", "k"], ["goal"]), ("pour", ["k"], ["x"]), ("mix", ["x"], ["goal"])]
    problem = build(units, ["knife", "k"])
    goal = goal_id(problem, "goal")
    plain = Session(problem).solve(goal)
    assert plain.status == "optimal" and len(plain.units) == 1
    rule = ':- use(U), input(U,O), label(O,"knife").\n'
    constrained = Session(problem, AspOptions(programs=[("rule", rule)])).solve(goal)
    assert constrained.status == "optimal" and sorted(constrained.units) == [1, 2]
    # brute force agrees: unit 0 alone is the one smallest tree, and it has the knife
    size, trees = best(problem, goal, lambda m: m["units"])
    assert size == 1 and trees == [(0,)]


def test_success_objective_keeps_its_weights():
    # success needs neglog/2, which lean facts leave out unless an encoding reads it
    units = [("a", ["k"], ["goal"]), ("b", ["k"], ["y"]), ("c", ["y"], ["goal"])]
    problem = build(units, ["k"], {"a": 0.1, "b": 0.9, "c": 0.9})
    goal = goal_id(problem, "goal")
    tree = Session(problem, AspOptions(objective=("success",))).solve(goal)
    assert tree.status == "optimal" and sorted(tree.units) == [1, 2]  # 0.81 beats 0.1


def test_parser_fast_path_errors_and_ids():
    foon = parse_text("O12\tegg\t0\nS3\twhole\nM7\tcrack*\t0\t1\nO1\tegg\nS\tcracked\n//\n")
    assert len(foon.units) == 1 and foon.units[0].motion == "crack"
    assert foon.units[0].outputs[0].states == ("cracked",)
    from foon2asp.errors import InputError

    for text, needle in (
        ("O egg\n", "expected a TAB"),
        ("Ox\tegg\n", "unknown line type"),
        (" O\tegg\n", "unknown line type"),
        ("X\tegg\n", "unknown line type"),
    ):
        with pytest.raises(InputError, match=needle):
            parse_text(text)


def test_json_list_same_data():
    records = [{"goal": {"label": 'a "quoted"\nlabel'}, "units": [1, 2]}, {"x": None, "é": 1.5}]
    text = json_list(records)
    assert json.loads(text) == records
    assert text.count("\n") == len(records) + 1  # one record per line
    assert json.loads(json_list([])) == []
