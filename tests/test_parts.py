"""Parts: batch's automatic grounding (whole or per goal), chosen from the goals' relevant parts."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

import foon2asp
from foon2asp.api import KnowledgeBase
from foon2asp.cli.main import main
from foon2asp.methods import parts as grounding
from synth import preset


@pytest.fixture(scope="module")
def tiny() -> KnowledgeBase:
    syn = preset("tiny")
    return KnowledgeBase(syn.dataset(), syn.problem())


def test_auto_grounding_is_per_goal_on_the_shared_foon(shared_foon_dir):
    kb = foon2asp.load(shared_foon_dir)
    mode, reason = grounding.choose_grounding(kb.problem, kb.goal_ids("all-objects"))
    assert mode == "per-goal" and "under 10 %" in reason


def test_auto_grounding_is_whole_on_a_hard_preset(monkeypatch):
    syn = preset("hard-4k")
    p = syn.problem()
    goals = [p.foon.object_ids[g] for g in syn.goals]
    mode, reason = grounding.choose_grounding(p, goals)
    assert mode == "whole" and "10 % or more" in reason
    monkeypatch.setattr(grounding, "AUTO_MAX_WHOLE", 1000)
    assert grounding.choose_grounding(p, goals)[0] == "per-goal"


def test_batch_reports_the_grounding_it_chose(tmp_path, tiny):
    report = tiny.batch("all", None)
    assert report.grounding == "whole" and "viable units" in report.grounding_reason
    assert [r["status"] for r in report.records] == ["optimal"] * 6 + ["unreachable"]
    res = CliRunner().invoke(main, ["batch", "--data", "demo", "--goals", "all", "-o", str(tmp_path / "r.jsonl")])
    assert "grounding: " in res.output and "(auto: " in res.output
    fixed = tiny.batch("all", None, grounding="per-goal")
    assert fixed.grounding == "per-goal" and fixed.grounding_reason == ""
    assert [r["units"] for r in fixed.records] == [r["units"] for r in report.records]
