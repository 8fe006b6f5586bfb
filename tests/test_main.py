"""The command line's entry (foon2asp.cli.main): bad option values, output paths and internal errors as one line each."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from foon2asp.cli.main import main
from helpers import DEMO, one_line_error
from helpers import run_cli as run


@pytest.mark.parametrize(
    "args, option",
    [
        (["solve", "--goal", "tomato salad", "--max-depth", "2147483648"], "--max-depth"),
        (["solve", "--goal", "tomato salad", "--max-units", "2147483648"], "--max-units"),
        (["solve", "--goal", "tomato salad", "--time-limit", "nan"], "--time-limit"),
        (["solve", "--goal", "tomato salad", "--time-limit", "-1"], "--time-limit"),
        (["solve", "--goal", "tomato salad", "--time-limit", "inf"], "--time-limit"),
        (["batch", "--goals", "all", "--scheduler", "nonsense here"], "--scheduler"),
        (["batch", "--goals", "all", "--scheduler", "tcp://host:99999"], "--scheduler"),
    ],
)
def test_bad_options_are_one_line_naming_the_option(args, option):
    msg = one_line_error(run(*args))
    assert option in msg


def test_max_units_at_the_32_bit_limit_is_not_unreachable():
    res = run("solve", "--goal", "tomato salad", "--max-units", str(2**31 - 1))
    assert res.exit_code == 0, res.stderr
    assert "Status: optimal" in res.output and "units 4" in res.output


def test_output_folders_are_created(tmp_path):
    target = tmp_path / "new" / "deeper" / "x.lp"
    res = run("facts", "-o", target)
    assert res.exit_code == 0, res.stderr
    assert target.read_text().startswith("%") or target.stat().st_size > 0
    merged = tmp_path / "m" / "x.txt"
    assert run("merge", DEMO / "FOON.txt", "-o", merged).exit_code == 0 and merged.exists()
    out = tmp_path / "trees" / "sub"
    assert run("solve", "--goal", "tomato salad", "--output", out).exit_code == 0
    assert len(list(out.iterdir())) == 1


@pytest.mark.parametrize(
    "args",
    [
        ["solve", "--goal", "tomato salad", "--output", "/proc/version/x"],
        ["facts", "-o", "/proc/version/x.lp"],
        ["merge", str(DEMO / "FOON.txt"), "-o", "/proc/version/x.txt"],
        ["batch", "--goals", "all", "--output", "/proc/version/x.jsonl"],
    ],
)
def test_unwritable_outputs_are_one_line_naming_the_path(args):
    msg = one_line_error(run(*args))
    assert "/proc/version" in msg


def test_internal_error_is_exit_3_with_traceback_only_under_debug(monkeypatch):
    from foon2asp.foon import goals

    def boom(*a, **k):
        raise ZeroDivisionError("boom")

    monkeypatch.setattr(goals, "resolve", boom)
    msg = one_line_error(run("solve", "--goal", "x"), code=3)
    assert "internal error: ZeroDivisionError: boom" in msg and "please report" in msg
    res = CliRunner().invoke(main, ["--debug", "solve", "--data", "demo", "--goal", "x"])
    assert res.exit_code == 3 and "Traceback" in res.stderr
