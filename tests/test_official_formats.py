"""The official FOON dialect and FOON JSON: what FOON_view and foon_api load.

``official_units`` reads a file the way those tools do -- written here from
their documented rules, not from their code: an ``O`` line is
``O<id>\\t<label>\\t<in-motion 0|1>``, an ``S`` line ``S<id>\\t<state>`` with an
optional ``{...}`` or ``[...]`` field, an ``M`` line
``M<id>\\t<motion>\\t<start>\\t<end>``, ``//`` closes a unit; two objects are the
same node iff their ids, labels, states (id, label, related object) and
ingredients are equal, and a unit equal to an earlier one is not added.  So
ids shared by two labels, or missing, make units merge -- which is what the
conformance tests catch.
"""

from __future__ import annotations

import io
import json
import re

import pytest
from click.testing import CliRunner

from foon2asp.cli.main import main
from foon2asp.foon import foonjson
from foon2asp.foon.model import Foon, FoonObject, Unit
from foon2asp.foon.parser import IdMap, format_units, id_map, parse_lines, read_foon, write_foon
from foon2asp.tree.serialize import tree_foon

O_LINE = re.compile(r"^O(\d+)\t([^\t]+)\t([01])$")
S_LINE = re.compile(r"^S(\d+)\t([^\t]+)(?:\t([\[{].*[\]}]))?$")
M_LINE = re.compile(r"^M(\d+)\t([^\t]+)\t([^\t]+)\t([^\t]+)$")


class Conformance(AssertionError):
    pass


def official_units(text: str) -> tuple[int, int, dict[str, dict[str, int]]]:
    """(units written, distinct units loaded, ids per kind) of an official FOON file; raises on a bad line."""
    ids: dict[str, dict[str, int]] = {"O": {}, "S": {}, "M": {}}
    owners: dict[str, dict[int, str]] = {"O": {}, "S": {}, "M": {}}

    def note(kind: str, i: str, label: str) -> None:
        if ids[kind].setdefault(label, int(i)) != int(i):
            raise Conformance(f"{kind}: {label!r} has two ids")
        if owners[kind].setdefault(int(i), label) != label:
            raise Conformance(f"{kind}{i} names both {owners[kind][int(i)]!r} and {label!r}")

    loaded: list[tuple] = []
    written = 0
    inputs: list = []
    outputs: list = []
    motion = None
    obj: list | None = None
    closed = True
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.rstrip("\r")
        if not line or line.startswith("#"):
            continue
        if line.startswith("//"):
            if inputs or motion:
                if motion is None:
                    raise Conformance(f"line {n}: unit without a motion")
                written += 1
                key = (motion, frozenset(map(tuple, inputs)), frozenset(map(tuple, outputs)))
                if key not in loaded:
                    loaded.append(key)
            inputs, outputs, motion, obj, closed = [], [], None, None, True
            continue
        closed = False
        if m := O_LINE.match(line):
            note("O", m.group(1), m.group(2))
            obj = [int(m.group(1)), m.group(2), (), ()]
            (outputs if motion else inputs).append(obj)
        elif m := S_LINE.match(line):
            if obj is None:
                raise Conformance(f"line {n}: state before an object")
            note("S", m.group(1), m.group(2))
            obj[2] = tuple(sorted(obj[2] + ((int(m.group(1)), m.group(2), m.group(3) or ""),)))
            if m.group(3) and m.group(3).startswith("{"):
                obj[3] = tuple(sorted(m.group(3)[1:-1].split(",")))
        elif m := M_LINE.match(line):
            note("M", m.group(1), m.group(2))
            if m.group(3) != "Assumed" or m.group(4) != "Assumed":
                raise Conformance(f"line {n}: times are not 'Assumed'")
            motion = (int(m.group(1)), m.group(2))
            obj = None
        else:
            raise Conformance(f"line {n}: not an official line: {line!r}")
    if not closed:
        raise Conformance("the last unit is not closed by //")
    return written, len(loaded), ids


def _obj(label, *states, contains=(), inside=None):
    return FoonObject.make(label, states, contains, inside)


