"""The kitchen and goals files: each JSON list decoded once, each object with its line."""

from __future__ import annotations

import json

import pytest

from foon2asp.foon.loaders import read_goals, read_kitchen
from foon2asp.foon.model import FoonObject
from helpers import file_error

GOALS = '[\n  {"label": "egg", "states": ["cracked"]},\n\n  {"label": "Bowl",\n   "container": null}\n]\n'


def test_goals_decoded_once_with_their_lines(tmp_path, monkeypatch):
    path = tmp_path / "goal_nodes.json"
    path.write_text(GOALS)
    calls = []
    decode = json.JSONDecoder.raw_decode
    monkeypatch.setattr(
        json.JSONDecoder, "raw_decode", lambda self, s, idx=0: calls.append(idx) or decode(self, s, idx)
    )
    goals = read_goals(path)
    assert goals == [(FoonObject.make("egg", ["cracked"]), 2), (FoonObject.make("bowl"), 4)]
    assert len(calls) == 1
    assert read_kitchen(path) == [FoonObject.make("egg", ["cracked"]), FoonObject.make("bowl")]
    assert len(calls) == 2


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ('[\n  {"label": "egg"},\n  [true, null]\n]', 3, "expected an object"),
        ('[\n  {"label": "egg"},\n  -Infinity\n]', 3, "expected an object"),
        ('\n\n{"label": "egg"}', 3, "expected a JSON list of objects"),
    ],
)
def test_bad_entries_name_their_line(tmp_path, text, line, words):
    err = file_error(tmp_path / "kitchen.json", text, read_kitchen)
    assert words in str(err) and err.line == line
