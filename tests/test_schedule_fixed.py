"""Schedules with a person among the agents: bounds against brute force, the goals of
../shared/foon proven at once, list schedules that pick the faster agent, the default time
limit and the status line."""

from __future__ import annotations

import random
import time

import pytest

import foon2asp
from conftest import REPO
from foon2asp.cli.goal_commands import status_text
from foon2asp.schedule import ScheduleSpec, schedule
from foon2asp.schedule import solve as solve_mod
from foon2asp.schedule.baseline import earliest_finish, known_schedule, list_schedule
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.instances import instance, makespan
from foon2asp.schedule.lower_bounds import bounds, human_lower
from foon2asp.schedule.result import ScheduleResult
from foon2asp.schedule.spec import Durations
from helpers import build, goal_id
from test_cli import run
from test_schedule_solve import AGENT_SETS, ENCODINGS, brute_schedule, given, random_spec, random_tree

TABLE = REPO / "bench" / "durations.json"


def test_a_fast_person_and_a_slow_arm_are_not_two_agents_of_the_person_speed():
    """Three independent units, 1 s for the person and 10 s for the arm: the person does all
    three (3 s).  Counting both agents at the person's speed would allow 2 s."""
    problem = build([("cut", ["k"], ["a"]), ("cut", ["k"], ["b"]), ("cut", ["k"], ["c"])], ["k"])
    spec = ScheduleSpec((("arm", 1), ("human", 1)), Durations({"cut": 10000}, {"human": {"cut": 1000}}))
    inst = instance(problem, [0, 1, 2], spec)
    assert bounds(inst).lower == 3000 == brute_schedule(problem, [0, 1, 2], spec)[0]
    assert human_lower(inst, 3000) == 3  # the arm cannot end a unit within 3 s
    r = schedule(problem, given(problem, goal_id(problem, "a"), [0, 1, 2]), spec, shortcut=False)
    assert (r.status, r.makespan, len(r.human), r.human_units_proven) == ("optimal", 3000, 3, True)


@pytest.mark.parametrize("seed, knife", [(4000 + s, 0.5) for s in range(40)] + [(900 + s, 0.6) for s in range(40)])
def test_the_bounds_with_a_person_are_at_most_brute_force(seed, knife):
    """The energetic bound with each unit on one kind (and over the pools of units only some
    kinds can do or that share a resource, bounds.pools), and the fewest human units at the
    optimal makespan (bounds.human_lower), never exceed what brute force finds."""
    rng = random.Random(seed)
    kinds = AGENT_SETS[2 + seed % 2]  # an arm or two and a person
    problem, _, units = random_tree(rng, 4 if seed % 2 else 5, knife=knife)
    spec = random_spec(rng, kinds)
    want = brute_schedule(problem, units, spec)
    inst = instance(problem, units, spec)
    if want is None:
        assert inst.incapable()
        return
    assert bounds(inst).lower <= want[0]
    assert human_lower(inst, want[0]) <= want[1]


@pytest.mark.parametrize("seed", range(16))
def test_two_phases_with_a_person_equal_brute_force(seed):
    """Makespan first, then the human units within it: both encodings give brute force's pair."""
    rng = random.Random(5000 + seed)
    kinds = AGENT_SETS[2 + seed % 2]
    problem, goal, units = random_tree(rng, 4 if seed % 2 else 5, knife=0.4)
    spec = random_spec(rng, kinds)
    want = brute_schedule(problem, units, spec)
    if want is None:
        return
    for encoding in ENCODINGS:
        r = schedule(problem, given(problem, goal, units), spec, encoding=encoding, shortcut=False)
        assert r.status == "optimal" and r.human_units_proven, (encoding, r.stats)
        assert (r.makespan, len(r.human)) == want, encoding
        assert check_schedule(problem, r.to_dict(), spec) is None


