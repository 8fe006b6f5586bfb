"""The clingo layer: named parts with parameters, deferred signals while the depth rounds are
grounded, the one reader of models (plain optimisation and multi-shot driver agree, and agree
with the fixpoint and the reference search), and alternatives as a field of the tree."""

from __future__ import annotations

import dataclasses
import os
import signal
import subprocess
import sys

import clingo
import pytest

from foon2asp.asp.control import Control
from foon2asp.asp.interrupts import signal_pending
from foon2asp.asp.multishot.depth import Rounds
from foon2asp.asp.multishot.driver import Driver, alternatives
from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon import goals as goals_mod
from foon2asp.methods.plan import session_of as Session
from foon2asp.tree.serialize import tree_json
from foon2asp.tree.tasktree import TaskTree, measures
from foon2asp.tree.validate import validate
from synth import preset
from test_session import reference


@pytest.fixture(scope="module")
def small():
    return preset("small").problem()


def _demo_goals(demo_problem):
    data, p = demo_problem
    labels = ("tomato salad", "scrambled egg", "whipped cream")
    return p, [goals_mod.resolve_label(data, p, label) for label in labels]


# --------------------------------------------------------------------------- Control


def test_control_grounds_named_parts_with_parameters():
    control = Control()
    control.add("rows", "#program row(k,n). cell(k,X) :- X = 1..n.", part="row", params=["k", "n"])
    control.add("base facts", "seen.")
    args = [(1, 3), (2, 2), (5, 1)]
    control.ground([("base", ()), *(("row", a) for a in args)])
    cells = {tuple(x.number for x in s.arguments) for s in control.facts_of("cell", 2)}
    assert cells == {(k, x) for k, n in args for x in range(1, n + 1)}
    assert {s.name for s in control.facts_of("seen", 0)} == {"seen"}
    # a part added later is grounded on the same control, with its own arguments
    control.extend("more rows", "#program late(k). late(k).", [("late", (7,))])
    assert [s.arguments[0].number for s in control.facts_of("late", 1)] == [7]


def test_control_stats_are_clingos_own_figures_of_the_last_solve():
    """The four numbers read from clingo's statistics equal those of its converted dict."""
    control = Control(["--models=0"])
    control.add("choices", "{a(1..6)}. :- a(X), a(Y), X < Y, Y - X < 2. #maximize { 1,X : a(X) }.")
    control.ground()
    with control.solving("opt"):
        result = control.solve()
    assert result.finished and result.satisfiable
    stats = control.stats()
    full = control.ctl.statistics
    assert stats["choices"] == int(full["solving"]["solvers"]["choices"]) > 0
    assert stats["conflicts"] == int(full["solving"]["solvers"]["conflicts"])
    assert stats["models"] == int(full["summary"]["models"]["enumerated"]) >= 1
    assert stats["solve_s"] == round(full["summary"]["times"]["solve"], 6)
    control.statistics = False
    assert control.stats() == {}


def _solved(program: str, args=("--models=0",)) -> Control:
    control = Control(list(args))
    control.add("program", program)
    control.ground()
    return control


def test_an_error_in_a_model_callback_reaches_the_caller_and_the_next_call_is_whole():
    control = _solved("{a;b}.")

    def fail(model):
        raise ValueError("from the callback")

    with pytest.raises((ValueError, RuntimeError), match="from the callback"):  # clingo may wrap it
        control.solve(fail)
    found: list[int] = []
    result = _solved("{a;b}.").solve(lambda m: found.append(1))
    assert result.finished and len(found) == 4


