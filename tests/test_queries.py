"""reachable, missing and query: checked against the validator and brute force."""

from __future__ import annotations

import itertools
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from foon2asp.analysis import queries
from foon2asp.asp import constraints
from foon2asp.asp.options import AspOptions
from foon2asp.cli.main import main
from foon2asp.errors import InputError
from foon2asp.foon import goals
from foon2asp.foon.problem import Problem
from foon2asp.methods.plan import session_of as Session
from foon2asp.report import query_answers as report_queries
from foon2asp.tree.validate import validate
from helpers import as_obj, brute_force, build, goal_id

REPO = Path(__file__).resolve().parent.parent

# ---------------------------------------------------------------- independent oracles


def extended(problem: Problem, extra) -> Problem:
    """The problem with objects ``extra`` (ids) added to the kitchen, built by hand."""
    items = list(problem.kitchen_items) + [problem.objects[o] for o in extra]
    return Problem(problem.foon, items, problem.motion_rates, problem.utensils, problem.utensil_rule)


def derivable(problem: Problem, goal: int, extra=()) -> bool:
    """Can ``goal`` be made with ``extra`` added?  By the validator: every unit that can fire, then the goal."""
    p = extended(problem, extra) if extra else problem
    fired = validate(p, goal, list(range(len(p.units)))).order
    return validate(p, goal, fired).valid


def bring_in_only(problem: Problem, goal: int) -> set[int]:
    """Objects outside the kitchen, other than the goal, whose every producer needs them,
    directly or through made objects all of whose producers need them (least fixpoint)."""
    n = len(problem.units)
    needs = [{o for o in problem.required[u] if o not in problem.kitchen} for u in range(n)]
    changed = True
    while changed:
        changed = False
        for u in range(n):
            for i in problem.required[u]:
                if i in problem.kitchen or i not in problem.producers:
                    continue
                common = set.intersection(*(needs[p] for p in problem.producers[i]))
                if not common <= needs[u]:
                    needs[u] |= common
                    changed = True
    used = {o for u in range(n) for o in problem.required[u]}
    return {
        o
        for o in used
        if o not in problem.kitchen and o != goal and all(o in needs[u] for u in problem.producers.get(o, ()))
    }


def relevant_objects(problem: Problem, goal: int) -> set[int]:
    return {goal} | {i for u in problem.relevant_units(goal) for i in problem.required[u]}


def smallest_sets(problem: Problem, goal: int, limit: int = 4):
    """(size, sets) of the smallest sets of bring-in-only objects that make the goal derivable."""
    cands = sorted(bring_in_only(problem, goal) & relevant_objects(problem, goal))
    for k in range(min(limit, len(cands)) + 1):
        sets = [s for s in itertools.combinations(cands, k) if derivable(problem, goal, s)]
        if sets:
            return k, sets
    return None, []


# ---------------------------------------------------------------- reachable


def test_reachable_matches_validator_for_all_25_goals(shared_problem):
    data, problem = shared_problem
    ids = goals.resolve(data, problem, (), "all")
    assert len(ids) == 25
    answers = queries.reachable(problem, ids)
    assert list(answers) == list(dict.fromkeys(ids))
    expected = {g: derivable(problem, g) for g in ids}
    assert answers == expected
    labels = {problem.objects[g].label for g, ok in answers.items() if not ok}
    assert labels == {"whipped cream", "fried rice"}


def test_reachable_all_objects_matches_validator_on_demo(demo_problem):
    data, problem = demo_problem
    ids = goals.all_objects(problem)
    answers = queries.reachable(problem, ids)
    assert answers == {o: derivable(problem, o) for o in ids}
    assert any(answers.values()) and not all(answers.values())


