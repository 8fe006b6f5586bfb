"""Comparing methods: validity marks, the ASP optimum column, formats, the registry."""

from __future__ import annotations

import csv
import io
import json
import random

import pytest
from click.testing import CliRunner

from foon2asp import methods
from foon2asp.analysis.compare import DEFAULT_METHODS, compare_iter
from foon2asp.cli.main import main
from foon2asp.methods.plan import session_of as Session
from foon2asp.report import render
from foon2asp.tree.tasktree import TaskTree
from foon2asp.tree.validate import validate
from helpers import best, build, goal_id


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def trap():
    """g: the greedy choice ('pour', likely and short) rests on a cycle; 'chop' works."""
    return build(
        [("pour", ["x"], ["g"]), ("fold", ["g", "k"], ["x"]), ("chop", ["k", "a"], ["g"]), ("cut", ["k"], ["a"])],
        kitchen=["k"],
        rates={"pour": 0.9, "fold": 0.9, "chop": 0.1, "cut": 0.5},
    )


def test_rows_mark_validity():
    p = trap()
    g = goal_id(p, "g")
    (row,) = compare_iter(p, [g])
    assert list(row.trees) == list(DEFAULT_METHODS)
    for name, tree in row.trees.items():
        assert tree.method == name
        assert tree.valid == (tree.has_tree and validate(p, g, tree.units).valid)
    assert row.trees["gbfs-h1"].valid is False
    assert "circular support" in row.trees["gbfs-h1"].problem
    assert row.trees["ids"].units == [3, 2]
    assert row.trees["asp"].status == "optimal" and len(row.trees["asp"].units) == 2


@pytest.mark.parametrize("seed", range(40))
def test_asp_column_is_the_brute_force_optimum(seed):
    rng = random.Random(seed)
    names = ["k1", "k2", "a", "b", "c", "g"]
    units = [
        (rng.choice(["pour", "mix"]), rng.sample(names, rng.randint(1, 3)), [rng.choice(names[2:])])
        for _ in range(rng.randint(3, 8))
    ]
    p = build(units, kitchen=["k1", "k2"], rates={"pour": 0.9, "mix": 0.4})
    if not any(o.label == "g" for o in p.objects):
        return
    g = goal_id(p, "g")
    (row,) = compare_iter(p, [g])
    smallest, _ = best(p, g, lambda m: m["units"])
    asp = row.trees["asp"]
    if smallest == float("inf"):
        assert asp.status == "unreachable" and asp.valid is False
        return
    assert asp.status == "optimal" and len(asp.units) == smallest and asp.valid
    for _name, tree in row.trees.items():
        if tree.valid:
            assert len(tree.units) >= smallest


def test_later_registered_methods_just_work():
    @methods.register("test-nothing", "search", "returns no tree (test only)")
    def _nothing(problem, options):
        return lambda goal: TaskTree(goal, "test-nothing", "not-found")

    try:
        p = trap()
        (row,) = compare_iter(p, [goal_id(p, "g")], ["ids", "test-nothing"])
        assert list(row.trees) == ["ids", "test-nothing"]
        assert row.trees["test-nothing"].valid is False
        assert "not-found" in render("compare", "text", p, [row])
    finally:
        del methods.METHODS["test-nothing"]


def test_unknown_method_is_bad_input():
    res = cli("compare", "--data", "demo", "--methods", "ids,nope")
    assert res.exit_code == 2
    assert "unknown method 'nope'" in res.stderr and len(res.stderr.strip().splitlines()) == 1


