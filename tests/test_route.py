"""The goal runner's routes (foon2asp.methods.runner): every route against brute force.

Small random FOONs with real choice, cycles and units with several products: for every
objective the answer of every route (settled by preparation, clingo on the prepared part,
clingo on the whole grounding) is an optimal, valid tree of the brute-force optimum; the
answer says what proved it; the tree is the same on every path; user constraints keep the
optimum exact, and a goal whose every tree they forbid is ``infeasible``.
"""

from __future__ import annotations

import functools
import random

import pytest

from foon2asp.asp.options import AspOptions
from foon2asp.methods.runner import PROVEN_BY, GoalRunner
from foon2asp.tree.tasktree import measures
from foon2asp.tree.validate import validate
from foon2asp.tree.weights import total
from helpers import brute_force, build

OBJECTIVES = [("units",), ("success",), ("inputs",), ("depth",), ("success", "depth")]


@functools.cache
def random_foon(seed: int):
    """Up to 12 units over 7 made objects: several producers each, units with two products,
    inputs made elsewhere (so cycles), and some units that never fire."""
    rng = random.Random(seed)
    kitchen = ["k0", "k1", "k2"]
    made = [f"o{i}" for i in range(7)]
    units = []
    for i in range(rng.randint(8, 12)):
        outs = rng.sample(made, 2 if rng.random() < 0.3 else 1)
        pool = kitchen + [m for m in made if m not in outs] + ["never"] * (rng.random() < 0.1)
        ins = rng.sample(pool, rng.randint(1, 3))
        units.append((f"m{i % 5}", ins, outs))
    rates = {f"m{i}": r for i, r in enumerate((0.9, 0.5, 0.7, 0.3, 0.95))}
    return build(units, kitchen, rates)


def score(problem, goal, tree, objective):
    """The cost vector of ``tree`` for ``objective`` with units as the last tie-breaker."""
    ranked = list(dict.fromkeys((*objective, "units")))
    depth = measures(problem, goal, list(tree))["depth"]
    return tuple(depth if name == "depth" else total(problem, name, tree) for name in ranked)


def optimum(problem, goal, objective, allowed=lambda tree: True):
    trees = [t for t in brute_force(problem, goal) if allowed(t)]
    return min((score(problem, goal, t, objective) for t in trees), default=None)


def made_objects(problem):
    return sorted({o for u in range(len(problem.units)) for o in problem.products[u]})


@pytest.mark.parametrize("objective", OBJECTIVES, ids=",".join)
@pytest.mark.parametrize("seed", range(25))
def test_every_route_answers_the_brute_force_optimum(seed, objective):
    problem = random_foon(seed)
    options = AspOptions(objective=objective)
    fast = GoalRunner("asp", problem, options)
    unsettled = GoalRunner("asp", problem, options, shortcuts=False)
    whole = GoalRunner("asp", problem, options, grounding="per-goal")
    for goal in made_objects(problem):
        want = optimum(problem, goal, objective)
        for run in (fast, unsettled, whole):
            route = run.route(goal)
            tree = run(goal)
            if want is None:
                assert tree.status == "unreachable", (seed, goal, route)
                assert tree.proven_by in ("fixpoint", "clingo"), (seed, goal, route)
                continue
            assert tree.status == "optimal", (seed, goal, route, tree.status)
            assert validate(problem, goal, list(tree.units)).valid, (seed, goal, route)
            assert score(problem, goal, tree.units, objective) == want, (seed, goal, route)
            assert tree.proven_by == PROVEN_BY[route], (seed, goal, route)
        assert sorted(fast(goal).units) == sorted(unsettled(goal).units), (seed, goal)


def test_the_routes_are_all_taken_and_named():
    """Over the random FOONs every route of the table answers some goal, and the JSON names it."""
    seen = set()
    for seed in range(25):
        problem = random_foon(seed)
        run = GoalRunner("asp", problem, AspOptions())
        for goal in made_objects(problem):
            seen.add(run.route(goal))
        run_depth = GoalRunner("asp", problem, AspOptions(objective=("depth",)))
        seen.update(run_depth.route(g) for g in made_objects(problem))
    assert seen == {"fixpoint", "only-tree", "prepared", "clingo"}


