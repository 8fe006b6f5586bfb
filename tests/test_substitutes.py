"""Ingredient substitutes (foon2asp.foon.substitutes, foon2asp.asp.substitute_facts, encodings/substitutes.lp).

The solver's trees are compared with brute force on small random FOONs: every
set of substitutions (kitchen items standing in for objects) and every set of
units, judged by the independent validator with the substituted objects as
kitchen items; the best is the least summed substitution cost, then the fewest
units.
"""

from __future__ import annotations

import itertools
import random

import pytest

from foon2asp.asp.facts import facts
from foon2asp.asp.options import AspOptions
from foon2asp.asp.substitute_facts import report, substitute_facts
from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import (
    Substitute,
    by_needed,
    candidates,
    parse_substitutes,
    read_substitutes,
    stand_ins,
    substituted_kitchen,
    with_substitutes,
)
from foon2asp.methods.plan import grounding, plain
from foon2asp.methods.plan import session_of as Session
from foon2asp.methods.runner import solve_goals as run_goals
from foon2asp.tree.validate import validate
from helpers import build, goal_id, obj


def solve_goals(problem, goals, method="asp", options=None, **kw):
    """The goal runner's trees for ``goals`` (default: the units objective)."""
    return run_goals(problem, goals, method, options or AspOptions(), **kw)


# --- reading --------------------------------------------------------------------------------


def test_lines_and_json_forms(tmp_path):
    lines = "# onions\nonion: red onion, shallot=2\n\n  Butter :margarine = 3\n"
    want = (
        Substitute("onion", "red onion", 1),
        Substitute("onion", "shallot", 2),
        Substitute("butter", "margarine", 3),
    )
    assert parse_substitutes(lines) == want
    text = '{"onion": ["Red Onion"], "onion ": {"shallot": 2}, "butter": {"margarine": 3}}'
    assert set(parse_substitutes(text)) == {
        Substitute("onion", "red onion", 1),
        Substitute("onion", "shallot", 2),
        Substitute("butter", "margarine", 3),
    }
    path = tmp_path / "subs.txt"
    path.write_text(lines, encoding="utf-8")
    assert read_substitutes(path) == want


@pytest.mark.parametrize(
    "text, where, what",
    [
        ("onion: red onion\nshallot\n", "s.txt:2", "expected 'label: substitute"),
        ("onion:\n", "s.txt:1", "no substitutes"),
        ("onion: shallot=0\n", "s.txt:1", "positive integer"),
        ("onion: shallot=two\n", "s.txt:1", "positive integer"),
        ("onion: shallot, shallot=2\n", "s.txt:1", "listed twice"),
        ("onion: Onion\n", "s.txt:1", "its own substitute"),
        ("onion: , shallot\n", "s.txt:1", "both sides"),
        ('["onion"]', "s.txt", "expected a JSON object"),
        ('{"onion": "shallot"}', "s.txt", "list of labels"),
        ('{"onion": {"shallot": true}}', "s.txt", "positive integer"),
        ('{"onion": {"shallot": 1.5}}', "s.txt", "positive integer"),
        ('{"onion": ["shallot"', "s.txt:1", "bad JSON"),
    ],
)
def test_bad_files_name_file_and_line(text, where, what):
    with pytest.raises(InputError) as err:
        parse_substitutes(text, "s.txt")
    message = str(err.value)
    assert message.startswith(where + ":") and what in message and "\n" not in message