def test_a_search_cut_by_its_time_limit_leaves_no_interrupt_for_the_next_call():
    """A search stopped at its deadline, then searches on the same control: each runs to its end
    (an interrupt that came after a call ended is taken by the next call, not by its search)."""
    hard = "{p(1..40,1..39)}. :- p(I,H1), p(J,H1), I < J. :- I = 1..40, not p(I,H) : H = 1..39."
    control = _solved(hard)
    result = control.solve(time_limit=0.2)
    assert not result.finished and result.interrupted and result.satisfiable is not True
    # then the same control without a limit, under an assumption that ends it at once
    done = control.solve(assumptions=[(clingo.Function("p", [clingo.Number(1), clingo.Number(0)]), True)])
    assert done.finished and done.unsatisfiable
    small = _solved("{a;b}. :- a, b.")
    for limit in (1e-6, 1e-5, 1e-4, 1e-3, None):
        found: list[int] = []
        small.solve(lambda m: found.append(1), time_limit=limit)
    found = []
    result = small.solve(lambda m: found.append(1))
    assert result.finished and not result.interrupted and len(found) == 3


_STOPPED_AT_LIMIT = """
import sys, time
from foon2asp.asp.control import Control
hard = "{p(1..40,1..39)}. :- p(I,H), p(J,H), I < J. :- I = 1..40, not p(I,H) : H = 1..39. #minimize{1,I,H: p(I,H)}."
control = Control([*sys.argv[1:], "--opt-mode=opt", "--opt-strategy=usc,oll,succinct,stratify"])
control.add("pigeons", hard)
control.ground()
t0 = time.perf_counter()
result = control.solve(time_limit=0.3)
print(result.finished, result.interrupted, round(time.perf_counter() - t0, 2))
"""


@pytest.mark.parametrize(
    "args",
    [[], ["--single-shot"], ["--parallel-mode=2"], ["--single-shot", "--parallel-mode=2"]],
    ids=["multi-shot", "single-shot", "threads", "single-shot-threads"],
)
def test_a_search_stops_at_its_time_limit_whatever_the_control(args):
    """A search that cannot end (41 pigeons, 40 holes) stops at its time limit, on a multi-shot
    control, a single-shot one (whose search only its solve handle reaches) and with threads; run
    in a process of its own, ended after 30 s if it does not stop."""
    ran = subprocess.run([sys.executable, "-c", _STOPPED_AT_LIMIT, *args], capture_output=True, text=True, timeout=30)
    assert ran.returncode == 0, ran.stderr
    finished, interrupted, seconds = ran.stdout.split()
    assert finished == "False" and interrupted == "True"
    assert 0.25 <= float(seconds) < 5


def test_control_grounding_error_is_one_line_about_what_was_grounded():
    control = Control()
    control.ground()
    with pytest.raises(InputError) as err:
        control.extend("broken part", "p(X) :- q.", what="grounding the test rounds")
    text = str(err.value)
    assert text.startswith("grounding the test rounds: ") and "unsafe" in text and "\n" not in text


def test_control_solving_mode_is_restored():
    control = Control(["--opt-mode=opt"])
    conf = control.ctl.configuration.solve
    before = (conf.opt_mode, conf.models, conf.project)
    with control.solving("optN", 4):
        assert (conf.opt_mode, conf.models) == ("optN", "4") and conf.project.startswith("project")
    with control.solving("first"):
        assert (conf.opt_mode, conf.models) == ("ignore", "1")
    assert (conf.opt_mode, conf.models, conf.project) == before
    with control.solving("first", bound=(3, 1)):
        assert (conf.opt_mode, conf.models) == ("enum,3,1", "1")
    assert (conf.opt_mode, conf.models, conf.project) == before


#: twelve atoms to choose, each costing its number: models improve one by one from 78 to 0
IMPROVING = "x(1..12). { a(X) } :- x(X). #minimize { X,X : a(X) }.\n"


def test_a_decision_with_a_bound_finds_a_model_that_cheap_or_none():
    control = Control(["--opt-mode=opt"])
    control.add("p", ":- not a(5), not a(7).\n" + IMPROVING)
    control.ground()
    costs: list[list[int]] = []
    with control.solving("first", bound=(5,)):
        result = control.solve(lambda m: costs.append(list(m.cost)))
    assert result.finished and result.satisfiable and costs == [[5]]
    with control.solving("first", bound=(4,)):
        assert control.solve().unsatisfiable is True


