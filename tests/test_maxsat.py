"""MaxSAT (foon2asp.maxsat): the optimum against brute force, loop cuts, bounds of a search cut short.

The relaxation and its loop cuts are checked on random FOONs with cycles against every valid
subset (tests/helpers.brute_force, judged by the independent validator), on a hand-made FOON
whose relaxation is cheaper than any tree, and on a hard synthetic goal cut short: the bound
it reports is at most the optimum a full run proves.
"""

from __future__ import annotations

import random
import time

import pytest

from foon2asp.asp.options import AspOptions
from foon2asp.maxsat import oracle as oracle_module
from foon2asp.maxsat.oracle import Oracle, Stopped
from foon2asp.maxsat.trees import minimum_tree, minimum_tree_mip
from foon2asp.methods.bounds import Bounds
from foon2asp.methods.runner import GoalRunner, solve_goals
from foon2asp.tree.tasktree import measures
from foon2asp.tree.validate import validate
from helpers import brute_force, build, goal_id
from maxsat_checks import RANKED, cyclic_foon


@pytest.mark.parametrize("chunk", range(8))
def test_minimum_tree_is_the_brute_force_optimum(chunk):
    checked = cut = 0
    for seed, ranked in [(s, r) for s in range(5 * chunk, 5 * chunk + 5) for r in RANKED]:
        problem = cyclic_foon(seed)
        bounds = Bounds(problem, ranked)
        for goal in range(len(problem.objects)):
            if goal in problem.kitchen:
                continue
            trees = brute_force(problem, goal)
            found = minimum_tree(problem, goal, range(len(problem.units)), bounds.w)
            cut += found.cuts
            if not trees:
                assert found.status == "unreachable" and found.tree is None
                continue
            opt = min(bounds.weight(t) for t in trees)
            assert found.status == "optimal", (seed, ranked, goal)
            assert validate(problem, goal, list(found.tree)).valid
            assert bounds.weight(found.tree) == opt == found.lower, (seed, ranked, goal)
            checked += 1
    assert checked > 0 and cut > 0  # the relaxation's optimum was no tree, and was cut, somewhere


def tied_foon(seed: int):
    """A random FOON where objects have several producers of the same size: many optimal trees."""
    rng = random.Random(seed)
    kitchen = ["k0", "k1", "k2", "k3"]
    made = [f"o{i}" for i in range(5)]
    units = []
    for i, out in enumerate(made):
        for _ in range(rng.randint(2, 3)):
            pool = kitchen + made[:i] * 2 + made[i + 1 :]  # a few back edges
            units.append(("m0", list(dict.fromkeys(rng.sample(pool, rng.randint(1, 2)))), [out]))
    rng.shuffle(units)  # producers of one object apart in id order
    return build(units, kitchen, {"m0": 0.5})


def canonical_key(n: int):
    """Sort key of the canonical order (foon2asp.asp.canonical): the tree holding the smallest
    unit on which two trees differ comes first."""
    return lambda tree: tuple(0 if u in tree else 1 for u in range(n))


@pytest.mark.parametrize("chunk", range(4))
def test_the_walk_ends_on_the_smallest_optimal_tree(chunk):
    """With ``smallest``, the tree is the first optimal tree of brute force in the canonical
    order (for the sum objectives, and within the goal's level), and the walk is proven."""
    walked = 0
    for seed, ranked in [(s, r) for s in range(5 * chunk, 5 * chunk + 5) for r in RANKED]:
        problem = (cyclic_foon if seed % 2 else tied_foon)(seed)
        levels, _ = problem.derivation_levels()
        bounds = Bounds(problem, ranked)
        key = canonical_key(len(problem.units))
        for goal in sorted(levels):
            if goal in problem.kitchen:
                continue
            every = brute_force(problem, goal)
            for depth in (None, levels[goal]):
                trees = every
                if depth is not None:
                    trees = [t for t in trees if measures(problem, goal, list(t))["depth"] <= depth]
                opt = min(bounds.weight(t) for t in trees)
                smallest = min((set(t) for t in trees if bounds.weight(t) == opt), key=key)
                found = minimum_tree(problem, goal, range(len(problem.units)), bounds.w, depth=depth, smallest=True)
                assert found.status == "optimal" and found.search == "complete", (seed, ranked, goal, depth)
                assert set(found.tree) == smallest, (seed, ranked, goal, depth)
                plain = minimum_tree(problem, goal, range(len(problem.units)), bounds.w, depth=depth)
                walked += set(plain.tree) != smallest
                known = minimum_tree(
                    problem, goal, range(len(problem.units)), bounds.w, depth=depth, smallest=True, known=opt
                )
                assert known.search is None and bounds.weight(known.tree) == opt  # the caller has an optimum
    assert walked > 0  # the first optimum was not the smallest, somewhere


