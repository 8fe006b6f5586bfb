"""Grouped decisions: the goals whose bounds tree meets their lower bound, decided by one clingo
call (``encodings/decide_many.lp``), answer exactly as each goal's own search answers it."""

from __future__ import annotations

import importlib
import json
import time
from dataclasses import replace

import pytest

import foon2asp
from foon2asp.asp.decisions import decide
from foon2asp.asp.grounding import Decisions
from foon2asp.asp.options import AspOptions
from foon2asp.asp.prepared import Preparation
from foon2asp.batch.pool import BatchSpec, Worker
from foon2asp.methods.plan import decisions, plan, request
from foon2asp.methods.runner import GoalRunner
from foon2asp.tree.serialize import tree_json
from foon2asp.tree.validate import validate
from helpers import build, goal_id
from test_runner import made_objects, optimum, random_foon, score

#: the objectives whose bounds decide goals at the bounds tree's cost
DECIDED = [("units",), ("success",), ("inputs",)]


def answer(problem, tree) -> tuple[dict, dict]:
    """The JSON of ``tree`` without its time, and its statistics without the plan."""
    record = tree_json(problem, tree)
    record.pop("time_s", None)
    stats = record.pop("stats", {})
    return record, {k: v for k, v in stats.items() if k != "plan"}


def grouped(tree) -> int:
    """How many goals the call that decided ``tree`` decided (0: its own search answered it)."""
    return tree.stats.get("plan", {}).get("decided_with", 0)


@pytest.mark.parametrize("objective", DECIDED, ids=",".join)
def test_grouped_decisions_answer_as_each_goal_alone_and_optimally(objective):
    """Over random small FOONs with real choice: planned ahead, the goals decided together get the
    answer, statistics and proof their own search gives, the brute-force optimum, a valid tree."""
    together = 0
    for seed in range(25):
        problem = random_foon(seed)
        goals = made_objects(problem)
        options = AspOptions(objective=objective)
        ahead, alone = GoalRunner("asp", problem, options), GoalRunner("asp", problem, options)
        for goal, tree in zip(goals, ahead.each(goals), strict=True):
            own = alone(goal)
            assert answer(problem, tree) == answer(problem, own), (seed, goal)
            if grouped(tree):
                together += 1
                assert grouped(own) == 0
                assert tree.status == "optimal" and tree.proven_by == "clingo", (seed, goal)
                assert validate(problem, goal, tree.units).valid, (seed, goal)
                want = optimum(problem, goal, objective)
                assert score(problem, goal, tree.units, objective) == want, (seed, goal)
    assert together >= 10, "too few goals were decided together to test anything"


def test_the_plan_groups_exactly_the_goals_decided_at_their_bound():
    """``decisions`` takes the prepared plans with a bound (a bounds tree that meets the lower
    bound) and nothing else; none for fewer than two, with progress reports or user programs."""
    for seed in range(25):  # a FOON with two goals decided at their bound and one searched
        problem = random_foon(seed)
        goals = made_objects(problem)
        req = request("asp", problem, AspOptions())
        plans = [plan(req, g) for g in goals]
        bounded = [p.goal[0] for p in plans if p.route == "prepared" and p.grounding.prepared.bound is not None]
        if len(bounded) >= 2 and any(p.route == "prepared" and p.goal[0] not in bounded for p in plans):
            break
    else:
        pytest.fail("no random FOON has goals of both kinds")
    group = decisions(req, plans)
    assert group is not None and [g.prepared.goal for g in group.groundings] == bounded
    assert group.entry == "decide_many" and "--heuristic=Domain" in group.args
    single = [p for p in plans if p.goal[0] == bounded[0]]
    assert decisions(req, single) is None
    reporting = request("asp", problem, AspOptions(progress=lambda report: None))
    assert decisions(reporting, [plan(reporting, g) for g in goals]) is None
    constrained = request("asp", problem, AspOptions(programs=[("none.lp", ":- use(U), unit(U), U < 0.\n")]))
    assert decisions(constrained, [plan(constrained, g) for g in goals]) is None


# the cycle 0, 1 (x -> g, g -> x) and the chain 2, 3, 4 (k -> a -> b -> g)
LOOP = [("m0", ["x"], ["g"]), ("m1", ["g"], ["x"]), ("m2", ["k"], ["a"]), ("m3", ["a"], ["b"]), ("m4", ["b"], ["g"])]


