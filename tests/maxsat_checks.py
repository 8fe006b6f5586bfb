"""Random FOONs with cycles, and the checks every MaxSAT solver of foon2asp.maxsat.trees passes.

``cyclic_foon`` makes small FOONs with several producers per object and many back edges;
the checks run one solver (``minimum_tree``, ``minimum_tree_mip``, ``minimum_tree_uwr``)
against brute force on them, so each solver is held to the same assertions.
"""

from __future__ import annotations

import random
import time
from collections.abc import Callable

from foon2asp.maxsat.trees import Result, minimum_tree
from foon2asp.methods.bounds import Bounds
from foon2asp.tree.tasktree import measures
from foon2asp.tree.validate import validate
from helpers import brute_force, build

#: the objectives the brute-force checks run under (ranked weights)
RANKED = [("units",), ("success", "units"), ("inputs", "units")]


def cyclic_foon(seed: int):
    """A random FOON with several producers per object and many back edges (cycles)."""
    rng = random.Random(seed)
    kitchen = ["k0", "k1", "k2"]
    made = [f"o{i}" for i in range(7)]
    units = []
    for i in range(rng.randint(8, 13)):
        out = rng.choice(made)
        pool = kitchen + [m for m in made if m != out] * 2  # made objects twice as likely: cycles
        ins = list(dict.fromkeys(rng.sample(pool, rng.randint(1, 3))))
        outs = [out] if rng.random() < 0.7 else [out, rng.choice([m for m in made if m != out])]
        units.append((f"m{i % 4}", ins, outs))
    rates = {f"m{i}": r for i, r in enumerate((0.9, 0.5, 0.7, 0.3))}
    return build(units, kitchen, rates)


def check_brute_force_optima(solve: Callable[..., Result], solver: str, chunk: int) -> None:
    """``solve`` (called as ``minimum_tree_*`` is) finds the brute-force optimum of every made
    object of five random FOONs (``chunk`` picks them), for every objective of :data:`RANKED`,
    with and without the goal's level as depth bound, proved by ``solver``."""
    checked = 0
    for seed, ranked in [(s, r) for s in range(5 * chunk, 5 * chunk + 5) for r in RANKED]:
        problem = cyclic_foon(seed)
        levels, _ = problem.derivation_levels()
        bounds = Bounds(problem, ranked)
        for goal in range(len(problem.objects)):
            if goal in problem.kitchen:
                continue
            every = brute_force(problem, goal)
            for depth in (None, levels[goal]) if goal in levels else (None,):
                trees = (
                    every if depth is None else [t for t in every if measures(problem, goal, list(t))["depth"] <= depth]
                )
                found = solve(problem, goal, range(len(problem.units)), bounds.w, depth=depth)
                if not trees:
                    assert found.status == "unreachable" and found.tree is None, (seed, ranked, goal, depth)
                    continue
                opt = min(bounds.weight(t) for t in trees)
                assert found.status == "optimal" and found.solver == solver, (seed, ranked, goal, depth)
                assert validate(problem, goal, list(found.tree)).valid
                assert bounds.weight(found.tree) == opt == found.lower, (seed, ranked, goal, depth)
                if depth is not None:
                    assert measures(problem, goal, list(found.tree))["depth"] <= depth
                checked += 1
    assert checked > 0


def check_required_units(solve: Callable[..., Result]) -> None:
    """``solve`` with one unit required gives the smallest tree holding it, for every unit."""
    problem = cyclic_foon(3)
    bounds = Bounds(problem, ("units",))
    levels, unit_levels = problem.derivation_levels()
    goal = max(levels, key=lambda o: levels[o])
    trees = brute_force(problem, goal)
    for u in sorted(unit_levels):
        with_u = [t for t in trees if u in t]
        found = solve(problem, goal, range(len(problem.units)), bounds.w, require=[u])
        if not with_u:
            assert found.status != "optimal" or u in found.tree
            continue
        assert found.status == "optimal" and u in found.tree
        assert len(found.tree) == min(len(t) for t in with_u)


def check_proof_after_a_stuck_rc2(objective: tuple[str, ...], solver: str, search: str, **after: float) -> None:
    """With RC2 stuck (the ``slow_rc2`` fixture), the helper ``after`` names (``mip_after=`` or
    ``uwr_after=``) proves the brute-force optimum of every made object of six random FOONs."""
    checked = 0
    for seed in range(6):
        problem = cyclic_foon(seed)
        bounds = Bounds(problem, objective)
        for goal in range(len(problem.objects)):
            trees = brute_force(problem, goal) if goal not in problem.kitchen else []
            if not trees:
                continue
            units = range(len(problem.units))
            found = minimum_tree(problem, goal, units, bounds.w, deadline=time.perf_counter() + 30, **after)
            opt = min(bounds.weight(t) for t in trees)
            assert found.status == "optimal" and found.solver == solver and found.search == search
            assert bounds.weight(found.tree) == opt == found.lower and validate(problem, goal, list(found.tree)).valid
            checked += 1
    assert checked > 10
