"""The walk back from what a tree lacks: an object no unit makes, or a cycle of makers."""

from __future__ import annotations

from foon2asp.tree.validate import find_missing_or_cycle

#: object -> the units that make it; unit -> the inputs it lacks
MAKERS = {"g": [0], "x": [1], "y": [2]}
LACKS = {0: ["x"], 1: ["y"], 2: ["g"], 3: ["z"]}


def test_finds_a_cycle_of_makers():
    assert find_missing_or_cycle([("g", None)], MAKERS, LACKS.__getitem__) == ("cycle", [("g", 0), ("x", 1), ("y", 2)])


def test_finds_an_object_no_unit_makes():
    makers = {**MAKERS, "y": [3]}
    assert find_missing_or_cycle([("g", None)], makers, LACKS.__getitem__) == ("missing", ("z", 3))
    assert find_missing_or_cycle([("w", 5)], makers, LACKS.__getitem__) == ("missing", ("w", 5))


def test_nothing_found_when_every_maker_has_its_inputs():
    assert find_missing_or_cycle([("g", None)], MAKERS, lambda u: []) is None