def test_candidates_by_label_and_by_ingredient():
    bowl = obj("bowl", "mixed", contains=("onion", "salt"))
    problem = build(
        [("mix", [obj("onion", "chopped"), obj("salt")], [bowl])],
        [obj("red onion", "chopped"), obj("salt"), obj("bowl", "mixed", contains=("salt", "shallot"))],
    )
    subs = parse_substitutes("onion: red onion, shallot=2\n")
    assert [(o.text, c) for o, c in stand_ins(obj("onion", "chopped"), by_needed(subs))] == [
        ("red onion, chopped", 1),
        ("shallot, chopped", 2),
    ]
    got = {(problem.objects[c.needed].text, c.used.text, c.cost) for c in candidates(problem, subs)}
    assert got == {
        ("onion, chopped", "red onion, chopped", 1),
        ("bowl, mixed, contains {onion,salt}", "bowl, mixed, contains {salt,shallot}", 2),
    }
    view = with_substitutes(problem, subs)
    assert view is not problem and with_substitutes(view, subs) is view
    assert view.substitutable == {goal_id(problem, obj("onion", "chopped")), goal_id(problem, bowl)}
    assert problem.substitutable == frozenset() and problem.viable_units == frozenset()
    assert view.viable_units == {0}


# --- the solver -----------------------------------------------------------------------------


def _soup(first: FoonObject | None = None) -> Problem:
    """Onion soup: chop a whole onion, cook the chopped one; the kitchen has no onion, but
    ``first`` (default: a whole red onion), a chopped red onion, a knife and a pan."""
    return build(
        [
            ("chop", [obj("onion", "whole"), obj("knife")], [obj("onion", "chopped")]),
            ("cook", [obj("onion", "chopped"), obj("pan")], [obj("soup", "cooked")]),
        ],
        [first or obj("red onion", "whole"), obj("red onion", "chopped"), obj("knife"), obj("pan")],
    )


def test_the_fewest_substitutions_rank_above_the_objective():
    problem = _soup()
    goal = goal_id(problem, obj("soup", "cooked"))
    subs = parse_substitutes("onion: red onion\n")
    [tree] = solve_goals(problem, [goal])
    assert tree.status == "unreachable"
    [tree] = solve_goals(problem, [goal], options=AspOptions(substitutes=subs))
    # one substitution either way: the chopped red onion saves the chop
    assert tree.status == "optimal" and [problem.units[u].motion for u in tree.units] == ["cook"]
    assert tree.substitutions == [{"needed": "onion, chopped", "used": "red onion, chopped"}]
    assert tree.asp_cost == [1, 1]
    # a kitchen that has the whole onion: no substitution, though it takes one unit more
    problem.kitchen_items.append(obj("onion", "whole"))
    problem = Problem(problem.foon, problem.kitchen_items)
    [tree] = solve_goals(problem, [goal], options=AspOptions(substitutes=subs))
    assert len(tree.units) == 2 and tree.substitutions == [] and tree.asp_cost == [0, 2]
    [tree] = solve_goals(problem, [goal], options=AspOptions(substitutes=subs, max_substitutions=0))
    assert len(tree.units) == 2


def test_max_substitutions_and_costs():
    problem = _soup()
    goal = goal_id(problem, obj("soup", "cooked"))
    subs = parse_substitutes("onion: red onion\n")
    [tree] = solve_goals(problem, [goal], options=AspOptions(substitutes=subs, max_substitutions=0))
    assert tree.status == "unreachable"
    # the chopped red onion costs 3, the whole shallot 1: chop the shallot
    problem = _soup(obj("shallot", "whole"))
    subs = parse_substitutes("onion: red onion=3, shallot\n")
    [tree] = solve_goals(problem, [goal_id(problem, obj("soup", "cooked"))], options=AspOptions(substitutes=subs))
    assert len(tree.units) == 2 and tree.asp_cost[0] == 1
    assert tree.substitutions == [{"needed": "onion, whole", "used": "shallot, whole"}]


def test_options_turn_the_shortcuts_off_and_load_the_encoding():
    subs = (Substitute("onion", "red onion"),)
    assert plain(AspOptions()) and not plain(AspOptions(substitutes=subs))
    problem = _soup()
    assert "substitutes" not in grounding(problem, AspOptions()).facts
    assert "substitutes" in grounding(problem, AspOptions(substitutes=subs)).facts
    for options in (
        AspOptions(substitutes=subs, max_depth=3),
        AspOptions(substitutes=subs, objective=("depth",)),
        AspOptions(substitutes=subs, heuristic="h1"),
    ):
        with pytest.raises(InputError, match="cannot use substitutes"):
            Session(problem, options)