@pytest.mark.parametrize("seed", range(6))
def test_the_walk_clauses_hold_exactly_the_smaller_assignments(seed):
    """oracle._smaller against brute force: an assignment of ``order`` extends to a model of
    the clauses iff it first differs from ``current`` where it is true and ``current`` is
    false, before ``current``'s last true variable."""
    from itertools import product

    from pysat.solvers import Solver

    from foon2asp.maxsat.oracle import _smaller

    rng = random.Random(seed)
    for _ in range(12):
        n = rng.randint(0, 7)
        order = rng.sample(range(1, n + 1), n)
        current = {v for v in order if rng.random() < 0.4}
        fresh = iter(range(n + 1, 10_000))
        clauses = _smaller(order, current, lambda: next(fresh))  # noqa: B023
        last = max((k for k, v in enumerate(order) if v in current), default=-1)
        with Solver(name="g4", bootstrap_with=clauses) as sat:
            for bits in product((False, True), repeat=n):
                first = next((k for k in range(n) if bits[k] != (order[k] in current)), None)
                smaller = first is not None and bits[first] and first < last
                assumptions = [v if b else -v for v, b in zip(order, bits, strict=True)]
                assert sat.solve(assumptions=assumptions) == smaller, (order, current, bits)


@pytest.mark.parametrize("solve", ["rc2", "highs"])
def test_a_cycle_cheaper_than_any_tree_is_cut(solve):
    """g needs x; x is made from g (a cycle of two units) or from the kitchen in three steps:
    the relaxation's optimum is the cycle, which is no tree; one loop cut later the optimum is 4."""
    problem = build(
        [
            ("mix", ["x"], ["g"]),
            ("melt", ["g"], ["x"]),
            ("cut", ["k"], ["y"]),
            ("boil", ["y"], ["z"]),
            ("fry", ["z"], ["x"]),
        ],
        ["k"],
    )
    goal = goal_id(problem, "g")
    if solve == "highs":
        pytest.importorskip("highspy")
    minimum = minimum_tree if solve == "rc2" else minimum_tree_mip
    found = minimum(problem, goal, range(len(problem.units)), [1] * len(problem.units))
    assert found.status == "optimal" and found.cuts >= 1
    assert found.tree == (0, 2, 3, 4) and found.lower == 4
    assert validate(problem, goal, list(found.tree)).valid
    # a required unit is in the tree: the cycle's second unit fires once g is made
    forced = minimum(problem, goal, range(5), [1] * 5, require=[1])
    assert forced.status == "optimal" and forced.tree == (0, 1, 2, 3, 4) and forced.lower == 5


def test_an_oracle_told_to_stop_keeps_a_valid_bound():
    oracle = Oracle()
    for v in range(1, 6):
        oracle.soft(-v, 1)
    oracle.hard([1, 2])
    oracle.hard([3, 4])
    with pytest.raises(Stopped):
        oracle.solve(deadline=time.perf_counter() - 1)
    assert oracle.lower == 0
    model = Oracle()
    for v in range(1, 6):
        model.soft(-v, 1)
    model.hard([1, 2])
    model.hard([3, 4])
    best = model.solve()
    assert best is not None and len(best & {1, 2, 3, 4, 5}) == 2 and model.lower == 2
    model.hard([5])  # a clause after a solve: a new solver, the bound kept
    again = model.solve()
    assert again is not None and 5 in again and model.lower == 3


