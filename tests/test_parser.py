"""Parsing both FOON dialects, identity, de-duplication, round trip, merge, errors."""

from __future__ import annotations

import pytest

from foon2asp.errors import InputError
from foon2asp.foon.model import Foon, FoonObject
from foon2asp.foon.parser import format_units, parse_lines, read_foon, read_foons

IDLESS = """# a comment
//
O\tonion
S\twhole
O\tknife
M\tchop
O\tonion
S\tchopped
S\tin\t[cutting board]
O\tknife
//
"""

OFFICIAL = (
    "# Source:\thttp://example.org/video\r\n"
    "//\r\n"
    "O278\tmixing bowl\t1\r\n"
    "S41\tempty\r\n"
    "O277\tmixer\t0\r\n"
    "S79\toff (ready)\r\n"
    "M1\tattach*\tAssumed\tAssumed\r\n"
    "O277\tmixer\t0\r\n"
    "S142\twith\t[mixing bowl]\r\n"
    "O278\tmixing bowl\t1\r\n"
    "S23\tcontains\t{sugar, heavy cream}\r\n"
    "S0\tattached to\t[mixer]\r\n"
    "//\r\n"
)


def test_idless_format():
    foon = parse_lines(IDLESS)
    assert len(foon.units) == 1
    unit = foon.units[0]
    assert unit.motion == "chop"
    assert unit.inputs == (FoonObject("onion", ("whole",)), FoonObject("knife"))
    assert unit.outputs[0] == FoonObject("onion", ("chopped",), (), "cutting board")
    assert unit.outputs[1].is_bare()


def test_official_format_relations_kept_as_states():
    foon = parse_lines(OFFICIAL)
    unit = foon.units[0]
    assert unit.motion == "attach"  # trailing * dropped
    mixer, bowl = unit.outputs
    assert mixer.states == ("with [mixing bowl]",)
    assert mixer.container is None  # not folded into the container
    assert bowl.ingredients == ("heavy cream", "sugar")
    assert bowl.states == ("attached to [mixer]",)
    assert unit.inputs[1].states == ("off (ready)",)


def test_identity_is_order_insensitive():
    a = FoonObject.make("Bowl", ["hot", "clean"], ["salt", "flour"], "table")
    b = FoonObject.make("bowl ", ["clean", "hot"], ["flour", "salt"], "table")
    assert a == b and hash(a) == hash(b)
    assert a != FoonObject.make("bowl", ["clean", "hot"], ["flour", "salt"], None)
    assert a != FoonObject.make("bowl", ["clean"], ["flour", "salt"], "table")


def test_duplicate_units_merged():
    reordered = "O\tknife\nO\tonion\nS\twhole\nM\tchop\nO\tknife\nO\tonion\nS\tin\t[cutting board]\nS\tchopped\n//\n"
    foon = parse_lines(IDLESS + reordered)
    # the second copy lists the inputs in another order: same unit
    assert len(foon.units) == 1
    other = parse_lines(IDLESS.replace("chop", "slice"))
    merged = Foon()
    for part in (foon, other, foon):  # the units of several FOONs in one
        parse_lines(format_units(part.units).splitlines(), foon=merged)
    assert [u.motion for u in merged.units] == ["chop", "slice"]


def test_round_trip_string():
    foon = parse_lines(OFFICIAL + IDLESS)
    again = parse_lines(format_units(foon.units))
    assert again.units == foon.units


@pytest.mark.parametrize(
    "text, line, words",
    [
        ("//\nX\tfoo\n", 2, "unknown line type"),
        ("//\nS\twhole\n", 2, "before any object"),
        ("//\nO\tonion\nM\tchop\nO\tonion\nS\tx\nM\tcut\n", 6, "second motion"),
        ("//\nM\tchop\nO\tonion\n", 2, "before any input"),
        ("//\nOonion\n", 2, "TAB"),
        ("//\nO\tbowl\nS\tin\t[a]\nS\tin\t[b]\nM\tx\nO\tbowl\n", 4, "two containers"),
    ],
)
def test_errors_name_line(text, line, words):
    with pytest.raises(InputError) as err:
        parse_lines(text, "f.txt")
    assert err.value.path == "f.txt" and err.value.line == line
    assert words in str(err.value)
    assert str(err.value).startswith(f"f.txt:{line}: ")
    assert "\n" not in str(err.value)


def test_unit_without_motion_warns_or_fails_when_strict():
    text = "//\nO\tegg\nS\tuncracked\nO\tegg\nS\tcracked\n//\n" + IDLESS
    foon = parse_lines(text, "f.txt")
    assert len(foon.units) == 1
    assert foon.warnings == ["f.txt:2: functional unit has no motion (M) line; unit skipped"]
    with pytest.raises(InputError) as err:
        parse_lines(text, "f.txt", strict=True)
    assert err.value.line == 2


def test_missing_file_is_input_error(tmp_path):
    with pytest.raises(InputError) as err:
        read_foon(tmp_path / "nope.txt")
    assert "nope.txt" in str(err.value)


def test_all_111_parse_and_merge(shared_111_dir, tmp_path):
    files = sorted(shared_111_dir.glob("*.txt"))
    assert len(files) == 111
    per_file = [read_foon(f) for f in files]
    assert all(len(f.units) > 0 for f in per_file)
    merged = read_foons(files)
    distinct = {u.key() for f in per_file for u in f.units}
    assert len(merged.units) == len(distinct)
    assert len(merged.units) < sum(len(f.units) for f in per_file)  # recipes share units
    # relations besides in/contains survive as states
    states = {s for o in merged.objects for s in o.states}
    for rel in ("on [", "with [", "attached to ["):
        assert any(s.startswith(rel) for s in states), rel
    # round trip through the writer
    out = tmp_path / "merged.txt"
    out.write_text(format_units(merged.units))
    again = read_foon(out)
    assert again.units == merged.units
    assert len(again.objects) == len(merged.objects)


def test_universal_foon(shared_foon_dir):
    foon = read_foon(shared_foon_dir / "FOON.txt")
    assert len(foon.units) == 2376
    assert not foon.warnings
    again = parse_lines(format_units(foon.units))
    assert again.units == foon.units


def test_parser_fast_path_errors_and_ids():
    foon = parse_lines("O12\tegg\t0\nS3\twhole\nM7\tcrack*\t0\t1\nO1\tegg\nS\tcracked\n//\n")
    assert len(foon.units) == 1 and foon.units[0].motion == "crack"
    assert foon.units[0].outputs[0].states == ("cracked",)
    for text, needle in (
        ("O egg\n", "expected a TAB"),
        ("Ox\tegg\n", "unknown line type"),
        (" O\tegg\n", "unknown line type"),
        ("X\tegg\n", "unknown line type"),
    ):
        with pytest.raises(InputError, match=needle):
            parse_lines(text)


def test_read_foon_streams_lines(tmp_path):
    """Reading a large FOON holds its text, not also a list of its lines."""
    import tracemalloc

    path = tmp_path / "big.txt"
    path.write_text(IDLESS * (2_000_000 // len(IDLESS)))
    size = path.stat().st_size
    tracemalloc.start()
    try:
        foon = read_foon(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert len(foon.units) == 1
    assert peak < 3 * size
