"""Facts: vocabulary, and labels can never inject ASP code."""

from __future__ import annotations

import re

import clingo
import pytest

from foon2asp.asp.facts import OPTIONAL, facts, neglog_weight, q
from foon2asp.asp.predicates import FACTS
from foon2asp.methods.plan import session_of as Session
from helpers import build, obj

NASTY = [
    'quote " inside',
    "back\\slash\\",
    "end). #show evil/0. evil.",
    "#show x.",
    "new\nline",
    '"). :- goal(_). %',
    "% comment",
    "unicode crème brûlée",
]


def nasty_problem():
    units = []
    kitchen = [obj("knife")]
    prev = obj("start", "raw")
    kitchen.append(prev)
    for _i, text in enumerate(NASTY):
        nxt = obj(text, text, contains=[text], inside=text)
        units.append((text, [prev, obj("knife")], [nxt]))
        prev = nxt
    return build(units, kitchen), prev


def ground_atoms(text: str) -> list[clingo.Symbol]:
    ctl = clingo.Control()
    ctl.add("base", [], text)
    ctl.ground([("base", [])])
    return [a.symbol for a in ctl.symbolic_atoms]


def test_labels_stay_data():
    problem, last = nasty_problem()
    gid = problem.foon.object_ids[last]
    text = facts(problem, goal_nodes=[gid], goal=gid)
    atoms = ground_atoms(text)
    signatures = {(a.name, len(a.arguments)) for a in atoms}
    assert signatures <= FACTS
    labels = {a.arguments[1].string for a in atoms if a.name == "label"}
    motions = {a.arguments[1].string for a in atoms if a.name == "motion"}
    expected = {o.label for o in problem.objects}
    assert labels == expected
    assert motions == {u.motion for u in problem.units}
    # every nasty text survives exactly (whitespace folded, lower-cased by the model)
    for text in NASTY:
        norm = " ".join(text.split()).lower()
        assert norm in labels
        assert any(a.name == "ingredient" and a.arguments[1].string == norm for a in atoms)
        assert any(a.name == "container" and a.arguments[1].string == norm for a in atoms)


def test_nasty_labels_solve():
    problem, last = nasty_problem()
    tree = Session(problem).solve(problem.foon.object_ids[last])
    assert tree.status == "optimal"
    assert len(tree.units) == len(NASTY)


def test_required_and_products():
    # the bowl holding only the tomato is not required (utensil rule); the knife output is no product
    bowl = obj("bowl", contains=["tomato"])
    tomato = obj("tomato", inside="bowl")
    problem = build(
        [("mix", [bowl, tomato, obj("knife")], [obj("salad", "mixed"), obj("knife")])],
        [tomato, obj("knife")],
        utensils=["bowl"],
    )
    atoms = {str(a) for a in ground_atoms(facts(problem))}
    ids = problem.foon.object_ids
    assert f"input(0,{ids[bowl]})" in atoms and f"required(0,{ids[bowl]})" not in atoms
    assert f"required(0,{ids[tomato]})" in atoms
    assert f"output(0,{ids[obj('knife')]})" in atoms and f"product(0,{ids[obj('knife')]})" not in atoms
    assert f"product(0,{ids[obj('salad', 'mixed')]})" in atoms


@pytest.mark.parametrize("rate, weight", [(1.0, 0), (0.5, 693), (0.1, 2303), (0.9, 105)])
def test_neglog_weights(rate, weight):
    assert neglog_weight(rate) == weight


@pytest.mark.parametrize("text", NASTY + ["tab\there", "nul\x00byte", "cr\rlf"])
def test_quoting_matches_clingo(text):
    literal = q(text)
    assert literal == str(clingo.String(text.replace("\x00", "")))
    (atom,) = ground_atoms(f"x({literal}).")
    assert atom.arguments[0].string == text.replace("\x00", "")


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
