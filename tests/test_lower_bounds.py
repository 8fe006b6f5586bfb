"""The lower bounds and the fixed-tree shortcut against their plain versions, and a joint search cut short."""

from __future__ import annotations

import json
import math
import random
import time

import pytest
from hypothesis import given as hgiven
from hypothesis import settings
from hypothesis import strategies as st

import foon2asp
from conftest import REPO
from foon2asp.cli.goal_commands import status_text
from foon2asp.schedule import ScheduleSpec, schedule
from foon2asp.schedule import solve as solve_mod
from foon2asp.schedule.baseline import earliest_finish, known_schedule, list_schedule
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.instances import divisor, earliest, instance, makespan, tails
from foon2asp.schedule.lower_bounds import bounds, energy_over, human_lower, kind_energy, window_length
from foon2asp.schedule.result import ScheduleResult
from foon2asp.schedule.spec import Durations
from helpers import build, goal_id
from test_cli import run
from test_solve import AGENT_SETS, ENCODINGS, brute_schedule, given, random_spec, random_tree


def _window_length(c: list[float], m: int) -> float:
    """The plain formula: the least L > 0 with sum(min(c_i, L)) <= m L, scanning the sorted
    parts (L in [c[j-1], c[j]) has n - j parts longer than L)."""
    c = sorted(x for x in c if x > 0)
    n = len(c)
    prefix = 0.0
    for j in range(n + 1):
        slope = m - (n - j)
        low = c[j - 1] if j else 0
        high = c[j] if j < n else math.inf
        if slope > 0:
            root = max(low, prefix / slope)
            if root < high or j == n:
                return root
        if j < n:
            prefix += c[j]
    return math.inf


