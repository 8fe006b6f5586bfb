"""What the search baselines' trees look like in every output: text says INVALID and never None."""

from __future__ import annotations

import json

from click.testing import CliRunner

from foon2asp.cli.main import main


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_text_of_an_invalid_greedy_tree_says_invalid():
    res = cli("solve", "--data", "demo", "--goal", "scrambled egg", "--method", "gbfs-h1")
    assert res.exit_code == 1  # an invalid tree
    lines = res.stdout.splitlines()
    assert lines[1] == "Method: gbfs-h1  Status: found  (units 4, success 0.1458, inputs 8, depth -)"
    assert lines[2] == (
        "INVALID: circular support: [egg, beaten, in [bowl]] is made by unit 8 (pour), which needs"
        " [egg, beaten, in [jar]]; [egg, beaten, in [jar]] is made by unit 9 (pour), which needs [egg, beaten, in [bowl]]"
    )
    assert "None" not in res.stdout
    valid = cli("solve", "--data", "demo", "--goal", "tomato salad", "--method", "gbfs-h1")
    assert valid.exit_code == 0 and "INVALID" not in valid.stdout and "None" not in valid.stdout


def test_text_and_json_agree_on_every_shared_goal(shared_foon_dir):
    for method in ("gbfs-h1", "gbfs-h2"):
        args = ("solve", "--data", shared_foon_dir, "--goals", "all", "--method", method)
        answers = json.loads(cli(*args, "--format", "json").stdout)
        text = cli(*args).stdout
        assert "None" not in text
        invalid = [a for a in answers if a.get("valid") is False]
        assert invalid  # the greedy trees for whipped cream and fried rice, at least
        assert text.count("\nINVALID: ") == len(invalid)
        for a in invalid:
            assert f"\nINVALID: {a['problem']}\n" in text
