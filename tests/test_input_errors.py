"""Input that would mislead: each is one line naming the file (and line) or the option, exit
status 2 -- or, when the input is usable but means something the user may not expect, one
warning saying what it means."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from foon2asp import api
from foon2asp.api.request import Options
from foon2asp.cli.main import main
from foon2asp.errors import InputError
from foon2asp.foon.parser import parse_lines
from helpers import DEMO, demo_copy, one_line_error

#: a unit whose output object is in a container, the state line (line 8) filled in by a test
UNIT = "O\ttomato\nS\twhole\nO\tbowl\nS\tempty\nM\tpour\nO\ttomato\nS\tchopped\n{state}\n//\n"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def warnings_of(res) -> list[str]:
    return [line for line in res.stderr.splitlines() if line.startswith("foon2asp: warning: ")]


def small_data(tmp_path: Path, state: str) -> Path:
    d = tmp_path / "small"
    d.mkdir()
    (d / "FOON.txt").write_text(UNIT.format(state=state))
    (d / "kitchen.json").write_text(
        '[{"label": "tomato", "states": ["whole"]}, {"label": "bowl", "states": ["empty"]}]'
    )
    (d / "motion.txt").write_text("pour\t0.9\n")
    return d


# ---- brackets in state lines --------------------------------------------------------


@pytest.mark.parametrize(
    "state, column, words",
    [
        ("S\tin\t[bowl", 6, "unbalanced '[' (no ']' after it) in the state 'in [bowl'"),
        ("S\tin\tbowl]", 10, "stray ']' (no '[' before it) in the state 'in bowl]'"),
        ("S\tin\t[bowl}", 11, "'[' closed by '}' in the state 'in [bowl}'"),
        ("S\tcontains\t{flour,sugar", 12, "unbalanced '{' (no '}' after it) in the state 'contains {flour,sugar'"),
        ("S\tcontains\tflour}", 17, "stray '}' (no '{' before it)"),
        ("S\ton [plate", 6, "unbalanced '[' (no ']' after it) in the state 'on [plate'"),
        ("S\ton\t[plate", 6, "unbalanced '['"),
        ("S12\tattached to\t[mixer", 17, "unbalanced '[' (no ']' after it) in the state 'attached to [mixer'"),
        ("S\tin\t[[bowl]]", 7, "nested or extra brackets in the state 'in [[bowl]]' ('in' takes one list"),
        ("S\tin\t[bowl] [pan]", 11, "nested or extra brackets in the state 'in [bowl] [pan]'"),
        ("S\tcontains\t{a,{b}}", 15, "nested or extra brackets in the state 'contains {a,{b}}'"),
    ],
)
def test_brackets_that_do_not_pair_up_are_located(state, column, words):
    with pytest.raises(InputError) as err:
        parse_lines(UNIT.format(state=state), "f.txt")
    assert (err.value.path, err.value.line, err.value.column) == ("f.txt", 8, column)
    assert str(err.value).startswith(f"f.txt:8:{column}: {words}")


def test_unbalanced_container_is_an_error_not_an_unreachable_goal(tmp_path):
    """``in [bowl`` once became the container ``[bowl`` and the goal was 'proven' unreachable."""
    d = small_data(tmp_path, "S\tin\t[bowl")
    msg = one_line_error(run("solve", "--data", d, "--goal", "tomato, chopped, in [bowl]"))
    assert msg == f"foon2asp: error: {d / 'FOON.txt'}:8:6: unbalanced '[' (no ']' after it) in the state 'in [bowl'"


@pytest.mark.parametrize(
    "state, container, states",
    [
        ("S\tin\t[bowl]", "bowl", ("chopped",)),
        ("S\tin\t{bowl}", "bowl", ("chopped",)),
        ("S\tin\tbowl", "bowl", ("chopped",)),
        ("S7\tin\t [bowl] ", "bowl", ("chopped",)),
        ("S\tunder [cooking pan]", None, ("chopped", "under [cooking pan]")),
        ("S\tattached to\t[mixer]", None, ("attached to [mixer]", "chopped")),
        ("S\tcoated\t[olive oil,salt]", None, ("chopped", "coated [olive oil,salt]")),
        ("S\tbarbecued\t{salt,garlic}", None, ("barbecued {salt,garlic}", "chopped")),
    ],
)
def test_brackets_that_pair_up_are_read(state, container, states):
    foon = parse_lines(UNIT.format(state=state), "f.txt")
    (out,) = foon.units[0].outputs
    assert (out.container, out.states) == (container, states)


def test_ingredients_in_braces_are_read():
    foon = parse_lines(UNIT.format(state="S\tcontains\t{flour, sugar}"), "f.txt")
    assert foon.units[0].outputs[0].ingredients == ("flour", "sugar")


# ---- the FOON file itself ----------------------------------------------------------


def test_mistyped_foon_path_names_the_foon_file(tmp_path):
    missing = tmp_path / "nope" / "FOON.txt"
    msg = one_line_error(run("solve", "--foon", missing, "--goal", "tomato salad"))
    assert msg == f"foon2asp: error: {missing}: FOON file not found"
    with pytest.raises(InputError, match="FOON file not found"):
        api.load(foon=missing)


@pytest.mark.parametrize("how", ["--data", "--foon"])
def test_foon_file_that_is_a_directory_is_said_to_be_one(tmp_path, how):
    d = demo_copy(tmp_path, "FOON.txt")
    (d / "FOON.txt").mkdir()
    msg = one_line_error(run("solve", how, d if how == "--data" else d / "FOON.txt", "--goal", "tomato salad"))
    assert msg == f"foon2asp: error: {d / 'FOON.txt'}: FOON file is a directory, not a file"


@pytest.mark.parametrize(
    "name, what", [("FOON.txt", "FOON"), ("kitchen.json", "kitchen"), ("goal_nodes.json", "goals")]
)
def test_a_data_file_that_is_a_broken_link_is_named_as_one(tmp_path, name, what):
    d = demo_copy(tmp_path, name)
    (d / name).symlink_to(tmp_path / "moved" / name)
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert msg == f"foon2asp: error: {d / name}: {what} file is a broken link (to {tmp_path / 'moved' / name})"


def test_a_goals_file_given_as_a_broken_link_is_named_as_one(tmp_path):
    (tmp_path / "goals.json").symlink_to("elsewhere.json")
    msg = one_line_error(run("solve", "--data", "demo", "--goals", tmp_path / "goals.json"))
    assert msg == f"foon2asp: error: {tmp_path / 'goals.json'}: goals file is a broken link (to elsewhere.json)"


def test_a_missing_goals_file_names_the_path_looked_for(tmp_path):
    d = demo_copy(tmp_path, "goal_nodes.json")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert msg == (
        f"foon2asp: error: --goals all needs a goals file, and there is no {d / 'goal_nodes.json'} (give --goals FILE)"
    )
    res = run("solve", "--foon", d / "FOON.txt")
    assert res.exit_code == 2
    assert f"error: no goal given and no goals file (there is no {d / 'goal_nodes.json'})" in res.stderr
    with pytest.raises(InputError, match="there is no .*goal_nodes.json"):
        api.load(d).select_goals((), "all")


@pytest.mark.parametrize("command", ["solve", "objects"])
def test_a_data_folder_without_a_kitchen_says_how_to_go_without(tmp_path, command):
    d = demo_copy(tmp_path, "kitchen.json")
    msg = one_line_error(run(command, "--data", d, *(["--goal", "tomato salad"] if command == "solve" else [])))
    flag = "--kitchen" if command == "solve" else "--kitchen-file"
    assert msg.startswith(f"foon2asp: error: {d / 'kitchen.json'}: kitchen file not found in the data folder;")
    assert f"{flag} leaves (every object no unit makes" in msg
    res = run(command, "--data", d, flag, "leaves", *(["--goal", "tomato salad"] if command == "solve" else []))
    assert res.exit_code == 0, res.output


def test_data_directory_that_is_a_file_is_said_to_be_one(tmp_path):
    f = tmp_path / "FOON.txt"
    f.write_text(UNIT.format(state="S\tin\t[bowl]"))
    msg = one_line_error(run("solve", "--data", f, "--goal", "tomato"))
    assert msg == f"foon2asp: error: {f}: data directory is a file, not a directory"


@pytest.mark.parametrize("text", ["", "# only a comment\n//\n", "\n\n"])
def test_foon_file_without_units_is_named_not_the_goals_file(tmp_path, text):
    d = demo_copy(tmp_path)
    (d / "FOON.txt").write_text(text)
    msg = one_line_error(run("solve", "--data", d))
    assert msg == f"foon2asp: error: {d / 'FOON.txt'}: FOON file has no functional units"
    assert "goal_nodes.json" not in msg


def test_foon_file_whose_units_are_all_skipped_says_so(tmp_path):
    d = demo_copy(tmp_path)
    (d / "FOON.txt").write_text("//\nO\tegg\nS\twhole\nO\tegg\nS\tcracked\n//\n")
    msg = one_line_error(run("solve", "--data", d))
    assert msg.startswith(f"foon2asp: error: {d / 'FOON.txt'}: FOON file has no functional units (1 skipped, first: ")
    assert "has no motion (M) line" in msg


# ---- motion.txt -------------------------------------------------------------------


def test_comment_lines_in_motion_file_are_skipped_without_a_warning(tmp_path):
    d = demo_copy(tmp_path)
    rates = (DEMO / "motion.txt").read_text()
    (d / "motion.txt").write_text("# success rates\n  # measured\n#\n" + rates + "# the end\n")
    res = run("solve", "--data", d, "--goal", "tomato salad")
    assert res.exit_code == 0, res.stderr
    assert warnings_of(res) == []
    assert "success 0.0216" in res.output  # the rates were read: chop 0.1 ... (0.5 each would differ)


def test_missing_motion_file_in_data_directory_is_warned_once(tmp_path):
    d = demo_copy(tmp_path, "motion.txt")
    res = run("solve", "--data", d, "--goal", "tomato salad")
    assert res.exit_code == 0, res.stderr
    assert warnings_of(res) == [
        f"foon2asp: warning: {d / 'motion.txt'}: no such file in the data directory:"
        " every motion gets the default success rate 0.5"
    ]
    kb = api.load(d)
    assert [w for w in kb.warnings if "motion.txt" in w] == [
        f"{d / 'motion.txt'}: no such file in the data directory: every motion gets the default success rate 0.5"
    ]


@pytest.mark.parametrize("text", ["", "# no rates yet\n"])
def test_empty_motion_file_is_warned_once(tmp_path, text):
    d = demo_copy(tmp_path)
    (d / "motion.txt").write_text(text)
    res = run("solve", "--data", d, "--goal", "tomato salad")
    assert res.exit_code == 0, res.stderr
    assert warnings_of(res) == [
        f"foon2asp: warning: {d / 'motion.txt'}: no success rate in the file:"
        " every motion gets the default success rate 0.5"
    ]


# ---- the kitchen --------------------------------------------------------------------


def test_empty_kitchen_is_warned_about(tmp_path):
    d = demo_copy(tmp_path)
    (d / "kitchen.json").write_text("[]")
    res = run("solve", "--data", d, "--goal", "tomato salad")
    assert res.exit_code == 0, res.stderr
    assert "Status: unreachable" in res.output
    assert warnings_of(res) == [
        f"foon2asp: warning: {d / 'kitchen.json'}: the kitchen is empty: no unit can start,"
        " so every goal is unreachable"
    ]


def test_empty_leaves_kitchen_is_warned_about(tmp_path):
    foon = tmp_path / "loop.txt"
    foon.write_text("O\ta\nS\tx\nM\tm\nO\tb\nS\ty\n//\nO\tb\nS\ty\nM\tm\nO\ta\nS\tx\n//\n")
    kb = api.load(foon=foon, kitchen="leaves", motion=DEMO / "motion.txt", utensils=DEMO / "utensils.txt")
    assert (
        "the kitchen is empty (every object of the FOON is made by some unit): no unit can start,"
        " so every goal is unreachable"
    ) in kb.warnings


def test_kitchen_with_items_is_not_warned_about():
    assert not any("kitchen is empty" in w for w in api.load("demo").warnings)


# ---- the time limit -----------------------------------------------------------------


@pytest.mark.parametrize("value", ["0", "0.0", "-1", "nan", "inf"])
def test_time_limit_must_be_positive_on_the_command_line(value):
    msg = one_line_error(run("solve", "--data", "demo", "--goal", "tomato salad", "--time-limit", value))
    assert f"Invalid value for '--time-limit': '{value}' is not a finite number of seconds > 0" in msg


@pytest.mark.parametrize("value", [0, 0.0, -1, math.nan, math.inf, -math.inf])
def test_the_library_refuses_the_time_limits_the_command_line_refuses(value):
    with pytest.raises(InputError) as err:
        Options.of(time_limit=value)
    assert str(err.value) == f"time_limit: {value!r} is not a finite number of seconds > 0 (None: the default)"
    with pytest.raises(InputError, match="is not a finite number of seconds > 0"):
        Options(time_limit=value)
    with pytest.raises(InputError, match="is not a finite number of seconds > 0"):
        api.load("demo").solve("tomato salad", time_limit=value)


@pytest.mark.parametrize("value", [True, "10"])
def test_the_library_refuses_a_time_limit_that_is_no_number(value):
    with pytest.raises(InputError, match="is not a number of seconds"):
        Options.of(time_limit=value)


def test_the_library_takes_a_positive_time_limit_or_none():
    assert Options.of(time_limit=2).time_limit == 2
    assert Options.of(time_limit=0.5).time_limit == 0.5
    assert Options.of(time_limit=None).time_limit is None


def test_misspelt_keyword_suggests_the_closest():
    with pytest.raises(TypeError) as err:
        Options.of(time_limt=5)  # type: ignore[call-arg]
    assert str(err.value) == "unexpected keyword argument 'time_limt' (did you mean 'time_limit'?)"
    with pytest.raises(TypeError, match=r"'forbid_motion' \(did you mean 'forbid_motions'\?\)"):
        api.load("demo").solve("tomato salad", forbid_motion=["chop"])  # type: ignore[call-arg]
    with pytest.raises(
        TypeError, match=r"Options\(\): unexpected keyword argument 'objectve' \(did you mean 'objective'"
    ):
        Options(objectve="success")  # type: ignore[call-arg]


def test_unknown_keyword_without_a_close_one_lists_the_keywords():
    with pytest.raises(TypeError) as err:
        Options.of(zzz=1)  # type: ignore[call-arg]
    assert str(err.value).startswith("unexpected keyword argument 'zzz'; the keywords are all_optimal, ")
    assert "time_limit" in str(err.value)


def test_a_foon_json_nested_too_deeply_is_named(tmp_path):
    """Deep nesting reaches Python's recursion limit while decoding: the library and the command
    line both name the file, in one line."""
    foon = tmp_path / "FOON.json"
    foon.write_text("[" * 100_000 + "]" * 100_000)
    kitchen = tmp_path / "kitchen.json"
    kitchen.write_text('[{"label": "egg"}]')
    with pytest.raises(InputError, match="JSON nested too deeply") as err:
        api.load(foon=str(foon), kitchen=str(kitchen))
    assert err.value.path == str(foon)
    res = CliRunner().invoke(main, ["objects", "--foon", str(foon), "--kitchen", str(kitchen)])
    assert one_line_error(res) == f"foon2asp: error: {foon}: JSON nested too deeply"


# ---- what messages echo ---------------------------------------------------------------


def test_a_huge_label_is_echoed_clipped(tmp_path):
    goals = tmp_path / "goals.json"
    goals.write_text(json.dumps([{"label": "x" * 1_000_000, "states": ["y"]}]))
    msg = one_line_error(run("solve", "--data", "demo", "--goals", goals))
    assert msg == f"foon2asp: error: {goals}:1: goal {'x' * 200}... is not an object of the FOON"
    msg = one_line_error(run("solve", "--data", "demo", "--goal", "x" * 100_000))
    assert msg == f"foon2asp: error: no goal or FOON object labelled '{'x' * 200}...'"


@pytest.mark.parametrize("char", ["\u202e", "\u2066", "\u200b", "\u200f", "\ufeff", "\u00ad"])
def test_invisible_and_bidi_characters_are_shown_escaped(tmp_path, char):
    goals = tmp_path / "goals.json"
    goals.write_text(json.dumps([{"label": f"egg{char}abc", "states": ["y"]}], ensure_ascii=False))
    shown = repr(char)[1:-1]  # the escape Python writes
    msg = one_line_error(run("solve", "--data", "demo", "--goals", goals))
    assert msg == f"foon2asp: error: {goals}:1: goal egg{shown}abc, y is not an object of the FOON; closest labels: egg"
    msg = one_line_error(run("solve", "--data", "demo", "--goal", f"egg{char}abc"))
    assert f"labelled 'egg{shown}abc'" in msg and char not in msg


def test_every_message_is_one_clipped_line():
    err = InputError("no such thing: " + "y" * 10_000 + "\u202e", "x" * 1000, 3)
    text = str(err)
    assert len(text) == len("x" * 200 + "...:3: ") + 2000 + len("...") and text.endswith("y...") and "\n" not in text
    assert text.startswith("x" * 200 + "...:3: no such thing: y")
