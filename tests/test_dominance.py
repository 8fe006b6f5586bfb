"""Dominated units (foon2asp.asp.dominance, encodings/dominance.lp): forbidding them keeps
the optimum and the canonical tree, checked against brute force and against sessions
that ground no dominance."""

from __future__ import annotations

import pytest

from foon2asp.asp import dominance
from foon2asp.asp.facts import neglog_weight
from foon2asp.asp.options import AspOptions
from foon2asp.foon.problem import Problem
from foon2asp.methods.plan import grounding
from foon2asp.methods.plan import session_of as Session
from foon2asp.tree.tasktree import measures
from helpers import brute_force, goal_part
from synth import preset

#: a user program that changes nothing but switches dominance off (a program may forbid anything)
NOOP = ("noop", "% nothing\n")

OBJECTIVES = [("units",), ("success",), ("inputs",), ("depth",), ("depth", "success"), ("success", "inputs")]


@pytest.fixture(scope="module")
def tiny() -> tuple[Problem, list[int]]:
    syn = preset("tiny")
    p = syn.problem()
    return p, [p.foon.object_ids[g] for g in syn.goals]


@pytest.fixture(scope="module")
def small() -> tuple[Problem, list[int]]:
    syn = preset("small")
    p = syn.problem()
    return p, [p.foon.object_ids[g] for g in syn.goals]


def test_pairs_are_cheaper_earlier_producers_from_fewer_inputs(small):
    p, goals = small
    units = p.units_for(goals)
    for ranked in (("units",), ("success", "inputs")):
        pairs = dominance.dominance_pairs(p, units, ranked)
        assert pairs
        for v, u, extra in pairs:
            cheaper = neglog_weight(p.rates[v]) < neglog_weight(p.rates[u]) or len(p.inputs[v]) < len(p.inputs[u])
            assert v < u or ("success" in ranked and cheaper)
            assert {i for i in p.required[v] if i not in p.kitchen} <= set(p.required[u])
            assert set(p.products[u]) - set(p.products[v]) - p.kitchen == set(extra)
            assert set(p.products[u]) & set(p.products[v])
            if "success" in ranked:
                assert neglog_weight(p.rates[v]) <= neglog_weight(p.rates[u])
                assert len(p.inputs[v]) <= len(p.inputs[u])
    assert any(v > u for v, u, _ in dominance.dominance_pairs(p, units, ("success",)))


def _dominated_by_definition(p: Problem, goal: int, pool: list[int], ranked: tuple[str, ...]) -> set[int]:
    """The module docstring's rule read straight off, over the units of ``pool`` alone."""
    kitchen = p.kitchen
    relevant = {goal}.union(*(p.required[u] for u in pool))
    weigh = [objectives_weight(p, name) for name in ranked if name != "depth"]
    out = set()
    for u in pool:
        need_u = set(p.required[u]) - kitchen
        made_u = set(p.products[u]) - kitchen
        for v in pool:
            made_v = set(p.products[v]) - kitchen
            if v == u or not made_u & made_v or not set(p.required[v]) - kitchen <= need_u:
                continue
            if any(w(v) > w(u) for w in weigh) or (v > u and not any(w(v) < w(u) for w in weigh)):
                continue
            if relevant.isdisjoint(made_u - made_v):
                out.add(u)
    return out


def objectives_weight(p: Problem, name: str):
    return {
        "units": lambda u: 1,
        "success": lambda u: neglog_weight(p.rates[u]),
        "inputs": lambda u: len(p.inputs[u]),
    }[name]


@pytest.mark.parametrize("ranked", [("units",), ("success",), ("depth", "inputs")])
def test_one_dominators_table_for_the_problem_gives_each_parts_dominated_units(small, ranked):
    p, _ = small
    table = dominance.Dominators(p, ranked)  # over the whole problem, kept across goals
    checked = dominated = 0
    for goal in sorted(p.derivable - p.kitchen)[::3]:
        pool = sorted(p.relevant_units(goal))
        expected = _dominated_by_definition(p, goal, pool, ranked)
        assert table.dominated(goal, pool) == expected
        thinned = pool[::2]  # a pool that leaves out producers: only dominators inside it count
        assert table.dominated(goal, thinned) == _dominated_by_definition(p, goal, thinned, ranked)
        on_part = {
            u
            for v, u, extra in dominance.dominance_pairs(p, pool, ranked)
            if {goal}.union(*(p.required[x] for x in pool)).isdisjoint(extra)
        }
        assert on_part == expected
        checked += 1
        dominated += len(expected)
    assert checked > 10 and dominated > 0


def test_only_plain_optimisation_forbids_dominated_units(tiny):
    def used(**kw) -> bool:
        options = AspOptions(**kw)
        return "dominated" in grounding(tiny[0], options).facts

    assert used() and used(objective=("depth", "success"), max_depth=4)
    assert not used(programs=[NOOP])
    assert not used(human_steps=1)
    assert not used(models=2)
    assert not used(all_optimal=True)
    assert not used(heuristic="h1")


def _canonical(trees: list[tuple[int, ...]]) -> tuple[int, ...]:
    """The smallest tree in the canonical order: the tree holding the smallest unit in which two differ."""
    universe = sorted({u for t in trees for u in t})
    return min(trees, key=lambda t: [u not in t for u in universe])


def test_the_canonical_optimum_agrees_with_brute_force(tiny):
    p, _ = tiny
    checked = 0
    for g in sorted(p.derivable - p.kitchen):
        found = goal_part(p, g)
        if found is None:
            continue
        sub, sg = found
        units = sub.units_for([sg])
        if not dominance.dominance_pairs(sub, units):
            continue
        trees = brute_force(sub, sg)
        for objective in (("units",), ("success",), ("inputs",)):
            key = [o if o != "success" else "neglog" for o in objective] + ["units"]

            def cost(t: tuple[int, ...], key=key) -> list:
                m = measures(sub, sg, list(t))
                return [
                    sum(neglog_weight(sub.rates[u]) for u in t) if k == "neglog" else m[k]  # noqa: B023
                    for k in key
                ]

            top = min(cost(t) for t in trees)
            want = _canonical([t for t in trees if cost(t) == top])
            got = Session(sub, AspOptions(objective=objective, units=units)).solve(sg)
            assert got.status == "optimal"
            assert tuple(sorted(got.units)) == want, (g, objective)
        checked += 1
    assert checked >= 3


@pytest.mark.parametrize("name", ["tiny", "small"])
def test_the_same_answers_as_without_dominance(name, tiny, small):
    p, goals = tiny if name == "tiny" else small
    same = total = 0
    for objective in OBJECTIVES:
        for g in goals:
            units = p.units_for([g])
            with_ = Session(p, AspOptions(objective=objective, units=units)).solve(g)
            without = Session(p, AspOptions(objective=objective, units=units, programs=[NOOP])).solve(g)
            assert with_.status == without.status, (objective, g)
            assert with_.asp_cost == without.asp_cost, (objective, g)
            if "canonical_search" not in with_.stats and "canonical_search" not in without.stats:
                # both searches for the smallest optimal tree ended within their budget
                assert sorted(with_.units) == sorted(without.units), (objective, g)
                same += 1
            total += 1
    assert same >= total // 2
