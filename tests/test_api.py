"""The library API: the contract names, the same answers as the CLI, docs/api.md executed."""

from __future__ import annotations

import json
import os

import pytest
from click.testing import CliRunner

import foon2asp
from foon2asp.cli.main import main
from foon2asp.tree.validate import bounds_proof
from helpers import real_choice


@pytest.fixture(scope="module")
def kb(shared_foon_dir):
    return foon2asp.load(shared_foon_dir)


def test_contract_answers(kb):
    t = kb.solve("greek salad")
    assert (t.status, t.cost["units"], len(t.units)) == ("optimal", 25, 25)
    assert kb.check(t).valid
    assert kb.solve("macaroni", objective="success").cost["success"] == 0.02187
    w = kb.missing("whipped cream")
    assert w.status == "optimal" and len(w.missing) == 1
    assert sum(kb.reachable().values()) == 23
    comparison = kb.compare(goals="all")
    assert sum(1 for x in comparison.trees if x.method == "gbfs-h1" and x.valid is False) == 10
    assert len(kb.goals) == 25 and len(kb.objects("scrambled egg")) == 15


def test_units_are_in_executable_order(kb):
    t = kb.solve("macaroni and cheese")
    had = set(kb.problem.kitchen)
    for u in t.unit_ids:
        assert all(i in had for i in kb.problem.required[u])
        had.update(kb.problem.products[u])
    assert t.goal_id in had


def test_to_dict_is_the_cli_json(kb, shared_foon_dir):
    res = CliRunner().invoke(main, ["solve", "--data", str(shared_foon_dir), "--goals", "all", "--format", "json"])
    assert res.exit_code == 0, res.output
    cli = json.loads(res.output)
    lib = [t.to_dict() for t in kb.solve("all")]
    strip = lambda d: {k: v for k, v in d.items() if k not in ("time_s", "stats")}  # noqa: E731
    assert [strip(d) for d in cli] == [strip(d) for d in lib]


def test_tree_proven_by_says_who_proved_each_reference_goal(kb):
    """``tree.proven_by`` is the JSON field; every reference goal with a choice in its part is
    clingo's, also one whose landmarks alone make it (one minimal tree, verified beside)."""
    trees = kb.solve("all")
    assert all(t.proven_by == t.to_dict()["proven_by"] for t in trees)
    counts: dict[str | None, int] = {}
    for t in trees:
        counts[t.proven_by] = counts.get(t.proven_by, 0) + 1
    assert counts == {"clingo": 21, "only-tree": 2, "fixpoint": 2}
    for t in trees:
        if t.proven_by == "clingo":
            assert "landmarks" not in t.to_dict(), t.goal_id
            if not real_choice(kb.problem, t.goal_id, t.unit_ids):  # one minimal tree: its landmarks
                assert bounds_proof(kb.problem, t.goal_id, t.unit_ids, t.unit_ids) is None
    assert {t.status for t in trees if t.proven_by == "fixpoint"} == {"unreachable"}


def test_goal_forms_name_the_same_object(kb):
    egg = kb.objects("scrambled egg")[3]
    oid = kb.object_id(egg)
    assert kb.object_id(str(egg)) == oid == kb.object_id(f"#{oid}") == kb.object_id(oid)
    with pytest.raises(foon2asp.InputError, match="scrambled egg"):
        kb.object_id("scrambled egg")


def test_several_goals_give_a_list(kb):
    trees = kb.solve(["greek salad", "ice"])
    assert isinstance(trees, list) and [t.cost["units"] for t in trees] == [25, 1]


def test_bad_input_is_input_error(tmp_path):
    with pytest.raises(foon2asp.InputError):
        foon2asp.load(tmp_path / "nowhere")
    with pytest.raises(foon2asp.InputError):
        foon2asp.load("demo").solve("tomato salad", objective="fastest")


def test_version_in_one_place():
    from importlib.metadata import version

    assert foon2asp.__version__ == version("foon2asp") or os.environ.get("PYTHONPATH")


def test_check_of_a_file_with_one_tree_is_a_report(kb, tmp_path):
    """``kb.check("tree.txt")`` gives a report with .valid; several trees give a list."""
    one = tmp_path / "one.foon"
    one.write_text(kb.solve("greek salad").to_foon())
    report = kb.check(one)
    assert not isinstance(report, list) and report.valid and report.optimum.cost["units"] == 25
    both = tmp_path / "both.foon"
    both.write_text("".join(t.to_foon() for t in kb.solve(["greek salad", "macaroni"])))
    reports = kb.check(both)
    assert isinstance(reports, list) and [r.valid for r in reports] == [True, True]
    assert [r.valid for r in kb.check_all(one)] == [True]


def test_every_answer_renders_or_says_it_cannot(kb, tmp_path):
    """A one-record answer renders as its command does for one goal; a method an answer lacks is
    an AttributeError naming the one it has; consolidate's mistyped keyword fails before reading."""
    missing = kb.missing("greek salad")
    assert missing.render("text") == missing.to_text()
    assert json.loads(missing.render("json")) == [missing.to_dict()]
    tree = tmp_path / "tree.foon"
    tree.write_text(kb.solve("greek salad").to_foon())
    report = kb.check(tree)
    assert report.valid and json.loads(report.render("json")) == [report.to_dict()]
    with pytest.raises(AttributeError, match="use render"):
        kb.compare("greek salad").to_dict()
    with pytest.raises(TypeError, match="consolidate\\(\\): .*did you mean 'level'"):
        foon2asp.consolidate([tmp_path / "absent.json"], levle=2)


def test_solve_honours_shortcuts_false_with_the_same_trees(kb):
    """``shortcuts=False`` (a keyword or in ``Options``): clingo answers the goals that polynomial
    reasoning would settle (the only trees), and proves the same trees; check's optimum too."""
    settled = kb.solve("all")
    assert {t.raw.proven_by for t in settled} >= {"only-tree"}
    for free in (kb.solve("all", shortcuts=False), kb.solve("all", options=foon2asp.Options(shortcuts=False))):
        assert [t.raw.proven_by for t in free] == ["clingo" if t.has_tree else t.raw.proven_by for t in settled]
        assert [sorted(t.unit_ids) for t in free] == [sorted(t.unit_ids) for t in settled]
        assert [t.raw.asp_cost for t in free] == [t.raw.asp_cost for t in settled]
    only = next(t for t in settled if t.raw.proven_by == "only-tree")
    assert kb.check(only).optimum.raw.proven_by == "only-tree"
    assert kb.check(only, options=foon2asp.Options(shortcuts=False)).optimum.raw.proven_by == "clingo"


def test_solve_honours_the_grounding_asked():
    """``grounding="per-goal"``: clingo's route grounds each goal's part (``stats.plan.shared``
    false), ``whole`` and ``auto`` one grounding for the goals asked; the trees are the same."""
    demo = foon2asp.load("demo")
    trees = {g: demo.solve("all", objective="depth", grounding=g) for g in ("auto", "whole", "per-goal")}
    shared = {g: {t.raw.stats["plan"]["shared"] for t in ts if t.has_tree} for g, ts in trees.items()}
    assert shared == {"auto": {True}, "whole": {True}, "per-goal": {False}}
    units = {g: [sorted(t.unit_ids) for t in ts] for g, ts in trees.items()}
    assert units["per-goal"] == units["whole"] == units["auto"] and any(units["whole"])
