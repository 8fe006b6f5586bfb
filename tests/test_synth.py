"""The hard FOON generator of bench/synth.py: seeded presets with real choice."""

from __future__ import annotations

import pytest

import foon2asp
from foon2asp.api import KnowledgeBase
from synth import PRESETS, preset, shape


@pytest.fixture(scope="module")
def tiny() -> KnowledgeBase:
    syn = preset("tiny")
    return KnowledgeBase(syn.dataset(), syn.problem())


def test_presets_are_seeded_and_have_real_choice():
    a, b = preset("small"), preset("small")
    assert [str(u) for u in a.foon.units] == [str(u) for u in b.foon.units]
    assert a.goals == b.goals
    assert set(PRESETS) >= {"tiny", "small", "hard-4k", "hard-10k"}
    s = shape(a.problem())
    assert s["units"] == 404 and s["objects"] == 466
    assert s["producers_per_object"] > 1.4 and s["cycles"] >= 2
    hard = preset("hard-4k")
    h = shape(hard.problem())
    assert 4000 <= h["units"] <= 4010 and 5000 <= h["objects"] <= 5200 and h["cycles"] >= 2
    assert len(hard.goals) == 21  # 20 goals with choice and one that nothing can make
    with pytest.raises(foon2asp.InputError):
        preset("nope")


def test_a_written_preset_loads_with_the_same_optima(tmp_path, tiny):
    preset("tiny").write(tmp_path / "tiny")
    kb = foon2asp.load(tmp_path / "tiny")
    assert (len(kb.problem.units), len(kb.problem.objects), len(kb.goals)) == (62, 89, 7)
    here = [t.cost.get("units") for t in kb.solve("all")]
    there = [t.cost.get("units") for t in tiny.solve("all")]
    assert here == there and here[-1] is None and all(here[:-1])