@pytest.mark.parametrize("seed", range(30))
def test_list_schedules_that_pick_the_faster_agent_are_valid(seed):
    """earliest_finish and known_schedule, with capabilities, a shared knife and a person:
    the independent checker accepts them, and the known schedule is never longer than the
    baseline."""
    rng = random.Random(6000 + seed)
    problem, goal, units = random_tree(rng, rng.randint(3, 9), knife=0.5)
    spec = random_spec(rng, AGENT_SETS[seed % len(AGENT_SETS)])
    inst = instance(problem, units, spec)
    if inst.incapable():
        return
    tree = given(problem, goal, units)
    agents = [name for name, _ in inst.agents]
    known, _ = known_schedule(inst, bounds(inst).lower)
    assert makespan(known) <= makespan(list_schedule(inst))
    for entries in (earliest_finish(inst), known):
        found = ScheduleResult(problem, tree, "feasible", agents, entries)
        assert check_schedule(problem, found.to_dict(), spec) is None


@pytest.fixture(scope="module")
def shared_kb(shared_foon_dir):
    return foon2asp.load(shared_foon_dir)


@pytest.mark.parametrize("label", ["shrimp mango salad", "beef stroganoff", "french toast"])
def test_shared_goals_on_two_arms_and_a_person_are_proven_at_once(shared_kb, label):
    """Every unit 1 s: the makespan meets its bound and the human units the fewest a person
    must do there, so the answer is proven in well under a second (one lexicographic
    optimisation did not prove it within a minute)."""
    kb = shared_kb
    tree = kb.solve(label).raw
    spec = ScheduleSpec((("arm", 2), ("human", 1)))
    t0 = time.perf_counter()
    r = schedule(kb.problem, tree, spec, time_limit=30)
    assert time.perf_counter() - t0 < 5
    assert r.status == "optimal" and r.human_units_proven, r.stats
    assert r.makespan == r.bounds.lower and len(r.human) == human_lower(
        instance(kb.problem, tree.units, spec), r.makespan
    )
    assert check_schedule(kb.problem, r.to_dict(), spec) is None
    assert "fewest human units" not in r.to_text()


def test_without_a_time_limit_a_schedule_stops_at_the_default(shared_kb, monkeypatch):
    """No time limit given: the default ends the search (60 s; here 1 s) with the best schedule
    and its lower bound; --help says so."""
    monkeypatch.setattr(solve_mod, "DEFAULT_TIME_LIMIT", 1.0)
    kb = shared_kb
    t0 = time.perf_counter()
    got = kb.schedule("shrimp mango salad", agents="arm=2,human=1", durations=TABLE)
    assert time.perf_counter() - t0 < 15
    assert got.status in ("feasible", "optimal")
    d = got.to_dict()
    assert d["bounds"]["lower"] <= d["makespan"] < d["baseline"]["makespan"]
    if got.status == "feasible":
        assert f"lower bound {d['bounds']['lower']:g} s" in got.to_text()
    flat = " ".join(run("schedule", "--help").output.split())
    assert "Without it the tree has no limit and each schedule solve 60 s." in flat


def test_the_status_line_shows_the_makespan_and_its_bound(shared_foon_dir):
    """--progress: a line on stderr with the best makespan and the lower bound as they improve,
    then the human units and the fewest a person must do."""
    res = run(
        "schedule", "--data", shared_foon_dir, "--goal", "greek salad", "--agents", "arm=2,human=1",
        "--durations", TABLE, "--progress", "--time-limit", "30",
    )  # fmt: skip
    lines = res.stderr.replace("\r", "\n")
    assert "schedule greek salad: makespan 57 s, lower bound 55 s" in lines  # the list schedule, at once
    assert "Status: optimal  Makespan: 55 s" in res.stdout
    human = {"goal": "x", "makespan": 40000, "lower": 40000, "human": 15, "human_lower": 11, "phase": "human"}
    assert status_text(human) == "schedule x: makespan 40 s (proven), human units 15, at least 11"