@pytest.mark.parametrize("seed", range(25))
def test_constraints_keep_the_optimum_exact_and_name_an_infeasible_goal(seed):
    """A rule that forbids a motion: the optimum among the trees without it (brute force), on the
    prepared route; a goal every tree of which uses it is ``infeasible`` with the rule named."""
    problem = random_foon(seed)
    rule = ("--rule #1", ':- use(U), motion(U,"m1").\n')
    options = AspOptions(programs=[rule])
    run = GoalRunner("asp", problem, options)
    plain = GoalRunner("asp", problem, AspOptions())
    for goal in made_objects(problem):
        allowed = lambda t: all(problem.units[u].motion != "m1" for u in t)  # noqa: E731
        want = optimum(problem, goal, ("units",), allowed)
        tree = run(goal)
        if want is None and optimum(problem, goal, ("units",)) is not None:
            assert tree.status == "infeasible" and tree.extra["infeasible_by"] == ["--rule #1"], (seed, goal)
            assert tree.proven_by == "clingo"
        elif want is None:
            assert tree.status == "unreachable" and tree.proven_by == "fixpoint", (seed, goal)
        else:
            assert tree.status == "optimal" and tree.proven_by == PROVEN_BY[run.route(goal)]
            assert allowed(tree.units) and validate(problem, goal, list(tree.units)).valid
            assert score(problem, goal, tree.units, ("units",)) == want, (seed, goal)
            if allowed(plain(goal).units):  # the rule changes nothing here: the same optimum
                assert tree.extra["asp_cost"] == plain(goal).extra["asp_cost"], (seed, goal)


def test_a_program_that_defines_what_the_encodings_define_goes_to_clingo_whole():
    problem = next(p for p in map(random_foon, range(25)) if p.derivable & set(made_objects(p)))
    options = AspOptions(programs=[("--rule #1", "use(U) :- unit(U), U < 0.\n")])
    run = GoalRunner("asp", problem, options)
    goal = next(g for g in made_objects(problem) if g in problem.derivable)
    assert run.route(goal) == "clingo"
    assert run(goal).proven_by == "clingo"


def test_search_baselines_are_proven_by_nothing():
    problem = random_foon(1)
    run = GoalRunner("gbfs-h1", problem, AspOptions())
    goal = made_objects(problem)[0]
    assert run.route(goal) == "search" and run(goal).proven_by is None


@pytest.mark.parametrize("seed", range(25))
def test_a_rule_that_changes_nothing_keeps_every_route_and_tree(seed):
    """A rule no tree breaks: each goal takes the route it takes without the rule, with the same
    tree (a settled tree is checked against the rule, not sent to clingo)."""
    problem = random_foon(seed)
    plain = GoalRunner("asp", problem, AspOptions())
    ruled = GoalRunner("asp", problem, AspOptions(programs=[("--rule #1", ':- use(U), motion(U,"teleport").\n')]))
    for goal in made_objects(problem):
        assert ruled.route(goal) == plain.route(goal), (seed, goal)
        a, b = plain(goal), ruled(goal)
        assert (a.status, a.extra.get("asp_cost")) == (b.status, b.extra.get("asp_cost")), (seed, goal)
        if plain.route(goal) != "prepared":
            assert sorted(a.units) == sorted(b.units), (seed, goal)


def test_a_settled_tree_that_breaks_a_rule_goes_to_clingo():
    """The bounds tree (or the only tree) of a goal breaks the rule: clingo decides the goal."""
    for seed in range(25):
        problem = random_foon(seed)
        plain = GoalRunner("asp", problem, AspOptions())
        for goal in made_objects(problem):
            if plain.route(goal) not in ("bounds", "only-tree"):
                continue
            unit = plain(goal).units[0]
            rule = f":- use({unit}).\n"
            ruled = GoalRunner("asp", problem, AspOptions(programs=[("--rule #1", rule)]))
            assert ruled.route(goal) == "prepared", (seed, goal)
            tree = ruled(goal)
            assert unit not in tree.units and tree.proven_by == "clingo", (seed, goal)
            return
    raise AssertionError("no settled goal found")