SAMPLE = [
    Unit(
        "slice",
        (_obj("tomato", "whole", inside="cutting board"), _obj("knife")),
        (_obj("tomato", "sliced", inside="cutting board"), _obj("knife")),
    ),
    Unit(
        "pour",
        (_obj("bowl", contains=["onion"]), _obj("onion", "chopped", inside="bowl"), _obj("pot", "on [stove]")),
        (_obj("pot", "on [stove]", contains=["onion"]), _obj("onion", "chopped", inside="pot"), _obj("bowl", "empty")),
    ),
    Unit("season", (_obj("steak", "raw", "seasoned {salt,pepper}"),), (_obj("steak", "cooked"),)),
]


def _sample_foon() -> Foon:
    foon = Foon()
    for u in SAMPLE:
        foon.add_unit(u)
    return foon


def test_official_dialect_conforms_and_round_trips():
    foon = _sample_foon()
    text = io.StringIO()
    write_foon(foon, text)
    written, loaded, ids = official_units(text.getvalue())
    assert (written, loaded) == (3, 3)
    assert set(ids["O"]) == {"tomato", "knife", "bowl", "onion", "pot", "steak"}
    assert len(set(ids["O"].values())) == 6  # distinct per label
    assert text.getvalue().startswith("//\nO")  # a leading // then the units
    again = parse_lines(text.getvalue())
    assert [u.key() for u in again.units] == [u.key() for u in foon.units]
    plain = format_units(foon.units)
    assert "\tAssumed" not in plain and "O\ttomato" in plain
    assert [u.key() for u in parse_lines(plain).units] == [u.key() for u in foon.units]
    # CRLF, as the official files have it
    crlf = text.getvalue().replace("\n", "\r\n")
    assert official_units(crlf)[:2] == (3, 3)
    assert [u.key() for u in parse_lines(crlf).units] == [u.key() for u in foon.units]


def test_conformance_checker_catches_placeholder_ids():
    """Ids all 0 make different labels one node: the checker must notice (it can fail)."""
    foon = _sample_foon()
    text = format_units(foon.units, ids=IdMap({}, {}))
    zeroed = re.sub(r"^([OSM])\d+\t", r"\g<1>0\t", text, flags=re.M)
    with pytest.raises(Conformance):
        official_units(zeroed)
    with pytest.raises(Conformance):
        official_units(format_units(foon.units))  # the ID-less dialect


def test_ids_of_official_files_are_reused_and_others_assigned_deterministically(shared_111_dir):
    foon = read_foon(shared_111_dir / "0001-whipped_cream.txt")
    ids = id_map(foon)
    assert ids.get("O", "mixing bowl") == 278 and ids.get("S", "empty") == 41 and ids.get("M", "pour") == 54
    fresh = ids.get("O", "a label never seen")
    assert fresh > max(foon.ids["O"].values())
    # a FOON without ids: the same ids every time, sorted by label
    plain = parse_lines(format_units(foon.units))
    a, b = IdMap(plain.ids, {"O": {"b", "a"}}), IdMap({}, {"O": {"a", "b"}})
    assert a.get("O", "a") == b.get("O", "a") == 1 and a.get("O", "b") == 2
    # a label whose id another label holds gets a fresh one
    clash = IdMap({"O": {"x": 5, "y": 5}}, {"O": {"x", "y"}})
    assert clash.get("O", "x") == 5 and clash.get("O", "y") == 6


def test_every_reachable_goal_writes_a_conforming_file(shared_foon_dir, tmp_path):
    out = tmp_path / "trees"
    res = CliRunner().invoke(
        main, ["solve", "--data", str(shared_foon_dir), "--goals", "all", "--format", "foon", "--output", str(out)]
    )
    assert res.exit_code == 0, res.output
    files = sorted(out.iterdir())
    assert len(files) == 25
    counted = 0
    for f in files:
        text = f.read_text()
        assert text.startswith("# task tree for ")
        written, loaded, _ = official_units(text)
        assert written == loaded == text.count("\nM")  # every unit loads, none merges
        if written:
            counted += 1
            again = CliRunner().invoke(main, ["check", str(f), "--data", str(shared_foon_dir), "--no-optimum"])
            assert again.exit_code == 0, again.output
    assert counted == 23  # whipped cream and fried rice are unreachable
    greek = next(f for f in files if "greek_salad" in f.name)
    assert official_units(greek.read_text())[:2] == (25, 25)


