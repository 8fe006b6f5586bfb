"""Reading data files (foon2asp.foon.reading): JSON limits, characters and encodings, each a one-line error naming file, line and column."""

from __future__ import annotations

import pytest

from helpers import demo_copy, one_line_error
from helpers import run_cli as run


@pytest.mark.parametrize("name", ["kitchen.json", "goal_nodes.json"])
def test_deeply_nested_json_is_one_located_error(tmp_path, name):
    d = demo_copy(tmp_path)
    (d / name).write_text("[" * 5000 + "]" * 5000)
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert f"{name}:1:101: JSON nested deeper than 100 levels" in msg


def test_huge_number_is_one_located_error(tmp_path):
    d = demo_copy(tmp_path)
    (d / "goal_nodes.json").write_text('[\n {"label": "x", "states": [], "n": ' + "9" * 5000 + "}]")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert "goal_nodes.json:2:" in msg and "number longer than 100 characters" in msg


@pytest.mark.parametrize("head", ['{"functional_units": [], "n": ', '[{"motion_node": "mix", "n": '])
def test_huge_number_in_a_foon_json_is_one_located_error(tmp_path, head):
    foon = tmp_path / "FOON.json"
    foon.write_text(head + "9" * 5000 + "}" + ("]" if head[0] == "[" else ""))
    msg = one_line_error(run("merge", foon, "-o", tmp_path / "out.txt"))
    assert msg == f"foon2asp: error: {foon}:1:{len(head) + 1}: number longer than 100 characters"


def test_deep_tree_json_in_check(tmp_path):
    tree = tmp_path / "t.json"
    tree.write_text('{"units": ' + "[" * 5000 + "]" * 5000 + "}")
    msg = one_line_error(run("check", tree, "--no-optimum"))
    assert "t.json:1:" in msg and "nested deeper" in msg


def test_lone_surrogate_in_tree_json(tmp_path):
    tree = tmp_path / "t.json"
    tree.write_text('{"goal": {"label": "tom\\ud800ato"}, "units": []}')
    msg = one_line_error(run("check", tree, "--no-optimum"))
    assert "t.json:1:20: string holds U+D800 (lone surrogate)" in msg


@pytest.mark.parametrize("escape, char", [("\\b", "U+0008"), ("\\f", "U+000C")])
def test_an_escaped_control_character_in_a_json_string_is_refused(tmp_path, escape, char):
    d = demo_copy(tmp_path)
    (d / "kitchen.json").write_text('[\n {"label": "egg' + escape + 'x"}]')
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert f"kitchen.json:2:12: string holds {char} (control character)" in msg


@pytest.mark.parametrize(
    "label, where, char", [("egg\\u0000x", "1:57", "U+0000 (NUL)"), ("egg\x85x", "1:61", "U+0085")]
)
def test_a_bad_character_in_a_foon_json_label_is_refused(tmp_path, label, where, char):
    """As in FOON text: a label merge would write but could not read back is refused."""
    foon = tmp_path / "FOON.json"
    node = '{"object_label": "%s", "object_states": []}'
    unit = '{"input_nodes": [%s], "motion_node": {"motion_label": "crack"}, "output_nodes": [%s]}'
    foon.write_text('{"functional_units": [' + unit % (node % label, node % "egg") + "]}")
    msg = one_line_error(run("merge", foon, "-o", tmp_path / "out.txt"))
    assert msg.startswith(f"foon2asp: error: {foon}:{where}: ") and char in msg


def test_nul_in_a_foon_label_is_refused_with_line_and_column(tmp_path):
    d = demo_copy(tmp_path)
    lines = (d / "FOON.txt").read_text().splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith("O"))
    lines[i] = lines[i][:3] + "\0" + lines[i][3:]
    (d / "FOON.txt").write_text("\n".join(lines) + "\n")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert f"FOON.txt:{i + 1}:4: U+0000 (NUL) is not allowed" in msg


@pytest.mark.parametrize("char", ["\x0b", "\x85", "\u2028", "\x1b"])
def test_control_characters_are_refused_and_escaped(tmp_path, char):
    d = demo_copy(tmp_path)
    (d / "utensils.txt").write_text("knife\nbo" + char + "wl\n", encoding="utf-8")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert "utensils.txt:2:3:" in msg
    assert char not in msg  # shown escaped, never raw


def test_not_utf8_names_line_and_byte(tmp_path):
    d = demo_copy(tmp_path)
    (d / "motion.txt").write_bytes(b"chop\t0.9\nsl\xffice\t0.8\n")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert "motion.txt:2:3: not UTF-8 text: byte 0xff" in msg


def test_bom_and_crlf_are_read(tmp_path):
    d = demo_copy(tmp_path)
    text = (d / "FOON.txt").read_text()
    (d / "FOON.txt").write_bytes(b"\xef\xbb\xbf" + text.replace("\n", "\r\n").encode())
    res = run("solve", "--data", d, "--goal", "tomato salad")
    assert res.exit_code == 0, res.stderr
    assert "units 4" in res.output


@pytest.mark.parametrize(
    "name, text, said, unsaid",
    [
        # a plain comment is no warning; one that looks like a label is
        ("utensils.txt", "# utensils\n#mixing bowl\nknife\n", "utensils.txt:2: line ignored", "utensils.txt:1"),
        ("motion.txt", "# nothing here\n", "no success rate in the file", None),
    ],
)
def test_data_file_lines_without_data_are_warned(tmp_path, name, text, said, unsaid):
    d = demo_copy(tmp_path)
    (d / name).write_text(text)
    res = run("solve", "--data", d, "--goal", "tomato salad")
    assert res.exit_code == 0
    assert said in res.stderr
    assert unsaid is None or unsaid not in res.stderr


def test_empty_goals_file_is_named(tmp_path):
    goals = tmp_path / "g.json"
    goals.write_text("[]")
    msg = one_line_error(run("solve", "--goals", goals))
    assert f"{goals}: the goals file lists no goal" in msg
