"""Motion-cost tables (foon2asp.foon.motioncost): both forms, exact scaling, located errors,
the one warning about motions the table lacks."""

from __future__ import annotations

import json
import random
from decimal import Decimal
from pathlib import Path

import pytest

from foon2asp.errors import InputError
from foon2asp.foon.motioncost import (
    DEFAULT_COST,
    MAX_COST,
    PRECISION,
    SCALE,
    as_number,
    parse_motion_costs,
    read_motion_costs,
    unit_weights,
    unscaled,
)

DEMO_TABLE = Path(__file__).resolve().parent.parent / "data" / "llm" / "motion-costs.json"


def test_json_and_lines_give_the_same_table(tmp_path):
    costs = {"chop": "0.9", "pour": "0.1", "mix": "1", "stir": "0.25", "pick-and-place": "0"}
    j = tmp_path / "c.json"
    j.write_text("{" + ", ".join(f'"{m}": {c}' for m, c in costs.items()) + "}\n")
    t = tmp_path / "c.txt"
    t.write_text("# motion costs\n\n" + "".join(f"{m}\t{c}\n" for m, c in costs.items()))
    a, b = read_motion_costs(j), read_motion_costs(t)
    assert a.costs == b.costs == {m: Decimal(c) for m, c in costs.items()}
    assert a.path == str(j)
    assert {m: a.weight(m) for m in costs} == {"chop": 90, "pour": 10, "mix": 100, "stir": 25, "pick-and-place": 0}


def test_scaling_is_exact_for_every_two_decimal_value():
    """Every value with up to two decimals scales to the integer a person would write (no float error)."""
    rng = random.Random(7)
    values = [f"{rng.randrange(0, 100_000) / 100:.2f}".rstrip("0").rstrip(".") for _ in range(300)]
    values += ["0.29", "0.57", "1.15", "4.35", "0.01", "999.99"]  # classic float traps
    text = "\n".join(f"m{i}\t{v}" for i, v in enumerate(values))
    table = parse_motion_costs(text, "t.txt")
    for i, v in enumerate(values):
        whole, _, frac = v.partition(".")
        assert table.weight(f"m{i}") == int(whole) * 100 + int((frac + "00")[:2]), v
        assert unscaled(table.weight(f"m{i}")) == Decimal(v)


def test_motions_are_matched_as_units_hold_them():
    table = parse_motion_costs('{"  Chop ": 0.5, "Pick  and Place*": 0.2}', "c.json")
    assert table.cost("chop") == Decimal("0.5")
    assert table.cost("pick and place") == Decimal("0.2")
    assert table.cost("CHOP") == Decimal("0.5")


@pytest.mark.parametrize(
    "text, line, words",
    [
        ('{"chop": 0.9,\n "pour": -0.1}', 2, "negative"),
        ('{"chop": 0.9,\n "pour": "cheap"}', 2, "must be a number"),
        ('{"chop": 0.9,\n\n "pour": NaN}', 3, "not a finite number"),
        ('{"chop": Infinity}', 1, "not a finite number"),
        ('{"chop": -Infinity}', 1, "not a finite number"),
        ('{"chop": null}', 1, "must be a number"),
        ('{"chop": true}', 1, "must be a number"),
        ('{"chop": [1]}', 1, "must be a number"),
        ('{"chop": 0.125}', 1, "finer than 0.01"),
        ('{"chop": 1e-9}', 1, "finer than 0.01"),
        ('{"chop": 1001}', 1, "at most 1000"),
        ('{"chop": 0.5,\n "CHOP": 0.6}', 2, "listed twice"),
        ('{"": 0.5}', 1, "empty motion"),
        ("chop\t0.5\npour\tcheap\n", 2, "not a number"),
        ("chop\t0.5\n# x\npour\t-1\n", 3, "negative"),
        ("chop\tnan\n", 1, "not a finite number"),
        ("chop\tinf\n", 1, "not a finite number"),
        ("chop\t0.001\n", 1, "finer than 0.01"),
        ("chop\n", 1, "expected 'motion<TAB>cost'"),
        ("chop\t" + "1" * 200 + "\n", 1, "longer than"),
        ("[0.5]", 1, "expected a JSON object"),
    ],
)
def test_bad_values_name_file_and_line(text, line, words):
    with pytest.raises(InputError) as err:
        parse_motion_costs(text, "costs.tbl")
    assert str(err.value).startswith(f"costs.tbl:{line}: "), str(err.value)
    assert words in str(err.value)
    assert "\n" not in str(err.value)


def test_same_value_twice_is_fine_and_zero_is_a_cost():
    table = parse_motion_costs("chop\t0.50\nchop\t0.5\nmix\t-0\n", "c.txt")
    assert table.costs == {"chop": Decimal("0.5"), "mix": Decimal(0)}
    assert table.weight("mix") == 0


def test_missing_motions_cost_one_with_one_warning():
    table = parse_motion_costs('{"chop": 0.9}', "c.json")
    weights, warning = unit_weights(table, ["chop", "stir", "pour", "stir"])
    assert weights == {"chop": 90, "pour": 100, "stir": 100}
    assert warning is not None and warning.startswith("c.json: 2 motions are not in the motion-cost table")
    assert warning.endswith(": pour, stir") and "\n" not in warning
    assert unit_weights(table, ["chop"]) == ({"chop": 90}, None)
    assert DEFAULT_COST * SCALE == 100


def test_reported_costs():
    assert as_number(unscaled(180)) == 1.8
    assert as_number(unscaled(300)) == 3 and isinstance(as_number(unscaled(300)), int)


def test_limits_are_stated():
    assert PRECISION == Decimal("0.01") and SCALE == 100 and MAX_COST * SCALE < 2**31


def test_demo_table(tmp_path):
    table = read_motion_costs(DEMO_TABLE)
    assert table.costs == {k: Decimal(str(v)) for k, v in json.loads(DEMO_TABLE.read_text()).items()}
    with pytest.raises(InputError, match="motion-cost file not found"):
        read_motion_costs(tmp_path / "none.json")
