"""Lower bounds and gaps of unproven answers (foon2asp.tree.gap), --gap, and the landmark bound.

Every bound any source proves -- the solver's cores while it searches, the landmarks,
a search cut short -- is checked to be at most the optimum: against brute force on
small random FOONs, and against a completed proof on synthetic FOONs with real choice.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

import foon2asp
from foon2asp.asp.options import AspOptions
from foon2asp.bounds.lower import Bounds
from foon2asp.cli.main import main
from foon2asp.methods.plan import session_of as Session
from foon2asp.methods.runner import solve_goals
from foon2asp.tree.gap import gap_of, gap_text, levels, settle, value
from foon2asp.tree.tasktree import TaskTree, measures
from foon2asp.tree.validate import validate
from foon2asp.tree.weights import neglog_weight
from helpers import brute_force
from synth import preset
from test_objectives import made_goals, random_foon


def weight(problem, name, units):
    """The solver's weight of a tree on one objective level (brute force's yardstick)."""
    if name == "units":
        return len(units)
    if name == "success":
        return sum(neglog_weight(problem.rates[u]) for u in units)
    if name == "inputs":
        return sum(len(problem.inputs[u]) for u in units)
    raise ValueError(name)


def lexicographic_optimum(problem, goal, ranked):
    trees = brute_force(problem, goal)
    if not trees:
        return None
    return min(tuple(weight(problem, n, t) for n in ranked) for t in trees)


def recorded(options):
    """Options whose progress callback keeps every lower bound the solver reports."""
    seen: list[list[int]] = []
    return AspOptions(**{**options.__dict__, "progress": lambda info: seen.append(list(info["lower"]))}), seen


def assert_bound_at_most(lower, optimum):
    """A lexicographic bound: level k is a bound once the levels above it are met."""
    for k, low in enumerate(lower):
        assert low <= optimum[k], (lower, optimum)
        if low < optimum[k]:
            return


@pytest.mark.parametrize("ranked", [("units",), ("success", "units"), ("inputs", "units")])
@pytest.mark.parametrize("seed", range(12))
def test_every_bound_is_at_most_the_brute_force_optimum(seed, ranked):
    problem = random_foon(seed, n_units=11)
    bounds = Bounds(problem, ranked)
    for goal in made_goals(problem):
        optimum = lexicographic_optimum(problem, goal, ranked)
        options, seen = recorded(AspOptions(objective=ranked, opt_strategy="usc"))
        tree = Session(problem, options).solve(goal, floor=bounds.first_lower(goal))
        if optimum is None:
            assert tree.status == "unreachable" and tree.bound is None
            continue
        # the landmark bound, every core bound seen while searching, and the final bound
        assert bounds.first_lower(goal) <= optimum[0]
        for lower in seen:
            assert_bound_at_most(lower, optimum)
        assert tree.status == "optimal" and tree.gap == 0.0
        assert tree.bound == {n: tree.cost[n] for n in ranked}
        assert tuple(weight(problem, n, tree.units) for n in ranked) == optimum


def test_cores_bound_the_optimum_on_a_foon_with_real_choice():
    syn = preset("small")
    problem = syn.problem()
    goals = [problem.foon.object_ids[g] for g in syn.goals]
    checked = 0
    for goal in goals:
        if goal not in problem.derivable:
            continue
        options, seen = recorded(AspOptions(opt_strategy="usc", canonical=False))
        tree = Session(problem, replace_units(options, problem, goal)).solve(goal)
        assert tree.status == "optimal"
        optimum = (len(tree.units),)
        for lower in seen:
            assert_bound_at_most(lower, optimum)
        checked += len(seen)
    assert checked > 0  # some core bounds were reported on the way


def replace_units(options, problem, goal):
    return AspOptions(**{**options.__dict__, "units": problem.units_for([goal])})


def test_a_goal_cut_short_reports_a_bound_at_most_the_proven_optimum(hard):
    problem, goals = hard
    goal = goals[7]  # about 40 units; proven in a few seconds, not in a fraction of one
    (short,) = solve_goals(problem, [goal], "asp", AspOptions(time_limit=0.05))
    (full,) = solve_goals(problem, [goal], "asp", AspOptions())
    assert full.status == "optimal" and full.bound == {"units": full.cost["units"]} and full.gap == 0.0
    assert short.status in ("feasible", "optimal")
    assert validate(problem, goal, short.units).valid
    assert short.bound["units"] <= full.cost["units"] <= len(short.units)
    if short.status == "feasible":
        assert short.gap == pytest.approx((len(short.units) - short.bound["units"]) / len(short.units), abs=1e-6)
        assert 0 < short.gap <= 1


def test_gap_stops_early_and_gap_zero_equals_plain_solving(hard):
    problem, goals = hard
    goal = goals[8]
    (stopped,) = solve_goals(problem, [goal], "asp", AspOptions(gap=0.5, time_limit=60))
    assert stopped.status == "feasible" and 0 < stopped.gap <= 0.5
    assert validate(problem, goal, stopped.units).valid
    assert stopped.bound["units"] <= len(stopped.units)
    small = preset("small")
    p = small.problem()
    ids = [p.foon.object_ids[g] for g in small.goals]
    plain = list(solve_goals(p, ids, "asp", AspOptions()))
    zero = list(solve_goals(p, ids, "asp", AspOptions(gap=0.0)))
    assert [(t.status, t.units, t.bound, t.gap) for t in zero] == [(t.status, t.units, t.bound, t.gap) for t in plain]


def test_cli_gap_zero_equals_plain_and_the_bound_is_in_json_and_text():
    runner = CliRunner()
    base = ["solve", "--data", "demo", "--goals", "all", "--format", "json"]
    plain = json.loads(runner.invoke(main, base).stdout)
    zero = json.loads(runner.invoke(main, [*base, "--gap", "0"]).stdout)
    strip = [{k: v for k, v in r.items() if k not in ("time_s", "stats")} for r in plain]
    assert strip == [{k: v for k, v in r.items() if k not in ("time_s", "stats")} for r in zero]
    for r in plain:
        if r["status"] == "optimal":
            assert r["gap"] == 0.0 and r["bound"]["units"] == r["cost"]["units"]
    bad = runner.invoke(main, [*base, "--gap", "-1"])
    assert bad.exit_code == 2 and "--gap" in bad.stderr
    pct = runner.invoke(main, [*base, "--gap", "5%"])
    assert pct.exit_code == 0


def test_library_trees_carry_bound_and_gap():
    kb = foon2asp.load("demo")
    tree = kb.solve("tomato salad", objective="success")
    assert tree.status == "optimal" and tree.gap == 0.0
    assert tree.bound == {"success": tree.cost["success"], "units": tree.cost["units"]}
    gbfs = kb.solve("tomato salad", method="gbfs-h1")
    assert gbfs.bound is None and gbfs.gap is None


# ---------------------------------------------------------------- the arithmetic


def test_values_levels_and_text():
    assert levels(("success", "units"), substitutes=True, human=True) == ("substitutions", "success", "units", "human")
    assert value("units", 54) == 54
    assert value("cost", 135) == 1.35 and value("cost", 200) == 2
    assert value("success", 0) == 1.0 and math.isclose(value("success", 693), 0.5, rel_tol=1e-3)
    assert gap_of([65], [54]) == pytest.approx(11 / 65, abs=1e-6)
    assert gap_of([65], None, floor=8) == pytest.approx(57 / 65, abs=1e-6)
    assert gap_of([3, 10], [2, 10], first=1) is None  # the level above is not closed
    assert gap_of([0], None) == 0.0
    tree = TaskTree(1, "asp-units", "feasible", list(range(65)), {"units": 65}, asp_cost=[65])
    settle_problem = None
    settle(settle_problem, tree, ("units",), [54])  # type: ignore[arg-type]
    assert tree.bound == {"units": 54} and tree.gap == pytest.approx(0.169231)
    assert gap_text(tree) == "units 65, lower bound 54, gap 17%"


def test_a_bound_that_meets_the_answer_proves_it(hard):
    problem, goals = hard
    goal = goals[2]
    (tree,) = solve_goals(problem, [goal], "asp", AspOptions())
    assert tree.status == "optimal"
    copy = TaskTree(goal, tree.method, "feasible", list(tree.units), dict(tree.cost), **tree.optional())
    settle(problem, copy, ("units",), [len(tree.units)])
    assert copy.status == "optimal" and copy.gap == 0.0 and copy.stats["proof"] == "lower bound"
    # a lexicographic level below an open level has only the trivial bound
    lex = TaskTree(goal, tree.method, "feasible", list(tree.units), measures(problem, goal, list(tree.units)))
    settle(problem, lex, ("success", "units"), [0, 5])
    assert lex.bound == {"success": 1.0, "units": 0} and lex.status == "feasible"


def test_batch_rows_and_compare_carry_the_bound(tmp_path, hard):
    out = tmp_path / "r.jsonl"
    res = CliRunner().invoke(main, ["batch", "--data", "demo", "--goals", "all", "-o", str(out), "--no-progress"])
    assert res.exit_code in (0, 1), res.output
    rows = [json.loads(line) for line in out.read_text().splitlines() if line.startswith("{") and '"method"' in line]
    assert rows and all(
        r["bound"]["units"] == r["cost"]["units"] and r["gap"] == 0.0 for r in rows if r["status"] == "optimal"
    )
    # compare's table shows the lower bound of a tree cut short
    from foon2asp.report.tables import units_cell

    problem, goals = hard
    (short,) = solve_goals(problem, [goals[16]], "asp", AspOptions(time_limit=0.05))
    short.valid = True
    if short.status == "feasible":
        assert units_cell(short) == f"{len(short.units)} feasible (>= {short.bound['units']})"


def test_depth_first_answers_cut_short_are_bounded_by_the_refuted_depths(hard):
    problem, goals = hard
    goal = goals[8]
    (short,) = solve_goals(problem, [goal], "asp", AspOptions(objective=("depth", "success"), time_limit=0.5))
    (full,) = solve_goals(problem, [goal], "asp", AspOptions(objective=("depth",)))
    assert full.status == "optimal" and full.bound["depth"] == full.cost["depth"]
    assert short.status in ("feasible", "optimal") and validate(problem, goal, short.units).valid
    assert 1 <= short.bound["depth"] <= full.cost["depth"] <= short.cost["depth"]
