"""The unit-list JSON form of generated task trees (foon2asp.foon.unitlist): every quirk of
generated files, located warnings and errors, named limits, and round trips."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from foon2asp.analysis.check import read_trees
from foon2asp.errors import BAD_CHAR, InputError
from foon2asp.foon import foonjson
from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.reading import read_text
from foon2asp.foon.unitlist import (
    MAX_ITEMS,
    MAX_TEXT_CHARS,
    dumps,
    is_unit_list,
    to_unit_list,
    unit_list_foon,
)
from helpers import file_error

LLM = Path(__file__).resolve().parent.parent / "data" / "llm"


def node(label, states=(), ingredients=(), container=None):
    return {"label": label, "states": list(states), "ingredients": list(ingredients), "container": container}


PEEL = {
    "input_nodes": [node("banana", ["whole"]), node("knife")],
    "motion_node": "peel",
    "output_nodes": [node("banana", ["peeled"])],
}
PEELED = FoonObject.make("banana", ["peeled"])
WHOLE = FoonObject.make("banana", ["whole"])
KNIFE = FoonObject.make("knife")


def read_unit_list(text, path, strict=False):
    foon = unit_list_foon(text, path, strict)
    return foon.units, foon.warnings


def read_unit_list_file(path, strict=False):
    return read_unit_list(read_text(path, "tree"), str(path), strict)


def read(units, strict=False, path="t.json"):
    return read_unit_list(json.dumps(units, indent=1), path, strict)


def test_the_issue_example():
    units, warnings = read([PEEL])
    assert units == [Unit("peel", (WHOLE, KNIFE), (PEELED,))]
    assert warnings == []


def test_null_and_missing_fields_are_empty():
    quirky = {
        "input_nodes": [
            {"label": "Banana", "states": ["whole"], "ingredients": None},
            {"label": "knife", "states": None},
            {"label": "milk", "container": "carton"},
        ],
        "motion_node": {"label": "Peel"},
        "output_nodes": [{"label": "banana", "states": ["peeled"], "container": None}],
    }
    units, warnings = read([quirky])
    milk = FoonObject.make("milk", container="carton")
    assert units == [Unit("peel", (WHOLE, KNIFE, milk), (PEELED,))]
    assert warnings == []


def test_motion_node_forms():
    for motion in ("peel", " Peel ", {"label": "peel"}, {"motion_label": "PEEL"}, "peel*"):
        units, _ = read([dict(PEEL, motion_node=motion)])
        assert units[0].motion == "peel", motion
    with pytest.raises(InputError, match="unit 1: 'motion_node' is an object without a 'label'"):
        read([dict(PEEL, motion_node={"id": 3})])
    with pytest.raises(InputError, match="unit 1: 'motion_node' must be a string"):
        read([dict(PEEL, motion_node=3)])


def test_identity_is_order_insensitive_and_labels_stay_as_written():
    mixed = {
        "input_nodes": [node("blender", [], ["blueberries", "banana"]), node("blueberry", ["fresh"])],
        "motion_node": "add",
        "output_nodes": [node("blender", [], ["banana", "blueberries", "blueberry"]), node("liquidmilk")],
    }
    units, _ = read([mixed])
    ins, outs = units[0].inputs, units[0].outputs
    assert ins[0] == FoonObject.make("blender", ingredients=["banana", "blueberries"])
    # plural, singular and run-together labels stay distinct objects at this stage
    assert ins[1].label == "blueberry" and outs[0].ingredients == ("banana", "blueberries", "blueberry")
    assert outs[1] == FoonObject.make("liquidmilk") and outs[1] != FoonObject.make("liquid milk")


@pytest.mark.parametrize("key", ["input_nodes", "motion_node", "output_nodes"])
def test_a_unit_missing_a_key_is_skipped_with_a_located_warning(key):
    broken = {k: v for k, v in PEEL.items() if k != key}
    other = dict(PEEL, motion_node="slice")
    units, warnings = read([other, broken, dict(PEEL, **{key: None})])
    assert [u.motion for u in units] == ["slice"]
    assert len(warnings) == 2
    assert warnings[0].startswith("t.json:") and f"unit 2 cannot be used: no '{key}'" in warnings[0]
    assert f"unit 3 cannot be used: no '{key}'" in warnings[1]
    line = int(warnings[0].split(":")[1])
    assert json.dumps([other, broken], indent=1).splitlines()[line - 1].strip() == "{"
    with pytest.raises(InputError, match=f"unit 2 cannot be used: no '{key}'") as err:
        read([other, broken], strict=True)
    assert str(err.value).startswith("t.json:")


def test_units_without_inputs_or_motion_are_skipped():
    units, warnings = read([dict(PEEL, input_nodes=[]), dict(PEEL, motion_node="  "), PEEL])
    assert len(units) == 1
    assert "unit 1 cannot be used: no input node" in warnings[0]
    assert "unit 2 cannot be used: an empty 'motion_node'" in warnings[1]


def test_repeated_units_are_merged_keeping_the_first():
    swapped = dict(PEEL, input_nodes=list(reversed(PEEL["input_nodes"])), motion_node={"label": "Peel"})
    slice_ = dict(PEEL, motion_node="slice")
    units, warnings = read([PEEL, slice_, swapped, PEEL, slice_])
    assert [u.motion for u in units] == ["peel", "slice"]
    assert units[0].inputs == (WHOLE, KNIFE)  # the first occurrence, as written
    assert warnings == [
        "t.json: 3 repeated units merged (unit 3 repeats unit 1, unit 4 repeats unit 1, unit 5 repeats unit 2)"
    ]


def test_bad_fields_name_file_line_unit_and_field():
    cases = [
        (dict(PEEL, input_nodes=[node("banana"), "knife"]), "unit 2, input_nodes[1]: expected an object"),
        (dict(PEEL, input_nodes="banana"), "unit 2: 'input_nodes' must be a list"),
        (dict(PEEL, output_nodes=[{"states": ["x"]}]), "unit 2, output_nodes[0]: object without a 'label'"),
        (dict(PEEL, output_nodes=[{"object_label": "x"}]), "'object_label' is FOON JSON"),
        (dict(PEEL, output_nodes=[node("x", ["a", 3])]), "output_nodes[0] ('x'): an entry of 'states' must be"),
        (dict(PEEL, output_nodes=[dict(node("x"), container=["bowl"])]), "('x'): 'container' must be a string"),
        (dict(PEEL, output_nodes=[dict(node("x"), ingredients="salt")]), "('x'): 'ingredients' must be a list"),
        (["not", "a", "unit"], "unit 2: expected an object {input_nodes, motion_node, output_nodes}"),
    ]
    for bad, words in cases:
        with pytest.raises(InputError) as err:
            read([PEEL, bad])
        message = str(err.value)
        assert words in message, message
        assert message.startswith("t.json:") and "\n" not in message


@pytest.mark.parametrize(
    "where, make, words",
    [
        ("states", lambda n: node("banana", [f"s{i}" for i in range(n)]), f"'states' has {MAX_ITEMS + 1:,} entries"),
        ("ingredients", lambda n: node("bowl", [], [f"i{i}" for i in range(n)]), "'ingredients' has"),
        ("label", lambda n: node("b" * (MAX_TEXT_CHARS + 1)), "'label' 'bbbb"),
        ("state", lambda n: node("banana", ["x" * (MAX_TEXT_CHARS + 1)]), "an entry of 'states'"),
        ("container", lambda n: node("milk", container="c" * (MAX_TEXT_CHARS + 1)), "'container'"),
    ],
)
def test_limits_name_file_unit_and_field(where, make, words):
    bad = dict(PEEL, output_nodes=[node("x"), make(MAX_ITEMS + 1)])
    with pytest.raises(InputError) as err:
        read([PEEL, bad], path="big.json")
    message = str(err.value)
    assert message.startswith("big.json:") and "unit 2, output_nodes[1]" in message, message
    assert words in message and "at most" in message and "no functional units" not in message
    assert len(message) < 300  # a long label is shortened in the message
    # at the limit the unit is read
    ok = dict(PEEL, output_nodes=[make(MAX_ITEMS)]) if where in ("states", "ingredients") else PEEL
    assert len(read([ok])[0]) == 1


def test_text_at_the_limit_is_read():
    text = "x" * MAX_TEXT_CHARS
    units, _ = read([dict(PEEL, motion_node=text, output_nodes=[node(text, [text], [text], text)])])
    assert units[0].motion == text and units[0].outputs[0] == FoonObject.make(text, [text], [text], text)


def test_motion_and_node_count_limits():
    with pytest.raises(InputError, match=r"unit 1: 'motion_node' 'mmm.*' has 1,001 characters \(at most 1,000\)"):
        read([dict(PEEL, motion_node="m" * 1001)])
    with pytest.raises(InputError, match=r"unit 1: 'input_nodes' has 1,001 entries \(at most 1,000\)"):
        read([dict(PEEL, input_nodes=[node(f"o{i}") for i in range(1001)])])


def test_file_level_limits_and_bad_json(tmp_path):
    for text, words in (
        ("[" * 300, "nested deeper than 100"),
        ('[{"input_nodes": [], "motion_node": ' + "9" * 200 + "}]", "number longer than 100"),
        ('{"input_nodes": []}', "expected a JSON list of objects"),
        ('[{"motion_node": "peel",}]', "bad JSON"),
    ):
        assert words in str(file_error(tmp_path / "t.json", text, read_unit_list_file))


def test_is_unit_list_tells_the_forms_apart():
    assert is_unit_list([PEEL])
    assert is_unit_list([{"motion_node": "peel"}])  # a unit missing keys is still this form
    lab = [{"motion": "peel", "inputs": [node("banana", ["whole"])], "outputs": [node("banana", ["peeled"])]}]
    assert not is_unit_list(lab)
    assert not is_unit_list({"functional_units": [PEEL]})
    assert not is_unit_list([{"functional_units": []}])
    assert not is_unit_list([{"goal": None, "units": []}])
    assert not is_unit_list([])
    assert not is_unit_list([PEEL, 3])
    assert not is_unit_list([{"label": "banana"}])  # a kitchen file
    # the existing readers still read their own forms only
    with pytest.raises(InputError, match="expected FOON JSON"):
        foonjson.parse_json(json.dumps([PEEL]), "t.json")


def random_units(rng: random.Random, n: int) -> list[Unit]:
    labels = ["banana", "blueberry", "blueberries", "liquidmilk", "blender", "glass", "knife", 'odd "label"', "Ünïcode"]
    states = ["whole", "peeled", "sliced", "empty", "fresh", "on [plate]", "seasoned {salt}"]

    def obj():
        return FoonObject.make(
            rng.choice(labels),
            rng.sample(states, rng.randint(0, 2)),
            rng.sample(labels, rng.randint(0, 2)),
            rng.choice([None, None, "bowl", "carton"]),
        )

    units: dict[tuple, Unit] = {}
    while len(units) < n:
        u = Unit(
            rng.choice(["peel", "slice", "pick-and-place", "blend"]),
            tuple(dict.fromkeys(obj() for _ in range(rng.randint(1, 3)))),
            tuple(dict.fromkeys(obj() for _ in range(rng.randint(0, 3)))),
        )
        units.setdefault(u.key(), u)
    return list(units.values())


@pytest.mark.parametrize("seed", range(5))
def test_round_trip(seed, tmp_path):
    units = random_units(random.Random(seed), 40)
    text = dumps(units)
    assert is_unit_list(json.loads(text))
    assert read_unit_list(text, "x.json") == (units, [])
    assert read_unit_list(json.dumps(to_unit_list(units)), "x.json") == (units, [])
    path = tmp_path / "x.json"
    path.write_text(text, encoding="utf-8")
    assert read_unit_list_file(path) == (units, [])
    assert all(
        e["input_nodes"][0]["container"] is None or isinstance(e["input_nodes"][0]["container"], str)
        for e in json.loads(text)
    )


def test_writer_form():
    entry = json.loads(dumps([Unit("peel", (WHOLE, KNIFE), (PEELED,))]))[0]
    assert entry == {
        "input_nodes": [node("banana", ["whole"]), node("knife")],
        "motion_node": "peel",
        "output_nodes": [node("banana", ["peeled"])],
    }
    assert dumps([]) == "[]\n" and read_unit_list(dumps([]), "e.json") == ([], [])


def test_foon_of_a_unit_list_keeps_origins_and_warnings():
    text = json.dumps([PEEL, {"motion_node": "x"}, dict(PEEL, motion_node="slice"), PEEL], indent=1)
    foon = unit_list_foon(text, "t.json")
    lines = text.splitlines()
    assert [u.motion for u in foon.units] == ["peel", "slice"]
    assert [p for p, _ in foon.origins] == ["t.json", "t.json"]
    assert all(lines[line - 1].strip() == "{" for _, line in foon.origins)
    assert len(foon.warnings) == 2


def test_demo_candidates():
    """The candidate smoothie trees under data/llm read as written, with their quirks reported."""
    read_all = {p.name: read_unit_list_file(p) for p in sorted(LLM.glob("smoothie-*.json"))}
    assert len(read_all) == 4
    assert all(len(units) >= 6 for units, _ in read_all.values())
    assert read_all["smoothie-1.json"][1] == [] and read_all["smoothie-2.json"][1] == []
    warnings = read_all["smoothie-3.json"][1]
    assert len(warnings) == 2 and "no 'output_nodes'" in warnings[0] and "1 repeated unit merged" in warnings[1]
    labels = {o.label for units, _ in read_all.values() for u in units for o in u.inputs}
    assert {"blueberry", "blueberries", "liquidmilk", "milk"} <= labels
    with pytest.raises(InputError, match="no 'output_nodes'"):
        read_unit_list_file(LLM / "smoothie-3.json", strict=True)


def test_mutated_files_give_a_result_or_one_line_error(tmp_path):
    """Random byte-level damage to a candidate file: never another exception, never a multi-line message."""
    seed_bytes = (LLM / "smoothie-2.json").read_bytes()
    rng = random.Random(11)
    hostile = [b"\x00", b"\xff", b"null", b"[]", b"{}", b'"', b",", b"9" * 150, b"[" * 120, b"\\ud800", b"\r"]
    path = tmp_path / "t.json"
    for _ in range(300):
        data = bytearray(seed_bytes)
        for _ in range(rng.randint(1, 3)):
            at = rng.randrange(len(data))
            op = rng.random()
            if op < 0.4:
                data[at : at + rng.randint(1, 20)] = b""
            elif op < 0.8:
                data[at:at] = rng.choice(hostile)
            else:
                data[at] = rng.randrange(256)
        path.write_bytes(bytes(data))
        try:
            read_unit_list_file(path)
        except InputError as exc:
            assert "\n" not in str(exc) and not BAD_CHAR.search(str(exc))


# ------------------------------------------------- the fuzzing finding about tree files


def test_trees_with_many_states_or_long_labels_are_read_not_refused(tmp_path):
    """A foon2asp JSON tree whose object has 1,000 states or a 100,000-character label: the
    tree reader reads it (it is not refused with "no functional units in the tree file")."""
    many = node("banana", [f"s{i}" for i in range(1000)])
    long = node("b" * 100_000, ["peeled"])
    for out in (many, long):
        tree = {"goal": out, "units": [{"motion": "peel", "inputs": [node("banana", ["whole"])], "outputs": [out]}]}
        path = tmp_path / "tree.json"
        for indent in (None, 1):
            path.write_text(json.dumps([tree], indent=indent))
            (read,) = read_trees(path)
            assert len(read.units) == 1
            assert read.units[0].unit.outputs[0] == FoonObject.make(out["label"], out["states"])


def test_several_trees_keep_the_lines_of_their_units(tmp_path):
    cut = dict(PEEL, input_nodes=[node("banana", ["peeled"]), node("knife")], motion_node="cut")
    text = (
        "[\n" + json.dumps([PEEL, {"motion_node": "x"}, cut], indent=1) + ",\n  [],\n" + json.dumps([cut, PEEL]) + "\n]"
    )
    path = tmp_path / "t.json"
    path.write_text(text)
    first, second = read_trees(path)
    assert (first.line, [(tu.step, tu.line) for tu in first.units]) == (2, [(1, 3), (3, 35)])
    assert (second.line, [(tu.step, tu.line) for tu in second.units]) == (66, [(1, 66), (2, 66)])
    assert first.warnings == [
        f"{path}:32: tree 1, unit 2 cannot be used: no 'input_nodes', no 'output_nodes' (skipped)"
    ]
