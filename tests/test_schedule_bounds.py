"""The lower bounds and the fixed-tree shortcut against their plain versions, and a joint search cut short."""

from __future__ import annotations

import math
import random

import pytest
from hypothesis import given as hgiven
from hypothesis import settings
from hypothesis import strategies as st

import foon2asp
from conftest import REPO
from foon2asp.schedule import ScheduleSpec, schedule
from foon2asp.schedule.baseline import known_schedule, list_schedule
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.instances import divisor, earliest, instance, makespan, tails
from foon2asp.schedule.lower_bounds import bounds, energy_over, kind_energy, window_length
from foon2asp.schedule.spec import Durations
from test_schedule_solve import AGENT_SETS, brute_schedule, given, random_spec, random_tree


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


def test_a_joint_search_cut_short_bounds_every_tree(shared_foon_dir):
    """Chocolate chip muffin on two arms with the duration table: the joint search takes seconds;
    cut at 0.1 s its answer says how short any tree could be, no more than the proven optimum."""
    kb = foon2asp.load(shared_foon_dir)
    table = REPO / "bench" / "durations.json"
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