def test_tree_round_trips_through_both_dialects_and_json(shared_problem):
    data, problem = shared_problem
    from foon2asp.asp.options import AspOptions
    from foon2asp.foon import goals
    from foon2asp.methods.plan import session_of as Session

    g = goals.resolve_label(data, problem, "greek salad")
    tree = Session(problem, AspOptions(units=problem.units_for([g]))).solve(g)
    keys = [problem.units[u].key() for u in tree.units]
    assert len(keys) == 25
    for dialect in ("official", "plain"):
        assert [u.key() for u in parse_lines(tree_foon(problem, tree, dialect)).units] == keys
    doc = foonjson.to_foon_json((problem.units[u] for u in tree.units), id_map(problem.foon))
    assert set(doc["functional_units"][0]) == {"input_nodes", "motion_node", "output_nodes"}
    node = doc["functional_units"][0]["input_nodes"][0]
    assert set(node) == {"object_id", "object_label", "object_states", "ingredients", "object_in_motion"}
    assert set(doc["functional_units"][0]["motion_node"]) == {"motion_id", "motion_label", "start_time", "end_time"}
    assert [u.key() for u in foonjson.parse_json(json.dumps(doc)).units] == keys


def test_foon_json_contains_in_and_relations():
    unit = SAMPLE[1]
    doc = foonjson.unit_json(unit, IdMap({}, {}))
    bowl = doc["input_nodes"][0]
    assert bowl["ingredients"] == ["onion"] and [s["state_label"] for s in bowl["object_states"]] == ["contains"]
    onion = doc["input_nodes"][1]
    assert {
        "state_id": onion["object_states"][-1]["state_id"],
        "state_label": "in",
        "relative_object": "bowl",
    } in onion["object_states"]
    pot = doc["input_nodes"][2]
    assert pot["object_states"][0]["state_label"] == "on" and pot["object_states"][0]["relative_object"] == "stove"
    assert doc["motion_node"]["start_time"] == doc["motion_node"]["end_time"] == "Assumed"


def test_lab_json_units_read_as_a_foon(tmp_path, demo_problem):
    _, problem = demo_problem
    lab = [u.to_json() for u in problem.units[:3]]
    path = tmp_path / "units.json"
    path.write_text(json.dumps(lab))
    assert [u.key() for u in read_foon(path).units] == [u.key() for u in problem.units[:3]]
    path.write_text('{"functional_units": [{"input_nodes": 3}]}')
    res = CliRunner().invoke(main, ["solve", "--foon", str(path), "--kitchen", str(tmp_path / "k.json")])
    assert res.exit_code == 2 and "functional unit 1" in res.output and "Traceback" not in res.output


def test_foon_json_as_input_solves_the_same(shared_foon_dir, tmp_path):
    merged = tmp_path / "foon.json"
    res = CliRunner().invoke(
        main, ["merge", str(shared_foon_dir / "FOON.txt"), "-o", str(merged), "--format", "foon-json"]
    )
    assert res.exit_code == 0, res.output
    args = ["--kitchen", str(shared_foon_dir / "kitchen.json"), "--goals", str(shared_foon_dir / "goal_nodes.json")]
    out = CliRunner().invoke(main, ["solve", "--foon", str(merged), *args, "--goal", "greek salad"]).output
    assert "units 25" in out


def test_111_files_rewritten_and_reread_unchanged(shared_111_dir):
    files = sorted(shared_111_dir.glob("*.txt"))
    assert len(files) == 111
    total = 0
    for f in files:
        foon = read_foon(f)
        keys = [u.key() for u in foon.units]
        text = io.StringIO()
        write_foon(foon, text)
        written, loaded, ids = official_units(text.getvalue())
        assert written == loaded == len(keys), f
        again = parse_lines(text.getvalue())
        assert [u.key() for u in again.units] == keys, f
        for kind, table in again.ids.items():  # the file's own ids are kept
            assert all(foon.ids[kind][k] == v for k, v in table.items()), f
        plain = parse_lines(format_units(foon.units))
        assert [u.key() for u in plain.units] == keys, f
        doc = foonjson.dumps(foon.units, id_map(foon))
        assert [u.key() for u in foonjson.parse_json(doc).units] == keys, f
        total += len(keys)
    assert total > 2000
