"""The independent schedule checker: it accepts solver schedules and rejects each kind of violation."""

from __future__ import annotations

import copy

import pytest

from foon2asp.schedule import ScheduleSpec, schedule
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.spec import Durations
from foon2asp.tree.tasktree import TaskTree, executable_order
from helpers import build, goal_id

KNIFE = ("knife",)


@pytest.fixture
def case():
    """cut a and cut b (both with the knife) in parallel on two arms, then mix them."""
    problem = build(
        [("cut", ["k", KNIFE], ["a"]), ("cut", ["k", KNIFE], ["b"]), ("mix", ["a", "b"], ["g"])],
        ["k", KNIFE],
    )
    spec = ScheduleSpec((("arm", 2), ("human", 1)), Durations({"cut": 2000, "mix": 1000}, {"human": {"mix": 500}}))
    tree = TaskTree(
        goal=goal_id(problem, "g"), method="given", status="optimal", units=executable_order(problem, [0, 1, 2])
    )
    record = schedule(problem, tree, spec, shortcut=False).to_dict()
    assert check_schedule(problem, record, spec) is None
    return problem, spec, record


def entry(record, motion_label):
    """The schedule entry of the unit that makes ``motion_label``'s product."""
    motion, label = motion_label
    return next(
        e for e in record["schedule"] if e["unit"]["motion"] == motion and e["unit"]["outputs"][0]["label"] == label
    )


def test_the_solver_schedule_is_as_expected(case):
    problem, spec, record = case
    assert record["makespan"] == 2.5 and record["status"] == "optimal"
    assert entry(record, ("mix", "g"))["agent"] == "human-1"  # the person mixes faster
    assert {entry(record, ("cut", x))["agent"] for x in "ab"} == {"arm-1", "arm-2"}


def test_precedence_violation(case):
    problem, spec, record = case
    bad = copy.deepcopy(record)
    mix = entry(bad, ("mix", "g"))
    mix["start"], mix["end"] = 1.0, 1.5
    bad["makespan"] = 2.0
    assert "before a, s is made" in check_schedule(problem, bad, spec)


def test_one_unit_per_agent_at_a_time(case):
    problem, spec, record = case
    bad = copy.deepcopy(record)
    entry(bad, ("cut", "b"))["agent"] = entry(bad, ("cut", "a"))["agent"]
    assert "at once" in check_schedule(problem, bad, spec)


def test_capabilities(case):
    problem, _, record = case
    spec = ScheduleSpec(
        (("arm", 2), ("human", 1)),
        Durations({"cut": 2000, "mix": 1000}, {"human": {"mix": 500}}),
        {"human": frozenset({"cut"})},
    )
    assert "cannot do 'mix'" in check_schedule(problem, record, spec)


def test_resources(case):
    problem, spec, record = case
    limited = ScheduleSpec(spec.agents, spec.durations, {}, {"knife": 1})
    assert "capacity 1" in check_schedule(problem, record, limited)
    roomy = ScheduleSpec(spec.agents, spec.durations, {}, {"knife": 2})
    assert check_schedule(problem, record, roomy) is None


def test_the_tree_must_be_valid(case):
    problem, spec, record = case
    bad = copy.deepcopy(record)
    bad["schedule"] = [e for e in bad["schedule"] if e["unit"]["outputs"][0]["label"] != "b"]
    assert "the tree is not valid" in check_schedule(problem, bad, spec)


def test_durations(case):
    problem, spec, record = case
    bad = copy.deepcopy(record)
    e = entry(bad, ("cut", "a"))
    e["end"] = e["start"] + 1.0
    assert "takes 1 s, not 2 s" in check_schedule(problem, bad, spec)


def test_makespan_is_the_latest_end(case):
    problem, spec, record = case
    bad = dict(record, makespan=3.0)
    assert "makespan" in check_schedule(problem, bad, spec)


@pytest.mark.parametrize(
    "change, words",
    [
        (lambda r: r["schedule"][0].update(agent="arm-9"), "not in 'agents'"),
        (lambda r: r["schedule"][0].update(start=0.0005), "exact to 0.001 s"),
        (lambda r: r["schedule"][0].update(start="soon"), "not a number"),
        (lambda r: r["schedule"][0]["unit"].update(motion="juggle"), "not in the FOON"),
        (lambda r: r["schedule"].append(r["schedule"][0]), "scheduled twice"),
        (lambda r: r["schedule"][0].update(end=-1.0), "0 <= start <= end"),
        (lambda r: r.update(status="unschedulable"), "holds no schedule"),
        (lambda r: r.update(schedule=None), "must be a list"),
    ],
)
def test_malformed_schedules(case, change, words):
    problem, spec, record = case
    bad = copy.deepcopy(record)
    change(bad)
    assert words in check_schedule(problem, bad, spec)