def test_demo_table():
    res = cli("compare", "--data", "demo", "--format", "markdown")
    assert res.exit_code == 1, res.output  # a greedy tree is invalid
    lines = res.stdout.splitlines()
    assert "| goal | ids | gbfs-h1 | gbfs-h2 | asp optimum |" in lines
    row = next(line for line in lines if line.startswith("| scrambled egg |"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    # the greedy trap: both heuristics take the jar pour, which rests on a cycle
    assert cells[2].endswith("invalid") and cells[3].endswith("invalid")
    assert not cells[1].endswith("invalid") and not cells[4].endswith("invalid")


# ---------------------------------------------------------------- the universal FOON


@pytest.fixture(scope="module")
def shared_json(shared_foon_dir):
    res = cli("compare", "--data", shared_foon_dir, "--goals", "all", "--format", "json")
    out = json.loads(res.stdout)
    # exit code 1: some greedy trees are invalid (every ASP answer is proven)
    assert any(r["valid"] is False and r["status"] == "found" for r in out)
    assert res.exit_code == 1, res.output
    return out


def by_goal(results):
    out: dict[str, dict[str, dict]] = {}
    for r in results:
        out.setdefault(r["goal"]["label"], {})[r["method"]] = r
    return out


def test_shared_json_shape(shared_json):
    assert len(shared_json) == 25 * 4
    for r in shared_json:
        assert set(r) >= {"goal", "method", "status", "cost", "units", "time_s", "valid"}
        assert isinstance(r["valid"], bool)
        assert r["method"] in DEFAULT_METHODS
        assert r["valid"] == (r["status"] in ("optimal", "found") and "problem" not in r)
    assert [r["method"] for r in shared_json[:4]] == list(DEFAULT_METHODS)


def test_shared_optimum_not_above_any_valid_tree(shared_json, shared_problem):
    data, problem = shared_problem
    rows = by_goal(shared_json)
    assert len(rows) == 25
    compared = 0
    for label, row in rows.items():
        asp = row["asp"]
        for name, r in row.items():
            if r["valid"]:
                assert asp["status"] == "optimal", label
                assert asp["cost"]["units"] <= r["cost"]["units"], (label, name)
                compared += 1
    assert compared >= 50


def test_shared_greedy_invalid_for_whipped_cream_and_fried_rice(shared_json):
    rows = by_goal(shared_json)
    for label in ("whipped cream", "fried rice"):
        assert rows[label]["asp"]["status"] == "unreachable"
        assert rows[label]["ids"]["status"] == "not-found"
        for name in ("gbfs-h1", "gbfs-h2"):
            r = rows[label][name]
            assert r["status"] == "found" and r["valid"] is False
            assert r["problem"].startswith("circular support")
    assert "packet, contains {carrot,corn,green pea}" in rows["fried rice"]["gbfs-h1"]["problem"]


def test_shared_ids_never_invalid(shared_json):
    for r in shared_json:
        if r["method"] == "ids" and r["status"] == "found":
            assert r["valid"]


def test_shared_restricted_grounding_gives_the_same_optimum(shared_json, shared_problem):
    data, problem = shared_problem
    session = Session(problem)  # the whole FOON grounded
    rows = by_goal(shared_json)
    for obj, _ in data.goals:
        tree = session.solve(problem.foon.object_ids[obj])
        asp = rows[obj.label]["asp"]
        assert tree.status == asp["status"], obj.label
        assert tree.cost.get("units") == asp["cost"].get("units"), obj.label


def test_shared_text_csv_markdown(shared_foon_dir, shared_json):
    text = cli("compare", "--data", shared_foon_dir, "--format", "text").stdout  # --goals all by default
    lines = text.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("goal "))
    table = lines[head + 2 : head + 27]
    assert [line.split("  ")[0].strip() for line in table] == list(by_goal(shared_json))
    assert lines[head].split()[-2:] == ["asp", "optimum"]
    assert "asp optimum <= every valid tree: yes" in text
    rows = list(csv.DictReader(io.StringIO(cli("compare", "--data", shared_foon_dir, "--format", "csv").stdout)))
    assert len(rows) == 100
    assert [r["valid"] == "true" for r in rows] == [r["valid"] for r in shared_json]
    md = cli(
        "compare", "--data", shared_foon_dir, "--goal", "macaroni", "--methods", "gbfs-h2,asp", "--format", "markdown"
    ).stdout
    assert "| goal | gbfs-h2 | asp optimum |" in md
    assert "| macaroni |" in md
