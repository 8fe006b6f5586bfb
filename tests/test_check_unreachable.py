"""``check`` on foon2asp's own answers for unreachable goals: no tree to check, confirmed by the FOON."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from conftest import DEMO
from foon2asp.cli.main import main

UNREACHABLE = (
    "Verdict: unreachable: no tree to check (confirmed: the goal is not derivable from the kitchen"
    " with any units of the FOON)"
)


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def solved(tmp_path, data, fmt):
    res = cli("solve", "--data", data, "--goals", "all", "--format", fmt)
    assert res.exit_code == 0, res.output
    path = tmp_path / f"trees.{fmt}"
    path.write_text(res.stdout)
    return path


@pytest.fixture(params=["demo", "shared"])
def data(request):
    if request.param == "demo":
        return "demo", 4, 2
    return request.getfixturevalue("shared_foon_dir"), 25, 2  # whipped cream and fried rice


@pytest.mark.parametrize("fmt", ["json", "foon"])
def test_round_trip_solve_check(tmp_path, data, fmt):
    folder, n, gone = data
    path = solved(tmp_path, folder, fmt)
    res = cli("check", path, "--data", folder)
    assert res.exit_code == 0, res.output
    assert res.stdout.count(UNREACHABLE) == gone
    assert "INVALID" not in res.stdout
    assert (
        res.stdout.splitlines()[-1]
        == f"Checked {n} trees: {n - gone} valid, 0 invalid, {gone} unreachable (no tree to check)"
    )
    # an unreachable answer has no size: no 'success 1' for a tree that is not there
    assert "Size: 0 units" not in res.stdout
    js = cli("check", path, "--data", folder, "--format", "json", "--no-optimum")
    assert js.exit_code == 0, js.output
    reports = json.loads(js.stdout)
    assert len(reports) == n
    gone_reports = [r for r in reports if r["problem"] == "unreachable"]
    assert len(gone_reports) == gone
    assert all(r["valid"] is None and r["message"].startswith("unreachable: no tree to check") for r in gone_reports)
    assert all(r["valid"] is True for r in reports if r not in gone_reports)


@pytest.mark.parametrize("fmt", ["json", "foon"])
def test_round_trip_through_an_output_folder(tmp_path, fmt):
    out = tmp_path / "trees"
    res = cli("solve", "--data", "demo", "--goals", "all", "--format", fmt, "-o", out)
    assert res.exit_code == 0, res.output
    files = sorted(out.iterdir())
    assert len(files) == 4
    res = cli("check", *files, "--data", DEMO, "--no-optimum")
    assert res.exit_code == 0, res.output
    assert res.stdout.count(UNREACHABLE) == 2
    assert res.stdout.splitlines()[-1] == "Checked 4 trees: 2 valid, 0 invalid, 2 unreachable (no tree to check)"
    # one file, one tree: no count at the end
    one = cli("check", files[2], "--data", DEMO, "--no-optimum")
    assert one.exit_code == 0 and "whipped cream" in one.stdout and UNREACHABLE in one.stdout
    assert "Checked" not in one.stdout


def test_no_units_for_a_reachable_goal_is_invalid(tmp_path):
    answers = json.loads(cli("solve", "--data", "demo", "--goals", "all", "--format", "json").stdout)
    answers[0].update(status="unknown", units=[], cost={})  # tomato salad, as a time limit would leave it
    path = tmp_path / "cut.json"
    path.write_text(json.dumps(answers))
    res = cli("check", path, "--data", DEMO, "--no-optimum")
    assert res.exit_code == 1
    assert (
        "Verdict: INVALID\nProblem: no tree to check, but the goal is derivable from the kitchen:"
        " the file gives no units for it\n"
    ) in res.stdout
    assert res.stdout.splitlines()[-1] == "Checked 4 trees: 1 valid, 1 invalid, 2 unreachable (no tree to check)"
    (first, *_) = json.loads(cli("check", path, "--data", DEMO, "--format", "json", "--no-optimum").stdout)
    assert first["valid"] is False and first["problem"] == "no-tree"


def test_a_meal_with_an_unreachable_dish(tmp_path):
    path = tmp_path / "meal.json"
    path.write_text(json.dumps([{"units": []}]))
    res = cli("check", path, "--data", DEMO, "--goal", "tomato salad", "--goal", "whipped cream", "--no-optimum")
    assert res.exit_code == 0, res.output
    assert (
        "Verdict: unreachable: no tree to check (confirmed: whipped cream, whipped, in [mixing bowl]"
        " is not derivable from the kitchen with any units of the FOON)"
    ) in res.stdout
    both = cli("check", path, "--data", DEMO, "--goal", "tomato salad", "--goal", "scrambled egg", "--no-optimum")
    assert (
        both.exit_code == 1
        and "Problem: no tree to check, but tomato salad, mixed, in [bowl] is derivable" in both.stdout
    )
