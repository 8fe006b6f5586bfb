"""UWrMaxSat on the MaxSAT formula (foon2asp.maxsat.uwr) and after RC2 (minimum_tree's ``uwr_after``).

The solver in its child process is checked against brute force on random FOONs with cycles
(every objective, with and without a depth bound, loop cuts included), then the race's
plumbing with an RC2 that never finishes on its own (UWrMaxSat, taking over from it, proves the
optimum; a proof by HiGHS beside it ends the takeover at once), a race cut short (RC2's bound
stays, at most the optimum), and the child process (stopped at a deadline and by a halt,
started again, killed from outside, given up when it keeps dying, never left behind, silent on
the standard output).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest

from foon2asp.maxsat import uwr
from foon2asp.maxsat.trees import minimum_tree, minimum_tree_uwr
from foon2asp.methods.bounds import Bounds
from foon2asp.tree.validate import validate
from helpers import brute_force
from maxsat_checks import check_brute_force_optima, check_proof_after_a_stuck_rc2, check_required_units, cyclic_foon

pytestmark = pytest.mark.skipif(not uwr.available(), reason="hermax (UWrMaxSat) is not installed")


@pytest.mark.parametrize("chunk", range(3))
def test_the_solver_finds_the_brute_force_optimum(chunk):
    check_brute_force_optima(minimum_tree_uwr, "uwrmaxsat", chunk)


def test_required_units_are_in_the_solvers_tree():
    check_required_units(minimum_tree_uwr)


def _stuck(halted: list[bool]):
    """A UWrMaxSat that never finishes: it waits for its halt or deadline (``halted`` gets
    whether it was halted) and answers "stopped"."""
    from foon2asp.maxsat import trees

    def stuck(problem, goal, units, weights, require, deadline, depth, halt, race):
        while not halt() and time.perf_counter() < deadline:
            time.sleep(0.01)
        halted.append(halt())
        return trees.Result(None, 0, "stopped", solver="uwrmaxsat")

    return stuck


def _hard_part(hard):
    """hard-4k's ninth preset goal (about 50 units in a part of about 2,900: seconds to prove),
    its weights (``units``) and its part without dominated units."""
    problem, goals = hard
    goal = goals[8]
    bounds = Bounds(problem, ("units",), problem.units_for([goal]))
    return problem, goal, bounds, bounds.keep(goal, problem.units_for([goal]))


def _deepest_goal():
    """A random cyclic FOON and its made object whose smallest tree is largest."""
    problem = cyclic_foon(4)
    goals = [o for o in range(len(problem.objects)) if o not in problem.kitchen and brute_force(problem, o)]
    goal = max(goals, key=lambda o: min(len(t) for t in brute_force(problem, o)))
    assert min(len(t) for t in brute_force(problem, goal)) >= 2
    return problem, goal


def test_uwrmaxsat_after_a_stuck_rc2_proves_the_optimum(slow_rc2):
    check_proof_after_a_stuck_rc2(("inputs", "units"), "uwrmaxsat", "uwrmaxsat", uwr_after=0.0)


def test_a_proof_by_highs_ends_the_takeover_at_once(slow_rc2, monkeypatch):
    """UWrMaxSat that never finishes (it waits for its halt) and HiGHS beside it: HiGHS's proof
    is the answer as soon as it is in, not at the deadline."""
    from foon2asp.maxsat import mip, trees

    if not mip.available():
        pytest.skip("highspy is not installed")
    halted: list[bool] = []
    monkeypatch.setattr(trees, "minimum_tree_uwr", _stuck(halted))
    problem, goal = _deepest_goal()
    bounds = Bounds(problem, ("success", "units"))
    t0 = time.perf_counter()
    found = minimum_tree(
        problem, goal, range(len(problem.units)), bounds.w, deadline=t0 + 30, mip_after=0.2, uwr_after=0.1
    )
    assert found.status == "optimal" and found.solver == "highs" and time.perf_counter() - t0 < 10
    assert found.lower == min(bounds.weight(t) for t in brute_force(problem, goal))
    waited = time.perf_counter()
    while not halted and time.perf_counter() - waited < 5:
        time.sleep(0.01)
    assert halted == [True]  # told to stop, not run out to the deadline


def test_a_race_cut_short_bounds_the_optimum(hard):
    problem, goal, bounds, part = _hard_part(hard)
    full = minimum_tree_uwr(problem, goal, part, bounds.w)
    assert full.status == "optimal" and validate(problem, goal, list(full.tree)).valid
    for after, limit in ((0.1, 0.3), (1.0, 1.5)):
        t0 = time.perf_counter()
        short = minimum_tree(problem, goal, part, bounds.w, deadline=t0 + limit, uwr_after=after)
        assert time.perf_counter() - t0 < limit + 1.0  # the child is stopped, not waited for
        if short.status == "optimal":
            assert bounds.weight(short.tree) == full.lower
            continue
        assert short.status == "stopped" and short.tree is None and short.lower <= full.lower
        if after >= 1.0:
            assert short.lower > 0  # RC2's bound from before the takeover stays


def _children() -> set[int]:
    """This process's child processes (Linux: /proc)."""
    pids = set()
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as stat:
                    if int(stat.read().rsplit(")", 1)[1].split()[1]) == os.getpid():
                        pids.add(int(entry))
            except (OSError, IndexError, ValueError):
                continue
    return pids


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_the_child_is_stopped_at_the_deadline_and_by_a_halt_and_starts_again(hard):
    problem, goal, bounds, part = _hard_part(hard)
    solver = uwr.Solver()
    hard_clauses = [[1, 2], [-1, 3], [-2, 3]]
    assert solver.solve(3, hard_clauses, [(-1, 1), (-2, 2), (-3, 1)]) == ("optimal", {1, 3})
    first = solver._child.pid  # one child serves one problem after another
    assert solver.solve(3, hard_clauses + [[-3]], [(-1, 1)]) == ("infeasible", None)
    assert solver._child.pid == first and first in _children()
    t0 = time.perf_counter()
    found = minimum_tree_uwr(problem, goal, part, bounds.w, deadline=t0 + 0.2)
    assert found.status == "stopped" and time.perf_counter() - t0 < 1.0
    found = minimum_tree_uwr(problem, goal, part, bounds.w, halt=lambda: time.perf_counter() > t0 + 0.4)
    assert found.status == "stopped"
    assert uwr.solver()._child is None  # killed, and waited for
    assert solver.solve(2, [[1, 2]], [(-1, 1), (-2, 1)])[0] == "optimal"
    solver._child.kill()  # killed from outside between two problems: a new child answers
    solver._child.wait()
    assert solver.solve(2, [[1, 2], [-1]], [(-1, 1), (-2, 1)]) == ("optimal", {2})

    def killer() -> bool:  # ... and during one (a halt that kills the child and does not halt)
        solver._child.kill()
        return False

    assert solver.solve(*_formula(problem, goal, part, bounds.w), halt=killer) == ("stopped", None)
    assert solver.solve(2, [[1, 2]], [(-1, 1), (-2, 2)]) == ("optimal", {1})
    solver.stop()
    assert solver._child is None