def test_stop_soon_ends_a_search_and_leaves_the_next_one_whole():
    """stop_soon ends the call as finished and stopped; an interrupt that comes after its end
    does not cut the next call short (many rounds: the two race)."""
    control = Control(["--opt-mode=opt", "--opt-strategy=bb"])
    control.add("p", IMPROVING)
    control.ground()
    for _ in range(40):
        seen: list[int] = []

        def first(model):
            seen.append(model.cost[0])
            control.stop_soon()

        stopped = control.solve(first)
        assert stopped.finished and stopped.stopped and seen
        whole = control.solve()
        assert whole.finished and whole.exhausted and not whole.interrupted


def test_a_decision_that_outlasts_its_time_limit_stops_at_it():
    """A decision starts in the calling thread and goes on in the background: either way the
    time limit ends it (ten pigeons in nine holes take clasp far longer)."""
    control = Control()
    control.add("p", "p(1..10). h(1..9). 1 { at(P,H) : h(H) } 1 :- p(P). :- at(P,H), at(Q,H), P < Q.\n")
    control.ground()
    for limit in (0.02, 0.3):
        with control.solving("first"):
            result = control.solve(time_limit=limit)
        assert not result.finished and result.satisfiable is None
        assert result.time_s < limit + 1.0


# --------------------------------------------------------------------------- depth rounds


def _interrupt_during_ground(control, monkeypatch) -> list[str]:
    """Make every ground call of ``control`` receive SIGINT first; returns the calls that ran to their end."""
    real = control.ctl.ground
    done: list[str] = []

    def ground(parts, *args, **kwargs):
        os.kill(os.getpid(), signal.SIGINT)
        assert signal_pending(), "SIGINT must wait while the depth rounds are grounded"
        real(parts, *args, **kwargs)
        done.extend(name for name, _ in parts)

    monkeypatch.setattr(control.ctl, "ground", ground)
    return done


@pytest.mark.parametrize("meal", [False, True])
def test_depth_blocks_defer_signals_and_stay_registered(demo_problem, monkeypatch, meal):
    p, goals = _demo_goals(demo_problem)
    session = Session(p, AspOptions(objective=("depth",)))
    rounds = Rounds.of(session)
    if meal:
        members = [rounds.block(g, 4) for g in goals[:2]]  # the goals' blocks first, uninterrupted
    done = _interrupt_during_ground(session.control, monkeypatch)
    with pytest.raises(KeyboardInterrupt):
        if meal:
            rounds.meal_block(tuple(goals[:2]), 4)
        else:
            rounds.block(goals[0], 4)
    # the interrupt came after the grounding, and the block is known: it is never grounded twice
    if meal:
        assert "meal" in done and (tuple(goals[:2]), 4) in rounds.meal_blocks
        assert [rounds.block(g, 4) for g in goals[:2]] == members
    else:
        assert "bound" in done and (goals[0], 4) in rounds.blocks
    monkeypatch.undo()
    tree = session.solve(tuple(goals[:2]) if meal else goals[0])
    assert tree.status == "optimal"


def test_the_driver_owns_its_depth_state(demo_problem):
    p, goals = _demo_goals(demo_problem)
    session = Session(p, AspOptions(objective=("depth",)))
    names = set(vars(session))
    trees = [session.solve(g) for g in goals[:2]] + [session.solve(tuple(goals[:2]))]
    assert set(vars(session)) == names, "solving adds no attribute to the session"
    driver = session._driver
    assert isinstance(driver, Driver) and driver.rounds is not None
    assert {g for g, _ in driver.rounds.blocks} >= set(goals[:2]) and driver.rounds.meal_blocks
    levels = p.derivation_levels()[0]
    assert [t.cost["depth"] for t in trees] == [levels[goals[0]], levels[goals[1]], max(levels[g] for g in goals[:2])]


# --------------------------------------------------------------------------- one reader


