"""PDDL export and plans read back: parsed by a PDDL parser, mapped to units, checked; Fast Downward agrees."""

from __future__ import annotations

import importlib.util
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from foon2asp.analysis import check as check_mod
from foon2asp.asp.constraints import ConstraintSpec
from foon2asp.asp.facts import neglog_weight
from foon2asp.asp.options import AspOptions
from foon2asp.cli import main
from foon2asp.errors import InputError
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.treefiles import action_name, looks_like_plan, read_trees, unit_of_action
from foon2asp.methods.plan import session_of as Session
from foon2asp.report import pddl


def fast_downward() -> Path | None:
    """The fast-downward.py driver the up-fast-downward wheel ships, if it runs here."""
    spec = importlib.util.find_spec("up_fast_downward")
    if spec is None or not spec.submodule_search_locations:
        return None
    path = Path(list(spec.submodule_search_locations)[0]) / "downward" / "fast-downward.py"
    return path if path.is_file() else None


#: A* with LM-cut and stubborn-set pruning: optimal, and fast on these delete-free problems
#: (plain astar(lmcut()) does not finish beef stroganoff in minutes)
FD_SEARCH = "astar(lmcut(),pruning=stubborn_sets_simple())"


def run_fd(tmp: Path) -> tuple[str, int]:
    fd = fast_downward()
    if fd is None:
        pytest.skip("Fast Downward is not installed (pip install up-fast-downward)")
    try:
        subprocess.run(
            [sys.executable, str(fd), "domain.pddl", "problem.pddl", "--search", FD_SEARCH],
            cwd=tmp,
            capture_output=True,
            text=True,
            timeout=240,
        )
    except (OSError, subprocess.TimeoutExpired) as exc:
        pytest.skip(f"Fast Downward did not run here: {exc}")
    plan = tmp / "sas_plan"
    if not plan.is_file():
        pytest.skip("Fast Downward wrote no plan (not runnable here?)")
    text = plan.read_text()
    m = re.search(r"cost = (\d+)", text)
    assert m, text
    return text, int(m.group(1))


def write(tmp: Path, task: pddl.PddlTask) -> None:
    (tmp / "domain.pddl").write_text(task.domain)
    (tmp / "problem.pddl").write_text(task.problem)


def resolve(data, p, *labels):
    return tuple(goals_mod.resolve_label(data, p, lab) for lab in labels)


def test_action_names_map_back(demo_problem):
    _, p = demo_problem
    for u in range(len(p.units)):
        name = action_name(p, u)
        assert re.fullmatch(r"u\d+-[a-z0-9-]+", name) and unit_of_action(name) == u
    assert unit_of_action("pick-up") is None


def test_export_parses_as_pddl_and_maps_to_units(shared_problem, tmp_path):
    parser = pytest.importorskip("pddl")
    data, p = shared_problem
    meal = resolve(data, p, "carrot salad", "coleslaw")
    for objective in ("units", "success"):
        task = pddl.export(p, meal, objective)
        write(tmp_path, task)
        domain = parser.parse_domain(tmp_path / "domain.pddl")
        problem = parser.parse_problem(tmp_path / "problem.pddl")
        names = {a.name for a in domain.actions}
        assert names == set(task.actions)
        assert {unit_of_action(n) for n in names} == set(p.units_for(meal))
        assert len(list(problem.goal.operands)) == 2
        if objective == "success":
            assert ":action-costs" in task.domain and "(:metric minimize (total-cost))" in task.problem
        # the optimal tree's units, in executable order, are a plan that checks as valid
        tree = Session(p, AspOptions(units=p.units_for(meal))).solve(meal)
        assert set(tree.units) <= {unit_of_action(n) for n in names}
        plan = "".join(f"({action_name(p, u)})\n" for u in tree.units) + f"; cost = {len(tree.units)} (unit cost)\n"
        (tmp_path / "plan").write_text(plan)
        plans = read_trees(tmp_path / "plan", p)
        (report,) = check_mod.check_trees(data, p, plans, ("carrot salad", "coleslaw"))
        assert report.valid and report.goals == meal
        assert report.cost["units"] == len(tree.units) == 33