def test_compare_with_constraints_draws_no_conclusion_from_the_baselines(shared_foon_dir):
    """The asp tree obeys --forbid-motion, the baselines do not: no 'smaller than the optimum'
    warning from an IDS tree that uses the motion, and the summary says why."""
    from click.testing import CliRunner

    from foon2asp.cli.main import main

    res = CliRunner().invoke(
        main, ["compare", "--data", str(shared_foon_dir), "--goal", "macaroni", "--forbid-motion", "heat"]
    )
    assert res.exit_code in (0, 1), res.output
    assert "smaller than the asp optimum" not in res.output
    assert "asp obeys the constraints (--forbid-motion heat); the other methods are unconstrained" in res.output
    plain = CliRunner().invoke(main, ["compare", "--data", str(shared_foon_dir), "--goal", "macaroni"])
    assert "asp optimum <= every valid tree: yes" in plain.output


def test_every_reference_goal_with_real_choice_is_proven_by_clingo(shared_foon_dir):
    """The 25 goals of ../shared/foon: a goal with more than one tree is clingo's, even when its
    bounds already meet; only goals without choice are settled by preparation."""
    import foon2asp

    kb = foon2asp.load(str(shared_foon_dir))
    run = GoalRunner("asp", kb.problem, AspOptions())
    seen = {}
    for goal in kb.goal_ids("all"):
        tree = run(goal)
        _, _, choice = run.parts.relevant(goal)
        if goal not in kb.problem.derivable or goal in kb.problem.kitchen:
            assert tree.proven_by == "fixpoint", goal
        elif choice:
            assert tree.status == "optimal" and tree.proven_by == "clingo", goal
        else:
            assert tree.proven_by == "only-tree", goal
        seen[tree.proven_by] = seen.get(tree.proven_by, 0) + 1
    assert seen.get("clingo", 0) >= 20 and "bounds" not in seen, seen


def test_loop_cuts_end_at_the_brute_force_optimum():
    """Goals whose optimal closed set rests on a cycle: clingo searches again after each loop
    cut, and the last round's tree is the brute-force optimum."""
    cut = 0
    for seed in range(25):
        problem = random_foon(seed)
        for objective in OBJECTIVES[:3]:
            run = GoalRunner("asp", problem, AspOptions(objective=objective), shortcuts=False)
            for goal in made_objects(problem):
                tree = run(goal)
                if not tree.stats.get("loop_cuts"):
                    continue
                cut += 1
                assert tree.status == "optimal" and tree.proven_by == "clingo", (seed, goal)
                assert validate(problem, goal, list(tree.units)).valid, (seed, goal)
                assert score(problem, goal, tree.units, objective) == optimum(problem, goal, objective), (seed, goal)
    assert cut >= 5


def test_an_infeasible_goal_names_each_program_that_alone_rules_out_every_tree():
    """Two rules, each forbidding one motion: a goal with trees but none that obeys both is
    ``infeasible``, naming exactly the rules that alone leave no tree (brute force)."""
    rules = [("--rule #1", ':- use(U), motion(U,"m1").\n'), ("--rule #2", ':- use(U), motion(U,"m3").\n')]
    seen = {0: 0, 1: 0}
    for seed in range(25):
        problem = random_foon(seed)
        run = GoalRunner("asp", problem, AspOptions(programs=rules))
        for goal in made_objects(problem):
            trees = brute_force(problem, goal)
            avoids = [lambda t, m=m: all(problem.units[u].motion != m for u in t) for m in ("m1", "m3")]
            if not trees or any(all(ok(t) for ok in avoids) for t in trees):
                continue
            tree = run(goal)
            want = [name for (name, _), ok in zip(rules, avoids, strict=True) if not any(ok(t) for t in trees)]
            assert tree.status == "infeasible" and tree.extra.get("infeasible_by", []) == want, (seed, goal, want)
            seen[min(len(want), 1)] += 1
    assert seen[0] > 0 and seen[1] > 0, seen