# --- brute force ----------------------------------------------------------------------------

LABELS = ["a", "b", "c", "d"]
SUBS = "a: a2, a3=2\nb: b2=2\nc: a\n"


def _random_problem(rng: random.Random) -> Problem:
    def thing() -> FoonObject:
        if rng.random() < 0.2:
            return obj("bowl", "full", contains=tuple(rng.sample(LABELS, 2)))
        return obj(rng.choice(LABELS), rng.choice(["s", "t"]))

    units = []
    for i in range(rng.randint(5, 8)):
        ins = [thing() for _ in range(rng.randint(1, 2))]
        units.append((f"m{i}", ins, [thing()]))
    stand = [obj(lab, st) for lab in ("a2", "a3", "b2", "a") for st in ("s", "t")]
    stand += [obj("bowl", "full", contains=("a2", x)) for x in LABELS]
    kitchen = rng.sample([obj(lab, "s") for lab in LABELS], 2) + rng.sample(stand, 4)
    return build(units, kitchen)


def _brute_force(problem: Problem, goal: int, subs, limit: int | None) -> tuple[int, int] | None:
    cands = [c for c in candidates(problem, subs) if c.needed != goal]
    best = None
    for k in range(len(cands) + 1):
        if limit is not None and k > limit:
            break
        for chosen in itertools.combinations(cands, k):
            if len({c.needed for c in chosen}) < k:
                continue
            view = substituted_kitchen(problem, [c.needed for c in chosen])
            cost = sum(c.cost for c in chosen)
            for n in range(len(problem.units) + 1):
                if best is not None and (cost, n) >= best:
                    break
                if any(
                    validate(view, goal, list(t)).valid for t in itertools.combinations(range(len(problem.units)), n)
                ):
                    best = (cost, n)
                    break
    return best


def test_against_brute_force():
    rng = random.Random(21)
    subs = parse_substitutes(SUBS)
    checked = used = 0
    for trial in range(40):
        problem = _random_problem(rng)
        goals = sorted({o for prods in problem.products for o in prods})
        limit = [None, 1, 0][trial % 3]
        options = AspOptions(substitutes=subs, max_substitutions=limit)
        grounding = ["whole", "per-goal"][trial % 2]
        trees = {t.goal: t for t in solve_goals(problem, goals, options=options, grounding=grounding)}
        by_text = {o.text: i for i, o in enumerate(problem.objects)}
        for g in goals:
            want = _brute_force(problem, g, subs, limit)
            tree = trees[g]
            if want is None:
                assert tree.status == "unreachable", (trial, g)
                continue
            assert tree.status == "optimal", (trial, g)
            made = tree.substitutions
            costs = {(problem.objects[c.needed].text, c.used.text): c.cost for c in candidates(problem, subs)}
            cost = sum(costs[(s["needed"], s["used"])] for s in made)
            assert (cost, len(tree.units)) == want, (trial, g)
            # the solver's cost vector: substitutions, then units (levels with nothing to count are absent)
            asp = tree.asp_cost
            assert asp in ([want[0], want[1]], [want[1]], []) and (len(asp) < 2 or asp[0] == cost)
            assert asp or want == (0, 0)
            assert limit is None or len(made) <= limit
            view = substituted_kitchen(problem, [by_text[s["needed"]] for s in made])
            assert validate(view, g, tree.units).valid
            checked += 1
            used += bool(made)
    assert checked > 60 and used > 15


# --- labels stay data -----------------------------------------------------------------------

SPECIAL = ['qu"ote', "back\\slash", "50% fat", "end.", "a :- b", "#show x.", "{braces}", "it's (x)."]