def test_forbid_filters_actions(shared_problem):
    data, p = shared_problem
    (g,) = resolve(data, p, "macaroni")
    task = pddl.export(p, [g], spec=ConstraintSpec(forbid_motion=("heat",)))
    assert task.actions and not any(p.units[u].motion == "heat" for u in task.actions.values())
    # the same optimum as the solver under the same constraint
    spec = ConstraintSpec(forbid_motion=("heat",))
    tree = Session(p, AspOptions(programs=spec.programs())).solve(g)
    assert set(tree.units) <= set(task.actions.values())
    with pytest.raises(InputError, match="--rule"):
        pddl.export(p, [g], spec=ConstraintSpec(rules=(":- use(1).",)))
    with pytest.raises(InputError, match="depth"):
        pddl.export(p, [g], "depth")


def test_plan_reading_and_check_cli(shared_foon_dir, shared_problem, tmp_path):
    data, p = shared_problem
    out = CliRunner().invoke(
        main, ["export", "pddl", "--data", str(shared_foon_dir), "--goal", "macaroni", "-o", str(tmp_path)]
    )
    assert out.exit_code == 0, out.output
    assert (tmp_path / "domain.pddl").is_file() and (tmp_path / "problem.pddl").is_file()
    (g,) = resolve(data, p, "macaroni")
    tree = Session(p).solve(g)
    good = "".join(f"({action_name(p, u)} )\n" for u in tree.units) + "; cost = 5 (unit cost)\n"
    (tmp_path / "good.plan").write_text(good)
    (plan,) = read_trees(tmp_path / "good.plan", p)
    assert looks_like_plan(good) and plan.method == "plan, reported cost 5"
    res = CliRunner().invoke(
        main, ["check", str(tmp_path / "good.plan"), "--data", str(shared_foon_dir), "--goal", "macaroni"]
    )
    assert res.exit_code == 0, res.output
    assert "Verdict: VALID" in res.stdout and "this tree is the optimum" in res.stdout
    # the last step dropped: the goal is not made; an unknown action is named with its line
    bad = "".join(f"({action_name(p, u)})\n" for u in tree.units[:-1])
    (tmp_path / "bad.plan").write_text(bad)
    res = CliRunner().invoke(
        main,
        ["check", str(tmp_path / "bad.plan"), "--data", str(shared_foon_dir), "--goal", "macaroni", "--format", "json"],
    )
    assert res.exit_code == 1
    (rep,) = json.loads(res.stdout)
    assert rep["valid"] is False and rep["problem"] == "goal-not-made" and rep["optimum"]["cost"]["units"] == 5
    (tmp_path / "odd.plan").write_text("(u999999-fly)\n")
    res = CliRunner().invoke(
        main, ["check", str(tmp_path / "odd.plan"), "--data", str(shared_foon_dir), "--goal", "macaroni"]
    )
    assert res.exit_code == 1 and "unknown unit" in res.stdout and "odd.plan:1" in res.stdout


@pytest.mark.parametrize(
    "labels,objective",
    [
        (("macaroni",), "units"),
        (("vinaigrette",), "units"),
        (("greek salad",), "units"),
        (("greek salad",), "success"),
        (("carrot salad", "coleslaw"), "success"),
        (("shrimp mango salad", "vinaigrette"), "units"),
        (("carrot salad", "coleslaw"), "units"),
        (("beef stroganoff",), "units"),
    ],
)
def test_fast_downward_optimum_equals_solve(shared_foon_dir, shared_problem, tmp_path, labels, objective):
    data, p = shared_problem
    meal = resolve(data, p, *labels)
    write(tmp_path, pddl.export(p, meal, objective))
    plan, cost = run_fd(tmp_path)
    tree = Session(p, AspOptions(objective=(objective,), units=p.units_for(meal))).solve(meal)
    assert tree.status == "optimal"
    expected = len(tree.units) if objective == "units" else sum(neglog_weight(p.rates[u]) for u in tree.units)
    assert cost == expected
    # the planner's plan checks as valid, its size beside the optimum
    goal_args = [x for lab in labels for x in ("--goal", lab)]
    res = CliRunner().invoke(main, ["check", str(tmp_path / "sas_plan"), "--data", str(shared_foon_dir), *goal_args])
    assert res.exit_code == 0, res.output
    assert "Verdict: VALID" in res.stdout
    if objective == "units":
        assert "this tree is the optimum" in res.stdout
