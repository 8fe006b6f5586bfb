"""HiGHS on the MaxSAT formula (foon2asp.maxsat.mip) and beside RC2 (minimum_tree's ``mip_after``).

The 0/1 program is checked against brute force on random FOONs with cycles (every objective,
with and without a depth bound, loop cuts included), the race's plumbing with an RC2 that
never finishes on its own (HiGHS's proof is the answer, with its bound and solver), a race
cut short (the bound at most the optimum, the incumbent a valid tree), and HiGHS's banner
kept off the standard output.
"""

from __future__ import annotations

import subprocess
import sys
import threading
import time

import pytest

from foon2asp.maxsat import mip
from foon2asp.maxsat.trees import minimum_tree, minimum_tree_mip
from foon2asp.methods.bounds import Bounds
from foon2asp.tree.validate import validate
from maxsat_checks import check_brute_force_optima, check_proof_after_a_stuck_rc2, check_required_units, cyclic_foon

pytestmark = pytest.mark.skipif(not mip.available(), reason="highspy is not installed")


@pytest.mark.parametrize("chunk", range(3))
def test_the_program_is_the_brute_force_optimum(chunk):
    check_brute_force_optima(minimum_tree_mip, "highs", chunk)


def test_required_units_are_in_the_programs_tree():
    check_required_units(minimum_tree_mip)


def test_highs_beside_a_stuck_rc2_proves_the_optimum(slow_rc2):
    check_proof_after_a_stuck_rc2(("success", "units"), "highs", "mip", mip_after=0.0)


def test_without_highs_a_stuck_rc2_stops_at_the_deadline(slow_rc2):
    problem = cyclic_foon(1)
    bounds = Bounds(problem, ("units",))
    levels, _ = problem.derivation_levels()
    goal = max(levels, key=lambda o: levels[o])
    found = minimum_tree(problem, goal, range(len(problem.units)), bounds.w, deadline=time.perf_counter() + 0.2)
    assert found.status == "stopped" and found.tree is None and found.incumbent is None and found.lower == 0


def test_a_race_cut_short_bounds_the_optimum_and_offers_a_tree(hard):
    problem, goals = hard
    goal = goals[8]  # about 50 units in a part of about 2,900: seconds to prove
    bounds = Bounds(problem, ("units",), problem.units_for([goal]))
    part = bounds.keep(goal, problem.units_for([goal]))
    full = minimum_tree(problem, goal, part, bounds.w)
    assert full.status == "optimal"
    for limit in (0.5, 1.5):
        short = minimum_tree(problem, goal, part, bounds.w, deadline=time.perf_counter() + limit, mip_after=0.0)
        if short.status == "optimal":
            assert bounds.weight(short.tree) == full.lower
            continue
        assert short.status == "stopped" and short.lower <= full.lower
        if short.incumbent is not None:
            assert validate(problem, goal, list(short.incumbent)).valid
            assert bounds.weight(short.incumbent) >= full.lower


def test_the_helper_thread_ends_with_the_search():
    problem = cyclic_foon(2)
    bounds = Bounds(problem, ("units",))
    before = set(threading.enumerate())  # (threads of earlier tests may end meanwhile)

    def started_here() -> list[threading.Thread]:
        return [t for t in threading.enumerate() if t not in before]

    for goal in range(len(problem.objects)):
        if goal not in problem.kitchen:
            minimum_tree(problem, goal, range(len(problem.units)), bounds.w, mip_after=0.0)
    waited = time.perf_counter()
    while started_here() and time.perf_counter() - waited < 20:
        time.sleep(0.05)
    assert started_here() == []  # the helpers stopped on their own


def test_a_program_past_its_deadline_stops_at_once():
    program = mip.Program(3, {1: 1, 2: 1, 3: 1})
    program.add([[1, 2], [-1, 3]])
    assert program.solve(deadline=time.perf_counter() - 1) == ("stopped", None)
    status, model = program.solve()
    assert status == "optimal" and model == {2}
    program.add([[-2]])
    assert program.solve() == ("optimal", {1, 3}) and program.lower == 2
    program.add([[-1]])
    assert program.solve() == ("infeasible", None)


def test_highs_prints_nothing():
    code = "from foon2asp.maxsat import mip; p = mip.Program(2, {1: 1, 2: 2}); p.add([[1, 2]]); print(p.solve())"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "('optimal', {1})" and out.stderr == ""


def test_highs_starts_later_on_shared_cores_and_never_on_one(monkeypatch):
    from foon2asp.methods import proofs

    for cores, processes, expected in [
        (1, 1, None),
        (1, 2, None),
        (2, 1, proofs.MIP_AFTER_S),
        (2, 2, proofs.MIP_AFTER_SHARED_S),
        (4, 2, proofs.MIP_AFTER_S),
    ]:
        monkeypatch.setattr(proofs, "_cores", lambda c=cores: c)
        proofs.share_cores(processes)
        assert proofs.mip_after() == expected, (cores, processes)
    proofs.share_cores(1)


def test_a_goal_cut_short_while_highs_runs_exits_with_status_1(tmp_path):
    """The time limit ends RC2 and HiGHS beside it: the process reports ``feasible`` and exits
    with 1, not aborted by a HiGHS run the interpreter's exit cut off (status 134)."""
    from foon2asp.foon.synth import preset
    from foon2asp.methods import proofs

    if proofs._cores() < 2:
        pytest.skip("HiGHS starts beside RC2 only with two cores or more")
    syn = preset("hard-4k")
    syn.write(tmp_path)
    goal = syn.problem().foon.object_ids[syn.goals[16]]  # RC2 alone takes about 10 s on it
    command = [sys.executable, "-m", "foon2asp", "solve", "--data", str(tmp_path), "--goal", f"#{goal}"]
    out = subprocess.run([*command, "--time-limit", "2.5", "--format", "json"], capture_output=True, text=True)
    assert out.returncode == 1, out.stderr[-300:]
    assert '"status": "feasible"' in out.stdout and "terminate" not in out.stderr
