"""Outputs that say what they assumed and what they wrote: a tree judged without a kitchen,
the objects a unit really makes, the files of ``solve -o DIR``."""

from __future__ import annotations

import json

from click.testing import CliRunner

from conftest import DEMO
from foon2asp.cli.main import main

SMOOTHIE = DEMO / "llm" / "smoothie-2.json"
CAVEAT = (
    "Note: a missing step cannot be detected without a kitchen: whatever no unit of the tree makes is"
    " assumed to be in the kitchen (give --kitchen FILE, or --data or --foon to check against a FOON)"
)


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


# ---------------------------------------------------------------- check without a kitchen


def test_a_tree_alone_lists_the_leaves_it_assumed_and_says_what_it_cannot_see():
    res = cli("check", SMOOTHIE)
    assert res.exit_code == 1  # step 3 cannot fire in the order written
    lines = res.stdout.splitlines()
    assert lines[1] == "Judged on its own: kitchen = its leaves (7 objects)"
    assert lines[2] == (
        "Assumed in the kitchen (its leaves): banana, whole; knife; cutting board; blueberries, fresh;"
        " blender, empty; milk, in [carton]; glass, empty"
    )
    assert lines[3] == CAVEAT
    (report,) = json.loads(cli("check", SMOOTHIE, "--format", "json").stdout)
    assert report["kitchen_assumed"] is True and report["note"] == CAVEAT.removeprefix("Note: ")
    assert len(report["kitchen"]) == 7


def test_a_missing_step_passes_unseen_without_a_kitchen_and_is_caught_with_one(tmp_path):
    smoothie = DEMO / "llm" / "smoothie-1.json"  # valid on its own
    full = json.loads(cli("check", smoothie, "--format", "json").stdout)[0]
    assert full["valid"] is True
    kitchen = tmp_path / "kitchen.json"
    kitchen.write_text(json.dumps(full["kitchen"]))  # its leaves, as a kitchen of its own
    # drop the first unit (peel): the peeled banana becomes a leaf, so it is taken to be in the kitchen
    path = tmp_path / "no-peel.json"
    path.write_text(json.dumps(json.loads(smoothie.read_text())[1:]))
    (alone,) = json.loads(cli("check", path, "--format", "json").stdout)
    assert alone["valid"] is True  # the missing step is not seen...
    assert {"label": "banana", "states": ["peeled"], "ingredients": [], "container": None} in alone["kitchen"]
    assert alone["kitchen_assumed"] is True and alone["note"] == CAVEAT.removeprefix("Note: ")  # ...and it says so
    given = cli("check", path, "--kitchen", kitchen, "--format", "json")
    assert given.exit_code == 1
    (report,) = json.loads(given.stdout)
    assert report["problem"] == "missing-input" and "banana, peeled" in report["message"]
    assert report["kitchen_assumed"] is False and report["note"] is None
    assert "Note:" not in cli("check", path, "--kitchen", kitchen).stdout


# ---------------------------------------------------------------- objects: made by


def test_a_unit_that_needs_the_object_does_not_make_it():
    # the demo's only unit that outputs "stove, on" (heat) also needs it
    res = cli("objects", "stove", "--data", "demo")
    assert res.exit_code == 0, res.output
    assert res.stdout == "#19  stove, on   (kitchen, only output by 1 unit that needs it)\n"
    (info,) = json.loads(cli("objects", "stove", "--data", "demo", "--format", "json").stdout)
    assert info["producers"] == 0
    made = json.loads(cli("objects", "--data", "demo", "--produced", "--format", "json").stdout)
    assert 19 not in {o["id"] for o in made} and all(o["producers"] > 0 for o in made)
    tomato = cli("objects", "tomato", "--data", "demo").stdout.splitlines()
    assert tomato[1] == "#2  tomato, chopped   (made by 2 units)"


def test_the_fried_rice_packet_is_made_by_no_unit(shared_foon_dir):
    res = cli("objects", "packet, contains {carrot,corn,green pea}", "--data", shared_foon_dir)
    assert res.stdout.endswith("packet, contains {carrot,corn,green pea}   (only output by 1 unit that needs it)\n")


# ---------------------------------------------------------------- solve -o DIR


def test_solve_into_a_folder_prints_one_line_per_file(tmp_path):
    out = tmp_path / "svg"
    res = cli("solve", "--data", "demo", "--goals", "all", "--format", "svg", "-o", out)
    assert res.exit_code == 0, res.output
    assert res.stdout.splitlines() == [
        f"wrote {out / '001-tomato_salad.svg'} (optimal)",
        f"wrote {out / '002-scrambled_egg.svg'} (optimal)",
        f"wrote {out / '003-whipped_cream.svg'} (unreachable)",
        f"wrote {out / '004-pancake.svg'} (unreachable)",
    ]
    assert (out / "001-tomato_salad.svg").read_text().lstrip().startswith("<?xml")


def test_solve_into_a_folder_with_several_methods_and_formats(tmp_path):
    for fmt, ext in (("text", "txt"), ("json", "json"), ("png", "png")):
        out = tmp_path / fmt
        res = cli(
            "solve", "--data", "demo", "--goal", "scrambled egg", "--methods", "asp,gbfs-h1", "--format", fmt, "-o", out
        )
        assert res.exit_code == 1  # the greedy tree is invalid
        assert res.stdout.splitlines() == [
            f"wrote {out / f'001-scrambled_egg-asp.{ext}'} (optimal)",
            f"wrote {out / f'001-scrambled_egg-gbfs-h1.{ext}'} (found, INVALID)",
        ]
        assert len(list(out.iterdir())) == 2