def _formula(problem, goal, units, weights):
    """The variables, clauses and soft literals of ``goal``'s MaxSAT formula (as minimum_tree_uwr has them)."""
    from foon2asp.maxsat.trees import _encoding

    enc = _encoding(problem, goal, units, None)
    return (enc.top, *enc.weighted(weights, ()))


def test_the_child_prints_nothing_and_ends_with_its_parent():
    code = (
        "from foon2asp.maxsat import uwr; s = uwr.solver(); print(s.solve(2, [[1, 2]], [(-1, 1), (-2, 2)])); "
        "import os; print(s._child.pid)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=60)
    answer, pid = out.stdout.strip().splitlines()
    assert answer == "('optimal', {1})" and out.stderr == ""
    deadline = time.time() + 10
    while os.path.exists(f"/proc/{pid}") and time.time() < deadline:  # (Linux; elsewhere nothing to see)
        time.sleep(0.05)
    if os.path.exists(f"/proc/{pid}"):
        with open(f"/proc/{pid}/stat") as stat:
            assert stat.read().rsplit(")", 1)[1].split()[0] == "Z", "the child outlived its parent"


def test_without_hermax_rc2_answers_alone(monkeypatch):
    monkeypatch.setattr(uwr, "available", lambda: False)
    problem, goal = _deepest_goal()
    bounds = Bounds(problem, ("units",))
    found = minimum_tree(problem, goal, range(len(problem.units)), bounds.w, uwr_after=0.0)
    assert found.status == "optimal" and found.solver == "rc2"
    assert len(found.tree) == min(len(t) for t in brute_force(problem, goal))


def test_a_child_that_keeps_dying_is_given_up(monkeypatch):
    monkeypatch.setattr(uwr, "__file__", "/nonexistent/uwr.py")  # the child exits at once, with no answer
    broken = uwr.Solver()
    monkeypatch.setattr(uwr, "_solver", broken)
    for _ in range(uwr.GIVE_UP_AFTER):
        assert not broken.broken and uwr.available()
        assert broken.solve(2, [[1, 2]], [(-1, 1), (-2, 1)]) == ("stopped", None)
    assert broken.broken and not uwr.available()
    t0 = time.perf_counter()
    assert broken.solve(2, [[1, 2]], [(-1, 1), (-2, 1)]) == ("stopped", None)  # no new child
    assert time.perf_counter() - t0 < 0.05 and broken._child is None
    problem, goal = _deepest_goal()
    bounds = Bounds(problem, ("units",))
    found = minimum_tree(problem, goal, range(len(problem.units)), bounds.w, uwr_after=0.0)
    assert found.status == "optimal" and found.solver == "rc2"  # RC2 answers alone


def test_a_second_thread_waits_for_the_child_no_longer_than_its_deadline(hard):
    import threading

    problem, goal, bounds, part = _hard_part(hard)
    formula = _formula(problem, goal, part, bounds.w)
    solver = uwr.Solver()
    first: list = []
    busy = threading.Thread(target=lambda: first.append(solver.solve(*formula, deadline=time.perf_counter() + 3)))
    busy.start()
    time.sleep(0.2)
    t0 = time.perf_counter()
    assert solver.solve(2, [[1, 2]], [(-1, 1), (-2, 1)], deadline=t0 + 0.2) == ("stopped", None)
    assert time.perf_counter() - t0 < 1.0
    busy.join()
    assert first and first[0][0] in ("optimal", "stopped")
    assert solver.solve(2, [[1, 2]], [(-1, 1), (-2, 2)]) == ("optimal", {1})
    solver.stop()


def test_the_child_outlives_the_thread_that_started_it():
    """(A child is killed when the thread that started it ends, unless one long-lived thread starts them.)"""
    import threading

    solver = uwr.Solver()
    answers: list = []
    helper = threading.Thread(target=lambda: answers.append(solver.solve(2, [[1, 2]], [(-1, 1), (-2, 2)])))
    helper.start()
    helper.join()
    pid = solver._child.pid
    time.sleep(0.3)
    assert answers == [("optimal", {1})] and solver._child.poll() is None
    assert solver.solve(2, [[1, 2], [-1]], [(-1, 1), (-2, 2)]) == ("optimal", {2}) and solver._child.pid == pid
    solver.stop()


def test_an_answer_cut_short_while_uwrmaxsat_runs_has_highs_bound(slow_rc2, monkeypatch, hard):
    """RC2 proves nothing and UWrMaxSat nothing before the deadline: the bound is the one HiGHS
    reached beside them by then (reported as it rises, not when HiGHS returns)."""
    from foon2asp.maxsat import mip, trees

    if not mip.available():
        pytest.skip("highspy is not installed")

    problem, goal, bounds, part = _hard_part(hard)
    optimum = minimum_tree_uwr(problem, goal, part, bounds.w).lower
    monkeypatch.setattr(trees, "minimum_tree_uwr", _stuck([]))
    t0 = time.perf_counter()
    short = minimum_tree(problem, goal, part, bounds.w, deadline=t0 + 4, mip_after=0.0, uwr_after=0.0)
    assert short.status == "stopped" and short.tree is None and 0 < short.lower <= optimum