def test_a_set_that_rests_on_a_cycle_is_left_to_its_own_search():
    """A goal whose set within the bound is a closed set on a cycle is not decided; the others are."""
    problem = build(LOOP + [("m5", ["k"], ["c"]), ("m6", ["k"], ["c"])], ["k"])
    req = request("asp", problem, AspOptions())
    g, c = goal_id(problem, "g"), goal_id(problem, "c")
    # the cycle as the hint, tried first, with a bound it meets
    cycle = Preparation(g, (0, 1, 2, 3, 4), hint=(0, 1), known=(2,), meets=lambda cost: True)
    other = Preparation(c, (5, 6), hint=(5,), known=(1,), meets=lambda cost: True)
    groundings = (replace(plan(req, g).grounding, prepared=cycle), replace(plan(req, c).grounding, prepared=other))
    assert decide(Decisions(problem, ("units",), groundings)) == {c}
    # the chain as the hint: both decided
    chain = replace(cycle, hint=(2, 3, 4), known=(3,))
    assert decide(Decisions(problem, ("units",), (replace(groundings[0], prepared=chain), groundings[1]))) == {g, c}


def test_a_decision_that_decides_nothing_leaves_every_goal_to_its_own_search(monkeypatch):
    """A grouped decision cut short (or finding no model) decides no goal: each is searched alone."""
    problem = next(
        p
        for p in map(random_foon, range(25))
        if sum(map(grouped, GoalRunner("asp", p, AspOptions()).each(made_objects(p))))
    )
    goals = made_objects(problem)
    monkeypatch.setattr(importlib.import_module("foon2asp.methods.runner"), "decide", lambda group: set())
    ahead = GoalRunner("asp", problem, AspOptions())
    alone = GoalRunner("asp", problem, AspOptions())
    trees = list(ahead.each(goals))
    assert not any(grouped(t) for t in trees)
    assert [answer(problem, t) for t in trees] == [answer(problem, alone(g)) for g in goals]


def test_a_worker_block_answers_as_goal_by_goal(shared_foon_dir):
    """A batch worker handed a block of tasks (a Dask chunk) decides its goals together and writes
    the lines it writes goal by goal, but for the time and the plan."""
    kb = foon2asp.load(str(shared_foon_dir))
    goals = kb.goal_ids("all-objects")[:400]
    spec = BatchSpec(kb.problem, ["asp"], AspOptions(), "per-goal")
    tasks = [(g, "asp") for g in goals]
    block = [json.loads(line) for line in Worker(spec).run_block(tasks)]
    one = Worker(spec)
    each = [json.loads(one.run(g, m)) for g, m in tasks]
    decided = sum(bool(r.get("stats", {}).get("plan", {}).get("decided_with")) for r in block)
    assert decided >= 50
    for a, b in zip(block, each, strict=True):
        for r in (a, b):
            r.pop("time_s", None)
            r.get("stats", {}).pop("plan", None)
        assert a == b


def test_a_goal_planned_ahead_counts_its_planning_in_its_time(monkeypatch):
    """Planned ahead, a goal's time still holds its planning (each plan here takes 20 ms)."""
    problem = random_foon(5)
    goals = made_objects(problem)
    runner_mod = importlib.import_module("foon2asp.methods.runner")
    slow = runner_mod.plan

    def planned(req, goal):
        time.sleep(0.02)
        return slow(req, goal)

    monkeypatch.setattr(runner_mod, "plan", planned)
    trees = list(GoalRunner("asp", problem, AspOptions()).each(goals))
    assert len(trees) == len(goals) and all(t.time_s >= 0.02 for t in trees)


def test_planning_ahead_stops_at_its_budget_so_the_first_answer_does_not_wait(monkeypatch):
    """With plans of 20 ms and 50 ms to plan ahead, the first answer comes after a few plans, not
    after the plans of every goal; every goal is still answered, once, as alone."""
    problem = random_foon(5)
    goals = made_objects(problem)
    runner_mod = importlib.import_module("foon2asp.methods.runner")
    slow, calls = runner_mod.plan, []

    def planned(req, goal):
        calls.append(goal)
        time.sleep(0.02)
        return slow(req, goal)

    monkeypatch.setattr(runner_mod, "plan", planned)
    monkeypatch.setattr(runner_mod, "AHEAD_S", 0.05)
    answers = GoalRunner("asp", problem, AspOptions()).each(goals)
    first = next(answers)
    assert 1 <= len(calls) <= 4 < len(goals)
    trees = [first, *answers]
    assert sorted(calls) == sorted(goals)  # each goal planned once
    alone = GoalRunner("asp", problem, AspOptions())
    assert [answer(problem, t) for t in trees] == [answer(problem, alone(g)) for g in goals]