def test_the_preprocessed_oracle_answers_as_the_plain_one():
    """Random weighted formulas with auxiliary variables the preprocessor eliminates: the same
    optimum with and without preprocessing, every model satisfying the original hard clauses,
    and None for unsatisfiable hard clauses."""
    rng = random.Random(11)
    compared = unsat = 0
    for _ in range(60):
        softs = rng.randint(3, 7)
        top = softs + rng.randint(2, 6)
        hard = [
            [rng.choice([-1, 1]) * rng.randint(1, top) for _ in range(rng.randint(1, 3))]
            for _ in range(rng.randint(4, 14))
        ]
        weights = [rng.choice([1, 1, 2, 5]) for _ in range(softs)]
        costs = []
        for rounds in (0, 1):
            oracle = Oracle()
            for v, w in enumerate(weights, 1):
                oracle.soft(-v, w)
            oracle.hards([list(c) for c in hard])
            previous, oracle_module.PROCESS = oracle_module.PROCESS, rounds
            try:
                model = oracle.solve()
            finally:
                oracle_module.PROCESS = previous
            if model is None:
                costs.append(None)
                continue
            assert all(any((lit > 0) == (abs(lit) in model) for lit in clause) for clause in hard)
            costs.append(sum(w for v, w in enumerate(weights, 1) if v in model))
            assert costs[-1] == oracle.lower
        assert costs[0] == costs[1]
        compared += 1
        unsat += costs[0] is None
    assert compared == 60 and 0 < unsat < 60


def test_a_search_cut_short_bounds_the_optimum_from_below(hard):
    problem, goals = hard
    goal = goals[8]  # about 50 units in a part of about 2,900: seconds to prove
    bounds = Bounds(problem, ("units",), problem.units_for([goal]))
    part = bounds.keep(goal, problem.units_for([goal]))
    full = minimum_tree(problem, goal, part, bounds.w, bounds.landmarks(goal))
    assert full.status == "optimal" and validate(problem, goal, list(full.tree)).valid
    assert bounds.lower(goal) <= full.lower == len(full.tree) <= bounds.upper(goal)
    lowers = []
    for limit in (0.05, 0.3, 1.0):
        short = minimum_tree(problem, goal, part, bounds.w, deadline=time.perf_counter() + limit)
        lowers.append(short.lower)
        assert short.lower <= full.lower
        assert short.status in ("stopped", "optimal")
    # a stop asked for by the caller (a gap reached) ends it with the bound seen
    seen: list[int] = []
    stopped = minimum_tree(problem, goal, part, bounds.w, stop=lambda lower: seen.append(lower) or lower >= 10)
    assert stopped.status == "stopped" and 10 <= stopped.lower <= full.lower and max(seen) >= 10


def test_the_runner_proves_a_hard_goal_by_maxsat_and_reports_a_bound_when_cut_short(hard):
    problem, goals = hard
    goal = goals[8]
    (full,) = solve_goals(problem, [goal], "asp", AspOptions())
    assert full.status == "optimal" and full.stats["shortcut"] == "maxsat"
    assert validate(problem, goal, full.units).valid
    assert full.bound == {"units": len(full.units)} and full.gap == 0.0
    (short,) = solve_goals(problem, [goal], "asp", AspOptions(time_limit=0.2))
    assert short.status == "feasible" and short.stats["shortcut"] == "maxsat"
    assert validate(problem, goal, short.units).valid
    assert short.bound["units"] <= len(full.units) < len(short.units)
    # without MaxSAT the solver's answer is the same tree
    runner = GoalRunner("asp", problem, AspOptions(time_limit=120), "per-goal")
    runner.maxsat = False
    clingo = runner(goal)
    assert clingo.status == "optimal" and len(clingo.units) == len(full.units)


@pytest.mark.parametrize("chunk", range(4))
def test_minimum_tree_within_a_depth_is_the_brute_force_optimum(chunk):
    """Within the goal's level (no tree is shallower): the least weight among the trees that deep."""
    checked = 0
    for seed, ranked in [(s, r) for s in range(10 * chunk, 10 * chunk + 10) for r in RANKED]:
        problem = cyclic_foon(seed)
        levels, _ = problem.derivation_levels()
        bounds = Bounds(problem, ranked)
        for goal in range(len(problem.objects)):
            if goal in problem.kitchen or goal not in levels:
                continue
            depth = levels[goal]
            trees = [t for t in brute_force(problem, goal) if measures(problem, goal, list(t))["depth"] <= depth]
            found = minimum_tree(problem, goal, range(len(problem.units)), bounds.w, depth=depth)
            assert found.status == "optimal" and found.cuts == 0
            assert validate(problem, goal, list(found.tree)).valid
            assert measures(problem, goal, list(found.tree))["depth"] == depth
            assert bounds.weight(found.tree) == min(bounds.weight(t) for t in trees) == found.lower, (seed, goal)
            checked += 1
    assert checked > 0


