"""Serialising results: JSON lists, one record per line; the optional fields of a tree."""

from __future__ import annotations

import dataclasses
import json

from foon2asp.tree.serialize import json_list, tree_json
from foon2asp.tree.tasktree import OPTIONAL, TaskTree


def test_json_list_same_data():
    records = [{"goal": {"label": 'a "quoted"\nlabel'}, "units": [1, 2]}, {"x": None, "é": 1.5}]
    text = json_list(records)
    assert json.loads(text) == records
    assert text.count("\n") == len(records) + 1  # one record per line
    assert json.loads(json_list([])) == []


def test_optional_fields_follow_stats_in_their_order_and_none_is_left_out(demo_problem):
    _, p = demo_problem
    names = [f.name for f in dataclasses.fields(TaskTree)]
    assert names[names.index("proven_by") + 1 :] == list(OPTIONAL)  # every optional field is written
    tree = TaskTree(0, "asp", "optimal", stats={"solves": 1})
    for k, name in enumerate(reversed(OPTIONAL)):  # set in the opposite order
        setattr(tree, name, k)
    record = tree_json(p, tree)
    assert list(record)[list(record).index("stats") + 1 :] == list(OPTIONAL)
    assert [record[name] for name in OPTIONAL] == list(range(len(OPTIONAL)))[::-1]
    # as the runner explains an infeasible goal: the programs, then why, then every program asked for
    bare = TaskTree(0, "asp", "infeasible", constraints=["--rule #1"], reason="r", infeasible_by=["--rule #1"])
    head = ["goal", "method", "status", "cost", "units", "time_s", "proven_by"]
    assert list(tree_json(p, bare)) == [*head, "infeasible_by", "reason", "constraints"]
    # false and empty values are kept, only None is left out
    judged = tree_json(p, TaskTree(0, "ids", "found", valid=False, substitutions=[]))
    assert list(judged) == [*head, "substitutions", "valid"] and judged["valid"] is False
