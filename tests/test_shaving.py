"""Shaving against brute force on random trees with a person, and the goal it proves on ../shared/foon."""

from __future__ import annotations

import os
import random
import signal
import time

import pytest

import foon2asp
from conftest import REPO
from foon2asp.asp.interrupts import deferred_signals
from foon2asp.schedule import encode, shaving
from foon2asp.schedule.baseline import list_schedule
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.encode import clock
from foon2asp.schedule.instances import compact, divisor, earliest, instance, makespan, tails
from foon2asp.schedule.lower_bounds import bounds
from foon2asp.schedule.shaving import human_floor, shave
from test_solve import AGENT_SETS, brute_schedule, random_spec, random_tree


@pytest.mark.parametrize("seed", range(40))
def test_shaving_keeps_the_optimum_and_its_human_units(seed):
    """At the brute-force optimum shaving leaves a domain, whose human count is at most the
    fewest human units there; one step below the optimum it may rule the makespan out, and
    what it rules out is below the optimum."""
    rng = random.Random(seed)
    kinds = AGENT_SETS[2 + seed % 2]
    problem, _, units = random_tree(rng, 4 + seed % 2, knife=0.0)
    spec = random_spec(rng, kinds)
    want = brute_schedule(problem, units, spec)
    if want is None:
        return
    opt, human = want
    inst = instance(problem, units, spec)
    dom = shave(inst, opt)
    assert dom is not None
    assert human_floor(inst, dom) <= human
    for u in inst.units:
        assert dom.durations[u] and set(dom.durations[u]) <= set(inst.durations[u])
        assert dom.release[u] + dom.least(u) <= dom.deadline[u] <= opt
    step = divisor(inst)
    for horizon in range(bounds(inst).lower, opt + 2 * step, step):
        assert shave(inst, horizon) is not None or horizon < opt


def test_shaving_raises_the_bound_and_counts_the_human_units(shared_foon_dir):
    """Coleslaw on two arms and a person with the duration table: the bounds allow 33 s,
    shaving rules out 33 s (the optimum is 36 s).  Shrimp mango salad: at 63 s, its bound and
    optimum, shaving counts 16 human units (the capacity count alone 13), the fewest there."""
    kb = foon2asp.load(shared_foon_dir)
    spec = foon2asp.schedule.ScheduleSpec.from_files("arm=2,human=1", REPO / "bench" / "durations.json")
    trees = {label: kb.solve(label).raw for label in ("coleslaw", "shrimp mango salad")}
    coleslaw = instance(kb.problem, trees["coleslaw"].units, spec)
    assert bounds(coleslaw).lower == 33000
    assert shave(coleslaw, 33000) is None and shave(coleslaw, 34000) is not None
    shrimp = instance(kb.problem, trees["shrimp mango salad"].units, spec)
    dom = shave(shrimp, 63000)
    assert dom is not None and human_floor(shrimp, dom) == 16
    r = kb.schedule("shrimp mango salad", agents="arm=2,human=1", durations=REPO / "bench" / "durations.json")
    assert r.status == "optimal" and r.makespan == 63.0 and len(r.raw.human) == 16
    assert r.raw.stats["tie_breakers"] == "proven"
    assert check_schedule(kb.problem, r.to_dict(), spec) is None


def test_a_signal_stops_shaving_beside_a_search():
    """While a search runs (its signals deferred), a signal stops the shaving its stop asks
    for: the clock reads 0, shaving returns its first domains, and the signal comes after."""
    rng = random.Random(0)
    problem, _, units = random_tree(rng, 5, knife=0.0)
    inst = instance(problem, units, random_spec(rng, AGENT_SETS[3]))
    left = clock(60.0)
    with pytest.raises(KeyboardInterrupt), deferred_signals():
        os.kill(os.getpid(), signal.SIGINT)
        assert left() == 0.0
        dom = shave(inst, 10**9, left=left)
        assert dom is not None and dom.durations == inst.durations
    assert left() > 0.0


@pytest.mark.parametrize("seed", range(40))
def test_the_phases_stops_keep_the_optimum_and_its_human_units(seed, monkeypatch):
    """The stops that shave beside the phases' searches, asked at once: the makespan's floor
    raised is at most the brute-force optimum and a schedule found at it is optimal; the
    human units' count raised at the optimum is at most the fewest there."""
    monkeypatch.setattr(shaving, "AFTER", 0.0)
    rng = random.Random(seed)
    problem, _, units = random_tree(rng, 5, knife=0.0)
    spec = random_spec(rng, AGENT_SETS[2 + seed % 2])
    want = brute_schedule(problem, units, spec)
    if want is None:
        return
    opt, human = want
    inst = instance(problem, units, spec)
    base = list_schedule(inst)
    job = encode.Job(inst, earliest(inst), tails(inst), makespan(base), bounds(inst).lower, known=base)
    floor = encode._FloorStop(job, encode.clock(None), base)
    met = floor.shave()
    assert bounds(inst).lower <= floor.floor <= opt
    assert floor.best is not None and makespan(floor.best) >= opt
    assert not met or makespan(floor.best) == opt
    assert floor.shaved is None or floor.shaved[0] == floor.floor
    count = shaving.HumanStop(inst, opt, 0, encode.clock(None), None, lambda entries, n: None)
    count.shave()
    assert count.low <= human


def test_an_undecided_search_at_the_floor_is_tried_again_for_twice_as_long(monkeypatch):
    """The search of the domains shaving leaves at the floor, undecided, is tried again once the
    makespan's search has run on alone as long, for twice the time; what it finds there stops it."""
    monkeypatch.setattr(shaving, "AFTER", 0.0)
    rng = random.Random(0)
    problem, _, units = random_tree(rng, 5, knife=0.0)
    inst = instance(problem, units, random_spec(rng, AGENT_SETS[3]))
    base = list_schedule(inst)
    limits: list = []

    def search(job, windows, horizon, floor, limit, only=None, enough=None, stop=None):
        limits.append(limit)
        return encode.Solution(base if len(limits) > 1 else None)

    monkeypatch.setattr(encode, "_steps_once", search)
    job = encode.Job(inst, earliest(inst), tails(inst), 10**9, bounds(inst).lower)
    stop = encode._FloorStop(job, encode.clock(None), None)
    assert not stop.shave() and limits == [encode.DECIDE] and stop.shaved is not None
    assert not stop.shave() and limits == [encode.DECIDE]  # the search runs on alone first
    while time.perf_counter() < stop.next:
        time.sleep(0.01)
    assert stop.shave() and limits == [encode.DECIDE, 2 * encode.DECIDE] and stop.best == compact(inst, base)
