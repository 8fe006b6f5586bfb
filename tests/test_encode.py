"""The order encoding of start times (schedule_order.lp), used for fixed trees without
durations 0: its optima equal the time-step encoding's and brute force's, on two identical
arms and a person among others."""

from __future__ import annotations

import random

import clingo
import pytest

from foon2asp.asp import encoding_files
from foon2asp.schedule import ScheduleSpec, schedule
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.encode import schedule_facts
from foon2asp.schedule.instances import divisor, earliest, instance, tails
from foon2asp.schedule.spec import Durations
from helpers import build, goal_id
from test_solve import AGENT_SETS, brute_schedule, given, random_spec, random_tree

TWO_ARMS_AND_A_PERSON = (("arm", 2), ("human", 1))


def optimum(name: str, inst, horizon: int) -> tuple[int, int] | None:
    """(makespan in steps, human units) of the optimum of encoding ``name`` within ``horizon``
    (ms), every unit given; None when there is no schedule."""
    scale = divisor(inst)
    head, tail = earliest(inst), tails(inst)
    windows = {u: (head[u], horizon - tail[u]) for u in inst.units if head[u] <= horizon - tail[u]}
    if len(windows) < len(inst.units):
        return None
    facts = schedule_facts(inst, scale, windows, True, False, tail)
    ctl = clingo.Control(["--opt-mode=optN", "--models=0"])
    ctl.load(encoding_files.entry(name))
    ctl.add("base", [], facts)
    ctl.add("base", [], f"horizon({horizon // scale}).\nfloor(0).\npriority(makespan,2).\npriority(human,1).\n")
    ctl.ground([("base", [])])
    costs: list[list[int]] = []
    result = ctl.solve(on_model=lambda m: costs.append(list(m.cost)) if m.optimality_proven else None)
    if result.unsatisfiable:
        return None
    assert result.exhausted and costs
    cost = costs[-1]  # no human level without a person
    return cost[0], cost[1] if len(cost) > 1 else 0


def no_zeros(spec: ScheduleSpec) -> ScheduleSpec:
    """``spec`` with every duration positive (the order encoding's domain)."""
    durations = spec.durations
    motions = {m: d or 500 for m, d in durations.motions.items()}
    kinds = {k: {m: d or 500 for m, d in table.items()} for k, table in durations.kinds.items()}
    return ScheduleSpec(spec.agents, Durations(motions, kinds), spec.capabilities, spec.resources)


@pytest.mark.parametrize("seed", range(40))
def test_order_and_time_steps_have_the_same_optimum(seed):
    """On random trees (a shared knife, several kinds, two identical arms and a person among
    them) both encodings reach the same makespan and the same fewest human units."""
    rng = random.Random(7000 + seed)
    kinds = AGENT_SETS[seed % len(AGENT_SETS)] if seed % 3 else TWO_ARMS_AND_A_PERSON
    problem, _, units = random_tree(rng, 4 + seed % 3, knife=0.5)
    spec = no_zeros(random_spec(rng, kinds))
    inst = instance(problem, units, spec)
    if inst.incapable():
        return
    horizon = sum(max(t.values()) for t in inst.durations.values())
    steps = optimum("schedule_steps", inst, horizon)
    assert steps is not None
    assert optimum("schedule_order", inst, horizon) == steps


@pytest.mark.parametrize("horizon_steps", [3, 4, 5])
def test_order_encoding_is_unsatisfiable_below_the_optimum(horizon_steps):
    """Two units in a chain and one beside, 1 s each on the arms and 2 s for the person, two
    arms and a person: the makespan is 2 s, so a horizon of 1.5 s has no schedule."""
    problem = build([("cut", ["k"], ["a"]), ("mix", ["a"], ["b"]), ("cut", ["k"], ["c"])], ["k"])
    spec = ScheduleSpec(TWO_ARMS_AND_A_PERSON, Durations({"*": 1000}, {"human": {"*": 2000}}))
    inst = instance(problem, [0, 1, 2], spec)
    assert optimum("schedule_order", inst, 1500) is None
    assert optimum("schedule_order", inst, horizon_steps * 1000) == (2, 0)


def test_two_identical_arms_and_a_person_equal_brute_force():
    """Five units on two arms and a fast person: the fixed-tree schedule (the order encoding)
    has brute force's makespan and fewest human units, and the checker accepts it."""
    # motion: (inputs, output, seconds on an arm, seconds for the person)
    table = {
        "peel": (["k"], "a", 4, 2),
        "chop": (["a"], "b", 3, 1),
        "cut": (["k"], "c", 2, 1),
        "pour": (["k"], "d", 1, 1),
        "mix": (["b", "c", "d"], "e", 3, 1),
    }
    problem = build([(m, ins, [out]) for m, (ins, out, _, _) in table.items()], ["k"])
    arm = {m: 1000 * a for m, (_, _, a, _) in table.items()}
    person = {m: 1000 * h for m, (_, _, _, h) in table.items()}
    spec = ScheduleSpec(TWO_ARMS_AND_A_PERSON, Durations(arm, {"human": person}))
    units = [0, 1, 2, 3, 4]
    want = brute_schedule(problem, units, spec)
    r = schedule(problem, given(problem, goal_id(problem, "e"), units), spec, shortcut=False)
    assert (r.status, r.human_units_proven) == ("optimal", True)
    assert (r.makespan, len(r.human)) == want == (4000, 3)
    assert r.stats["encoding"] == "steps"
    assert check_schedule(problem, r.to_dict(), spec) is None


def test_an_unknown_encoding_is_refused_where_jobs_are_solved():
    from foon2asp.errors import InputError
    from foon2asp.schedule import encode

    with pytest.raises(InputError, match=r"unknown schedule encoding 'dll' \(have steps, dl\)"):
        encode.solve(None, "dll")  # type: ignore[arg-type]