@pytest.mark.parametrize("label", SPECIAL)
def test_special_labels_stay_data(tmp_path, label):
    import json

    path = tmp_path / "subs.json"
    path.write_text(json.dumps({"onion": [label]}), encoding="utf-8")
    subs = read_substitutes(path)
    assert subs == (Substitute("onion", label.lower(), 1),)
    problem = build(
        [("cook", [obj("onion", "chopped"), obj("pan")], [obj(label, "cooked")])],
        [obj(label, "chopped"), obj("pan")],
    )
    goal = goal_id(problem, obj(label, "cooked"))
    text = facts(problem) + substitute_facts(problem, subs)
    assert text.count("substitute(") == 1
    # a user program that reads the labels makes the session write them as facts
    program = "seen(L) :- label(_,L).\n#show seen/1.\n"
    options = AspOptions(substitutes=subs, programs=[("reads labels", program)])
    seen: set[str] = set()

    def on_model(model) -> None:
        seen.update(s.arguments[0].string for s in model.symbols(shown=True) if s.name == "seen")

    tree = Session(problem, options).solve(goal, on_model=on_model)
    assert seen == {label.lower(), "onion", "pan"}
    assert tree.status == "optimal" and len(tree.units) == 1
    assert tree.substitutions == [{"needed": "onion, chopped", "used": f"{label.lower()}, chopped"}]
    assert report(problem, [goal], tree.units, subs) == tree.substitutions


def validate_with(problem, goal, units, substitutes):
    """The independent validator's verdict on a tree that may rely on substitutes, and the
    substitutions it uses (:func:`report`): valid when the tree makes ``goal`` with every
    object a substitute can stand in for (but the goal) as a kitchen item."""
    substitutes = tuple(substitutes)
    units = list(units)
    needed = [c.needed for c in candidates(problem, substitutes) if c.needed != goal]
    verdict = validate(substituted_kitchen(problem, needed), goal, units)
    return verdict, report(problem, [goal], units, substitutes) if verdict.valid else []


def test_validator_accepts_a_tree_that_relies_on_substitutes():
    problem = _soup()
    goal = goal_id(problem, obj("soup", "cooked"))
    subs = parse_substitutes("onion: red onion\n")
    cook = [u for u, unit in enumerate(problem.units) if unit.motion == "cook"]
    assert not validate(problem, goal, cook).valid
    verdict, used = validate_with(problem, goal, cook, subs)
    assert verdict.valid and used == [{"needed": "onion, chopped", "used": "red onion, chopped"}]
    verdict, used = validate_with(problem, goal, cook, parse_substitutes("onion: shallot\n"))
    assert not verdict.valid and "onion, chopped" in (verdict.problem or "") and used == []
    # the goal itself is never stood in for
    soup = build([("cook", [obj("onion", "chopped")], [obj("soup", "cooked")])], [obj("stew", "cooked")])
    verdict, _ = validate_with(soup, goal_id(soup, obj("soup", "cooked")), [], parse_substitutes("soup: stew"))
    assert not verdict.valid


def test_substitutes_at_a_level_with_normalised_labels():
    from foon2asp.foon.matching import Projection, Texts

    problem = _soup()
    projection = Projection(1, Texts(normalize=True))
    foon = projection.foon(problem.foon)
    kitchen = projection.objects(problem.kitchen_items[:1] + problem.kitchen_items[2:])  # no chopped red onion
    level1 = Problem(foon, kitchen)
    subs = projection.substitutes(parse_substitutes("Onions: red onions=2, onion\n"))
    assert subs == (Substitute("onion", "red onion", 2),)
    goal = level1.foon.object_ids[FoonObject("soup")]
    [tree] = solve_goals(level1, [goal], options=AspOptions(substitutes=subs))
    # at level 1 chopping passes the onion through: the red onion stands in for the onion
    assert [level1.units[u].motion for u in tree.units] == ["cook"]
    assert tree.substitutions == [{"needed": "onion", "used": "red onion"}]