def _expected_status(problem, meal, max_depth=None) -> str:
    """From the least fixpoint alone: is there a tree (within ``max_depth`` rounds)?"""
    levels = problem.derivation_levels()[0]
    if not all(g in problem.kitchen or g in levels for g in meal):
        return "unreachable"
    depth = max(0 if g in problem.kitchen else levels[g] for g in meal)
    return "unreachable" if max_depth is not None and depth > max_depth else "optimal"


@pytest.mark.parametrize("objective", ["units", "success", "inputs", "depth"])
def test_plain_and_driven_solves_read_the_same_trees(demo_problem, small, objective):
    """One plain optimisation (Session) and the multi-shot driver (all optimal trees, capped at
    one) give the same status, cost and canonical tree; the status is the fixpoint's, the cost
    the reference search's."""
    p, demo = _demo_goals(demo_problem)
    cases = [(p, [*demo, tuple(demo[:2])]), (small, sorted(small.derivable - small.kitchen)[::40][:5])]
    for problem, goals in cases:
        plain = Session(problem, AspOptions(objective=(objective,)))
        driven = Session(problem, AspOptions(objective=(objective,), all_optimal=True, all_optimal_cap=1))
        for goal in goals:
            meal = goal if isinstance(goal, tuple) else (goal,)
            one, two = plain.solve(goal), driven.solve(goal)
            assert one.status == two.status == _expected_status(problem, meal)
            assert one.asp_cost == two.asp_cost
            if not one.has_tree:
                continue
            assert all(validate(problem, g, one.units).valid for g in meal)
            assert one.cost == measures(problem, meal, one.units) and two.cost == measures(problem, meal, two.units)
            if "canonical_search" not in one.stats and "canonical_search" not in two.stats:
                assert sorted(one.units) == sorted(two.units)
            if objective in ("units", "success") and len(meal) == 1 and problem is p:
                assert one.asp_cost[0] == round(reference(problem, meal[0], objective))
            if objective == "depth":
                assert one.cost["depth"] == max(problem.derivation_levels()[0].get(g, 0) for g in meal)


def test_depth_bounds_and_meals_read_the_fixpoints_status(demo_problem):
    p, goals = _demo_goals(demo_problem)
    for bound in (2, 3, 4, 5):
        session = Session(p, AspOptions(max_depth=bound))
        for goal in [*goals, tuple(goals[:2])]:
            meal = goal if isinstance(goal, tuple) else (goal,)
            tree = session.solve(goal)
            assert tree.status == _expected_status(p, meal, bound)
            if tree.has_tree:
                assert tree.cost["depth"] <= bound and all(validate(p, g, tree.units).valid for g in meal)


def test_alternatives_are_a_field_ranked_by_one_status(demo_problem):
    p, goals = _demo_goals(demo_problem)
    assert "alternatives" in {f.name for f in dataclasses.fields(TaskTree)}
    assert TaskTree(0, "m", "optimal").alternatives == []
    every = Session(p, AspOptions(all_optimal=True))
    session = Session(p, AspOptions(models=3))
    for goal in [*goals, tuple(goals[:2])]:
        meal = goal if isinstance(goal, tuple) else (goal,)
        tree = session.solve(goal)
        if not tree.has_tree:
            assert tree.alternatives == []
            continue
        found = alternatives(tree)
        assert found == [tree, *tree.alternatives] and not hasattr(tree, "extra")
        assert all(t.alternatives == [] for t in found[1:])
        assert [t.rank for t in found] == list(range(1, len(found) + 1))
        costs = [tuple(t.asp_cost) for t in found]
        assert costs == sorted(costs)
        assert [t.status for t in found] == ["optimal" if c == costs[0] else "ranked" for c in costs]
        assert len({frozenset(t.units) for t in found}) == len(found)
        assert all(validate(p, g, t.units).valid for t in found for g in meal)
        # as many optimal ones as the optimal trees there are (up to 3)
        optimal = alternatives(every.solve(goal))
        assert sum(t.status == "optimal" for t in found) == min(3, len(optimal))
        # the JSON of a tree is the tree alone
        assert "alternatives" not in tree_json(p, tree)