def _plain_energy(inst, start, tail, floor, step) -> int:
    """Energetic reasoning written out loop by loop, every unit a part of its own."""
    m = len(inst.agents)
    d = {u: inst.min_duration(u) for u in inst.units}
    gaps = []
    for a in sorted({start[u] for u in inst.units}):
        for b in sorted({tail[u] - d[u] for u in inst.units}):
            length = _window_length([min(d[u], start[u] + d[u] - a, tail[u] - b) for u in inst.units], m)
            if length > 0:
                gaps.append((a + b, a + b + length))
    best = -(-floor // step) * step
    moved = True
    while moved:
        moved = False
        for low, high in gaps:
            if low < best < high:
                best = math.ceil(high / step) * step
                moved = True
    return best


def _single_units(inst, start, tail, floor) -> int:
    """Energetic reasoning over parts of one unit each, at least durations on every agent."""
    d = {u: inst.min_duration(u) for u in inst.units}
    return energy_over([[u] for u in inst.units], d, start, tail, len(inst.agents), floor, divisor(inst))


@pytest.mark.parametrize("m", [1, 2, 3])
def test_window_lengths_equal_the_plain_formula(m):
    rng = random.Random(m)
    rows = [[rng.choice([0, 0.5, 1, 2, 3, 5]) for _ in range(rng.randint(1, 7))] for _ in range(200)]
    for row in rows:
        got = window_length(row, m)
        assert got == pytest.approx(_window_length(row, m)), row


@settings(max_examples=200, deadline=None)
@hgiven(st.lists(st.integers(0, 12), max_size=8), st.integers(1, 4))
def test_window_length_is_the_least_window_that_holds_the_parts(c, m):
    """The formula against the plain scan, and the window it gives holds the parts."""
    got = window_length(c, m)
    assert got == pytest.approx(_window_length(c, m))
    if 0 < got < math.inf:
        assert sum(min(x, got) for x in c) <= m * got + 1e-9


@settings(max_examples=40, deadline=None)
@hgiven(st.integers(0, 10**6))
def test_energy_bound_equals_the_loops(seed):
    """The energetic bound of random trees equals the one written out loop by loop; with
    several kinds, the bound with kinds is at least it and at most brute force."""
    rng = random.Random(seed)
    problem, _, units = random_tree(rng, rng.randint(2, 5), knife=0.0)
    spec = random_spec(rng, AGENT_SETS[seed % 4])
    spec = ScheduleSpec(spec.agents, spec.durations, {}, {})
    inst = instance(problem, units, spec)
    if inst.incapable():
        return
    start, tail = earliest(inst), tails(inst)
    b = bounds(inst)
    floor = max(b.chain, b.work)
    plain = _plain_energy(inst, start, tail, floor, divisor(inst))
    assert _single_units(inst, start, tail, floor) == plain
    assert plain <= kind_energy(inst, start, tail, plain, divisor(inst)) <= brute_schedule(problem, units, spec)[0]


@pytest.mark.parametrize("seed", range(12))
def test_energy_over_single_units_equals_the_tree_bound(seed):
    """With every unit a part of its own and the tree's own tails, the energetic bound over
    parts is the fixed tree's, and equals the one written out loop by loop."""
    rng = random.Random(seed)
    problem, _, units = random_tree(rng, rng.randint(3, 9), knife=0.0)
    spec = random_spec(rng, AGENT_SETS[seed % 2])
    spec = ScheduleSpec(spec.agents, spec.durations, {}, {})
    inst = instance(problem, units, spec)
    start, tail = earliest(inst), tails(inst)
    b = bounds(inst)
    floor = max(b.chain, b.work)
    got = _single_units(inst, start, tail, floor)
    assert got == b.energy
    assert got == _plain_energy(inst, start, tail, floor, divisor(inst))


def test_perturbed_list_schedules_are_never_longer_and_the_same_every_time():
    rng = random.Random(7)
    for _ in range(20):
        problem, _, units = random_tree(rng, rng.randint(4, 10), knife=0.3)
        spec = random_spec(rng, AGENT_SETS[rng.randint(0, 3)])
        inst = instance(problem, units, spec)
        if inst.incapable():
            continue
        target = bounds(inst).lower
        one, two = known_schedule(inst, target)[0], known_schedule(inst, target)[0]
        assert one == two
        assert target <= makespan(one) <= makespan(list_schedule(inst))


def test_a_perturbed_list_schedule_at_the_lower_bound_is_the_optimum():
    """Trees where plain list scheduling misses the lower bound and a perturbed one meets it:
    the shortcut answer equals the solver's and brute force."""
    rng = random.Random(11)
    found = 0
    for _ in range(400):
        problem, goal, units = random_tree(rng, rng.randint(4, 6), knife=0.0)
        spec = ScheduleSpec(
            (("arm", 2),), Durations({m: rng.choice([500, 1000, 1500, 2000, 3000]) for m in ("chop", "pour", "mix")})
        )
        inst = instance(problem, units, spec)
        b = bounds(inst)
        if makespan(list_schedule(inst)) == b.lower or makespan(known_schedule(inst, b.lower)[0]) > b.lower:
            continue
        found += 1
        tree = given(problem, goal, units)
        fast, slow = schedule(problem, tree, spec), schedule(problem, tree, spec, shortcut=False)
        assert "perturbed" in fast.stats["shortcut"] and fast.status == slow.status == "optimal"
        assert fast.makespan == slow.makespan == brute_schedule(problem, units, spec)[0] == b.lower
        assert fast.baseline > fast.makespan  # the baseline stays plain list scheduling
        assert check_schedule(problem, fast.to_dict(), spec) is None
        if found == 3:
            break
    assert found >= 1


def test_a_joint_search_cut_short_bounds_every_tree(shared_foon_dir, tmp_path):
    """Chocolate chip muffin on two arms with the duration table (less its person's table: no
    agent is a person): the joint search takes seconds; cut at 0.1 s its answer says how short any
    tree could be, no more than the proven optimum."""
    kb = foon2asp.load(shared_foon_dir)
    table = tmp_path / "durations.json"
    durations = json.loads((REPO / "bench" / "durations.json").read_text())
    table.write_text(json.dumps({k: v for k, v in durations.items() if k != "human"}))
    full = kb.schedule("chocolate chip muffin", agents="arm=2", durations=table, joint=True)
    cut = kb.schedule("chocolate chip muffin", agents="arm=2", durations=table, joint=True, time_limit=0.1)
    assert full.status == "optimal" and full.raw.joint_bound is None and "joint_bound" not in full.to_dict()
    assert cut.status == "feasible" and cut.makespan >= full.makespan
    d = cut.to_dict()
    assert d["joint_bound"] <= full.makespan and d["joint_bound"] <= d["makespan"]
    assert f"Every tree: at least {d['joint_bound']:g} s" in cut.to_text()


@pytest.mark.parametrize("seed, lower, optimum", [(18, 4500, 4500), (80, 3500, 3500), (165, 3500, 4000)])
def test_one_window_per_kind_raises_the_bound(seed, lower, optimum):
    """Random trees with a person where one window for both kinds allows half a second less:
    one window per kind (both from the start, or both to the end; bounds._kinds_fit) raises
    the bound, never above brute force."""
    rng = random.Random(seed)
    kinds = AGENT_SETS[2 + seed % 2]
    problem, _, units = random_tree(rng, 5 + seed % 2, knife=0.0)
    spec = random_spec(rng, kinds)
    assert bounds(instance(problem, units, spec)).lower == lower
    assert brute_schedule(problem, units, spec)[0] == optimum


# Schedules with a person among the agents: bounds against brute force, the goals of
# ../shared/foon proven at once, list schedules that pick the faster agent, the default time
# limit and the status line.


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
        assert f"lower bound before the search {d['bounds']['lower']:g} s" in got.to_text()
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