@pytest.mark.parametrize("objective", [("depth",), ("depth", "success"), ("depth", "inputs")])
def test_depth_first_by_maxsat_equals_the_rounds_of_clingo(objective):
    """Depth first: MaxSAT within the goal's level gives the trees, costs and bounds of the
    driver's rounds (MaxSAT off), goal by goal on random FOONs with cycles."""
    options = AspOptions(objective=objective)
    proven = 0
    for seed in range(25):
        problem = cyclic_foon(seed)
        sat = GoalRunner("asp", problem, options, "per-goal")
        rounds = GoalRunner("asp", problem, options, "per-goal")
        rounds.maxsat = False
        for goal in sorted(problem.derivable - problem.kitchen):
            a, b = sat(goal), rounds(goal)
            assert a.status == b.status == "optimal", (seed, goal)
            assert sorted(a.units) == sorted(b.units), (seed, goal)
            assert a.cost == b.cost and a.bound == b.bound and a.gap == b.gap == 0.0
            assert a.extra["asp_cost"] == list(b.extra["asp_cost"])
            assert a.stats["shortcut"] in ("maxsat", "no-choice") and "shortcut" not in b.stats
            proven += a.stats["shortcut"] == "maxsat"
        assert rounds.counts["maxsat"] == 0
    assert proven > 20


def test_depth_first_cut_short_reports_the_depth_and_a_bound(hard):
    problem, goals = hard
    goal = goals[8]
    options = AspOptions(objective=("depth", "success"))
    (full,) = solve_goals(problem, [goal], "asp", options)
    assert full.status == "optimal" and full.stats["shortcut"] == "maxsat"
    assert validate(problem, goal, full.units).valid
    (short,) = solve_goals(problem, [goal], "asp", AspOptions(objective=("depth", "success"), time_limit=0.05))
    assert short.status in ("feasible", "optimal") and validate(problem, goal, short.units).valid
    assert short.cost["depth"] == full.cost["depth"] == short.bound["depth"]
    assert short.bound["success"] >= full.cost["success"] - 1e-12  # a bound on the product: from above


def test_a_sat_call_deaf_to_the_interrupt_is_given_up():
    """A SAT call that does not answer the interrupt: the caller goes on (Stopped) while the
    call still runs, marks the solver abandoned, and the call ends later on its own."""
    import threading

    from foon2asp.maxsat.oracle import _watched

    release, ended = threading.Event(), threading.Event()

    class Sat:
        interrupts = 0

        def interrupt(self):
            self.interrupts += 1

    class Solver:
        cost, halt, abandoned, oracle = 3, False, False, Sat()

    def deaf():
        release.wait(30)
        ended.set()
        return [1]

    solver = Solver()
    with pytest.raises(Stopped):
        _watched(solver, time.perf_counter() + 0.05, None, deaf)
    assert not ended.is_set() and solver.halt and solver.abandoned and solver.oracle.interrupts >= 1
    release.set()
    assert ended.wait(5)
    # a call that returns: its result, and the stop asked with the solver's cost
    asked = []
    assert _watched(Solver(), None, lambda cost: asked.append(cost) or False, lambda: (time.sleep(0.1), 7)[1]) == 7
    assert asked and set(asked) == {3}


@pytest.mark.parametrize("size", [3, 8, 9, 14])
def test_rc2_minimises_only_small_cores_with_equal_weights(size):
    """A core of ``size`` soft literals of which one alone is unsatisfiable: minimised to that
    one up to oracle.MINIMISE_UP_TO literals, kept as found above."""
    from pysat.formula import WCNF

    from foon2asp.maxsat import oracle

    formula = WCNF()
    formula.append([1])  # x1 must hold: the soft literal -x1 alone is a core
    for v in range(1, size + 1):
        formula.append([-v], weight=1)
    rc2 = oracle._RC2(formula, solver=oracle.SAT_SOLVER, exhaust=True, minz=True, trim=0, process=0)
    rc2.core = [-v for v in range(size, 0, -1)]
    rc2.minw = 1
    rc2.minimize_core()
    assert sorted(rc2.core) == ([-1] if size <= oracle.MINIMISE_UP_TO else sorted(-v for v in range(1, size + 1)))
    rc2.delete()