def test_cli_reachable_json_and_text():
    r = CliRunner().invoke(main, ["reachable", "--data", "demo", "--format", "json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert [(x["goal"]["label"], x["reachable"]) for x in out] == [
        ("tomato salad", True),
        ("scrambled egg", True),
        ("whipped cream", False),
        ("pancake", False),
    ]
    assert set(out[0]) == {"goal", "reachable"}
    r = CliRunner().invoke(main, ["reachable", "--data", "demo", "--goal", "pancake"])
    assert r.stdout.splitlines() == ["no   pancake, cooked, syrupy, in [pan]", "0 of 1 reachable from the kitchen"]


# ---------------------------------------------------------------- missing: hand-made FOONs

SMALL = {
    # two raw items missing for c; a third route needs three
    "two": (
        [("m", ["a", "x"], ["b"]), ("m", ["b", "y"], ["c"]), ("m", ["a", "p", "q"], ["d"]), ("m", ["d", "r"], ["c"])],
        ["a"],
        "c",
    ),
    # glitch: a unit lists the bottle as input and output; the water is made from the bottle
    "glitch": (
        [("pour", ["bottle", "cup"], ["bottle", "water"]), ("mix", ["water", "flour"], ["dough"])],
        ["cup", "flour"],
        "dough",
    ),
    # b can be made two ways, one needs only a missing item, the other two
    "choice": ([("m", ["x"], ["b"]), ("m", ["y", "z"], ["b"]), ("m", ["b", "a"], ["g"]), ("m", ["w"], ["a"])], [], "g"),
    # reachable already: nothing is missing
    "reachable": ([("m", ["a"], ["b"]), ("n", ["b"], ["c"])], ["a"], "c"),
    # a cycle with an escape: e is made from c or from f; f only from e
    "loop": ([("m", ["e", "k"], ["g"]), ("m", ["c"], ["e"]), ("m", ["f"], ["e"]), ("m", ["e"], ["f"])], ["k"], "g"),
}


@pytest.mark.parametrize("name", sorted(SMALL))
def test_missing_small_vs_brute_force(name):
    units, kitchen, goal = SMALL[name]
    p = build(units, kitchen)
    g = goal_id(p, goal)
    size, sets = smallest_sets(p, g)
    result = queries.missing(p, g)
    assert set(result.buyable) == bring_in_only(p, g) & relevant_objects(p, g)
    if size is None:
        assert result.status == "unreachable"
        return
    assert result.status == "optimal"
    assert len(result.missing) == size
    assert tuple(result.missing) in sets
    p2 = extended(p, result.missing)
    assert validate(p2, g, result.units).valid
    # fewest units among all smallest sets, by brute force over unit subsets
    fewest = min(min(len(t) for t in brute_force(extended(p, s), g)) for s in sets)
    assert len(result.units) == fewest == result.cost["units"]


def test_missing_expected_answers_on_small():
    p = build(*SMALL["two"][:2])
    r = queries.missing(p, goal_id(p, "c"))
    assert sorted(p.objects[o].label for o in r.missing) == ["x", "y"]
    p = build(*SMALL["glitch"][:2])
    r = queries.missing(p, goal_id(p, "dough"))
    assert [p.objects[o].label for o in r.missing] == ["bottle"]
    p = build(*SMALL["reachable"][:2])
    r = queries.missing(p, goal_id(p, "c"))
    assert r.status == "optimal" and r.missing == [] and len(r.units) == 2


def blocked():
    """g from a; a from b or c; b only from a; c from a or e; e only from c: nothing can only be brought in."""
    to_g = [("m1", ["a", "k"], ["g"]), ("m2", ["b"], ["a"]), ("m3", ["c"], ["a"])]
    cycles = [("m4", ["a"], ["b"]), ("m5", ["a"], ["c"]), ("m6", ["e"], ["c"]), ("m7", ["c"], ["e"])]
    return build(to_g + cycles, ["k"])


def test_missing_names_the_blocking_cycle():
    p = blocked()
    g = goal_id(p, "g")
    assert bring_in_only(p, g) == set()
    r = queries.missing(p, g)
    assert r.status == "unreachable" and r.missing == [] and r.units == []
    assert "cycle" in r.reason
    # the path leads from the goal to the cycle; every step: the unit makes the
    # object and needs the next one, which cannot be made
    chain = r.path + r.cycle
    assert chain[0][0] == g and len(r.cycle) == 2
    for k, (o, u) in enumerate(chain):
        nxt = chain[k + 1][0] if k + 1 < len(chain) else r.cycle[0][0]
        assert o in p.products[u] and nxt in p.required[u]
        assert not derivable(p, nxt)
    assert {p.objects[o].label for o, _ in r.cycle} in ({"a", "b"}, {"a", "c"})
    data = report_queries.missing_json(p, r)
    assert data["status"] == "unreachable" and len(data["cycle"]) == 2 and data["missing"] == []
    text = report_queries.missing_text(p, r)
    assert "the cycle:" in text and "back to the start" in text


def test_missing_goal_in_kitchen_and_unmade_goal():
    p = build([("m", ["a"], ["b"])], ["a"])
    r = queries.missing(p, goal_id(p, "a"))
    assert r.status == "optimal" and r.units == [] and r.missing == []
    assert "in the kitchen" in report_queries.missing_text(p, r)
    p = build([("m", ["a"], ["b"]), ("m", ["z"], ["a"])], [])
    r = queries.missing(p, goal_id(p, "z"))
    assert r.status == "unreachable" and "no unit" in r.reason


def test_missing_respects_constraints():
    p = build(*SMALL["choice"][:2])
    g = goal_id(p, "g")
    base = queries.missing(p, g)
    assert sorted(p.objects[o].label for o in base.missing) == ["w", "x"]
    forbid = [("f", constraints.forbid_object("x"))]
    r = queries.missing(p, g, AspOptions(programs=forbid))
    assert sorted(p.objects[o].label for o in r.missing) == ["w", "y", "z"]
    assert validate(extended(p, r.missing), g, r.units).valid
    r = queries.missing(p, g, AspOptions(programs=[("f", constraints.forbid_motion("m"))]))
    assert r.status == "infeasible" and r.reason == "the constraints rule out every tree"


# ---------------------------------------------------------------- missing: ../shared/foon


@pytest.mark.parametrize(
    "label, expected",
    [("whipped cream", None), ("fried rice", {("bottle", ("water",)), ("packet", ("carrot", "corn", "green pea"))})],
)
def test_missing_on_shared(shared_problem, label, expected):
    data, problem = shared_problem
    g = goals.resolve_label(data, problem, label)
    assert not derivable(problem, g)
    result = queries.missing(problem, g)
    assert result.status == "optimal"
    size = {"whipped cream": 1, "fried rice": 2}[label]
    assert len(result.missing) == size
    if expected:
        assert {(problem.objects[o].label, problem.objects[o].ingredients) for o in result.missing} == expected
    # the answer works: the validator accepts the tree with the objects added
    assert validate(extended(problem, result.missing), g, result.units).valid
    # and no smaller set of bring-in-only objects does
    k, sets = smallest_sets(problem, g)
    assert k == size and tuple(result.missing) in sets
    # fewest units among the smallest sets (the tree encoding, on each extended kitchen)
    units = problem.relevant_units(g)
    fewest = min(len(Session(extended(problem, s), AspOptions(units=units)).solve(g).units) for s in sets)
    assert len(result.units) == fewest


def test_missing_reachable_goals_on_shared_equal_solve(shared_problem):
    # for every reachable goal nothing is missing and the tree is as small as solve's
    data, problem = shared_problem
    session = Session(problem, AspOptions())
    reachable = [g for g in goals.resolve(data, problem, (), "all") if derivable(problem, g)]
    assert len(reachable) == 23
    for g in reachable:
        r = queries.missing(problem, g)
        assert r.status == "optimal" and r.missing == []
        assert validate(problem, g, r.units).valid
        assert len(r.units) == len(session.solve(g).units)


def test_missing_goes_through_the_goal_runner(shared_problem):
    # a goal the kitchen can make: the same tree as solve's runner, for every tree objective
    from foon2asp.methods.runner import solve_goals

    data, problem = shared_problem
    reachable = [g for g in goals.resolve(data, problem, (), "all") if derivable(problem, g)][:6]
    for objective in (("units",), ("success", "units"), ("inputs",)):
        options = AspOptions(objective=objective)
        trees = list(solve_goals(problem, reachable, "asp", options))
        for g, tree in zip(reachable, trees):
            r = queries.missing(problem, g, options)
            assert r.status == tree.status == "optimal" and r.missing == []
            assert r.units == tree.units
            assert r.cost == dict(tree.cost, added=0)


def test_cli_missing_json_shape(shared_foon_dir):
    r = CliRunner().invoke(
        main, ["missing", "--data", str(shared_foon_dir), "--goal", "fried rice", "--format", "json"]
    )
    assert r.exit_code == 0, r.output
    (out,) = json.loads(r.stdout)
    assert {"goal", "status", "missing", "units"} <= set(out)
    assert out["status"] == "optimal" and len(out["missing"]) == 2
    assert {"motion", "inputs", "outputs"} == set(out["units"][0])
    assert out["cost"]["units"] == len(out["units"])


def test_cli_missing_text_demo():
    r = CliRunner().invoke(main, ["missing", "--data", "demo", "--goal", "pancake"])
    assert r.exit_code == 0, r.output
    assert "Missing 1 object(s)" in r.stdout and "+ maple syrup, in [bottle]" in r.stdout


# ---------------------------------------------------------------- query


def test_query_decodes_objects_and_units(tmp_path, demo_problem):
    data, problem = demo_problem
    prog = tmp_path / "q.lp"
    prog.write_text(
        "% which units chop, and what can be made\n"
        "#show chops/1.\n"
        'chops(U) :- motion(U,"chop").\n'
        '#show can(object(O)) : reach(O), label(O,"tomato salad").\n'
    )
    r = CliRunner().invoke(main, ["query", "--data", "demo", str(prog), "--encoding", "tree"])
    assert r.exit_code == 0, r.output
    assert "can(<tomato salad, mixed, in [bowl]>)" in r.stdout
    assert "chops(0)" in r.stdout  # a user predicate: plain numbers stay numbers
    out = json.loads(
        CliRunner()
        .invoke(main, ["query", "--data", "demo", str(prog), "--encoding", "tree", "--format", "json"])
        .stdout
    )
    (model,) = out["models"]
    can = [a for a in model["atoms"] if a["predicate"] == "can"]
    assert can[0]["arguments"][0]["label"] == "tomato salad"


def test_query_with_tree_and_objective(demo_problem):
    data, problem = demo_problem
    g = goals.resolve_label(data, problem, "tomato salad")
    res = queries.query(problem, ("q", "#show use/1.\n"), goal=g, with_encodings=["tree", "units"])
    assert res.status == "optimal"
    (answer,) = res.answers
    used = [s.arguments[0].number for s in answer.symbols]
    assert validate(problem, g, used).valid and len(used) == 4 == answer.cost[0]
    text = report_queries.query_text(problem, res)
    assert "use(<chop: tomato, whole; knife -> tomato, chopped; knife>)" in text


def test_query_enumerates_and_reports_unsat(tmp_path):
    res = queries.query(build([("m", ["a"], ["b"])], ["a"]), ("q", "{ p(1..3) } = 1.\n#show p/1."), models=0)
    assert res.status == "satisfiable" and len(res.answers) == 3
    prog = tmp_path / "no.lp"
    prog.write_text(":- kitchen(O).\n")
    r = CliRunner().invoke(main, ["query", "--data", "demo", str(prog)])
    assert r.exit_code == 1 and r.stdout == "Status: unsatisfiable\n"  # no model: exit 1, as documented


def test_query_exit_status_is_the_documented_one(tmp_path):
    """0 with a model, 1 without one (unsatisfiable), the same in both --help texts, the README and docs."""
    no, yes = tmp_path / "no.lp", tmp_path / "yes.lp"
    no.write_text(":- kitchen(O).\n")
    yes.write_text("#show kitchen/1.\n")
    r = CliRunner().invoke(main, ["query", "--data", "demo", "--format", "json", str(no)])
    assert r.exit_code == 1 and json.loads(r.stdout)["status"] == "unsatisfiable"
    r = CliRunner().invoke(main, ["query", "--data", "demo", str(yes)])
    assert r.exit_code == 0 and r.stdout.startswith("Status: satisfiable\n")
    flat = " ".join(CliRunner().invoke(main, ["query", "--help"]).output.split())
    assert "1 no such answer: proven unsatisfiable" in flat
    assert "query: unsatisfiable" in " ".join(CliRunner().invoke(main, ["--help"]).output.split())
    readme = " ".join((REPO / "README.md").read_text().split())
    assert "`query` is unsatisfiable" in readme and "for `query`, a model or proven unsatisfiable" not in readme
    assert "1 when unsatisfiable" in " ".join((REPO / "docs" / "queries.md").read_text().split())


def test_query_errors_are_located(tmp_path):
    prog = tmp_path / "bad.lp"
    prog.write_text("#show p/1.\np(X) :- q(.\n")
    r = CliRunner().invoke(main, ["query", "--data", "demo", str(prog)])
    assert r.exit_code == 2 and r.stderr.startswith(f"foon2asp: error: {prog}:2: syntax error")
    with pytest.raises(InputError, match="no encoding"):
        queries.query(build([("m", ["a"], ["b"])], ["a"]), ("q", "a."), with_encodings=["nope"])


def test_labels_in_facts_stay_data_for_queries():
    evil = as_obj('x"). #show hacked/0. hacked. %')
    p = build([("m", [evil], ["b"])], [evil])
    res = queries.query(p, ("q", "#show label/2."))
    labels = [s.arguments[1].string for s in res.answers[0].symbols]
    assert evil.label in labels and not any(s.name == "hacked" for s in res.answers[0].symbols)


def test_a_missing_query_program_is_named_as_a_program():
    """`query nope.lp` is about the program, not a constraint file."""
    from click.testing import CliRunner

    from foon2asp.cli.main import main

    res = CliRunner().invoke(main, ["query", "nope.lp", "--data", "demo"])
    assert res.exit_code == 2
    assert "nope.lp: ASP program file not found" in res.output and "constraint" not in res.output
