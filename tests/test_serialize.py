"""Serialising results: JSON lists, one record per line."""

from __future__ import annotations

import json

from foon2asp.tree.serialize import json_list


def test_json_list_same_data():
    records = [{"goal": {"label": 'a "quoted"\nlabel'}, "units": [1, 2]}, {"x": None, "é": 1.5}]
    text = json_list(records)
    assert json.loads(text) == records
    assert text.count("\n") == len(records) + 1  # one record per line
    assert json.loads(json_list([])) == []
