"""The goal runner (methods/runner.py): every registered method, every tree judged by the
independent validator (tree/validate.py), on the demo data and on a synthetic preset; and every
route against brute force on small random FOONs with real choice."""

from __future__ import annotations

import functools
import json
import random

import pytest

from conftest import DEMO
from foon2asp import methods
from foon2asp.analysis.compare import judge
from foon2asp.asp.grounding import fact_programs
from foon2asp.asp.objectives import motion_cost_weights, ranked
from foon2asp.asp.options import AspOptions
from foon2asp.batch.pool import BatchSpec, Worker
from foon2asp.errors import InputError
from foon2asp.foon.loaders import Dataset
from foon2asp.foon.problem import Problem
from foon2asp.methods.registry import effective_options
from foon2asp.methods.runner import PROVEN_BY, GoalRunner, solve_goals
from foon2asp.tree.tasktree import TaskTree, measures
from foon2asp.tree.validate import bounds_proof, validate
from foon2asp.tree.weights import total
from helpers import brute_force, build, real_choice
from synth import preset

CASES = ("demo", "tiny", "small")


@pytest.fixture(scope="module", params=CASES)
def case(request) -> tuple[str, Problem, list[int]]:
    """The case's name, problem and goals: every object of the demo data, the preset's goals."""
    if request.param == "demo":
        problem = Problem.from_dataset(Dataset.load(DEMO))
        return request.param, problem, list(range(len(problem.objects)))
    syn = preset(request.param)
    problem = syn.problem()
    return request.param, problem, [problem.foon.object_ids[g] for g in syn.goals]


@pytest.fixture(scope="module")
def options(case) -> AspOptions:
    """The default options with a motion-cost table (in hundredths), which the objective
    ``cost`` needs and every other objective ignores: seeded random costs, but on the
    small preset every motion costs 1 (with random costs the proof of one of its goals
    takes from seconds to minutes)."""
    name, problem, _ = case
    rng = random.Random(11)
    motions = sorted({u.motion for u in problem.units})
    return AspOptions(motion_costs={m: 100 if name == "small" else rng.randint(0, 300) for m in motions})


def derivable(problem: Problem, goal: int) -> bool:
    """By the validator alone: fire every unit that can fire, then is the goal had?"""
    fired = validate(problem, goal, list(range(len(problem.units)))).order
    return validate(problem, goal, fired).valid


def kind(name: str) -> str:
    """``exact`` (an ASP optimum), ``greedy`` (an ASP first model) or ``search``."""
    if methods.get(name).kind != "asp":
        return "search"
    return "greedy" if effective_options(name, AspOptions()).heuristic else "exact"


def objective_of(name: str) -> str:
    """The first objective an exact ASP method optimises."""
    return ranked(effective_options(name, AspOptions()))[0]


def value(problem: Problem, objective: str, goals, units: list[int], options: AspOptions) -> int:
    """The tree's value under ``objective``: the depth, or the sum of unit weights the solver minimises."""
    if objective == "depth":
        return measures(problem, goals, units)["depth"]
    if objective == "cost":
        assert options.motion_costs is not None
        weights = motion_cost_weights(problem, options.motion_costs)
        return sum(weights[u] for u in units)
    return total(problem, objective, units)


@pytest.fixture(scope="module")
def trees(case, options) -> dict[str, list[TaskTree]]:
    """Each method's trees for the case's goals, through the one entry point."""
    _, problem, goals = case
    return {name: list(solve_goals(problem, goals, name, options)) for name in methods.names()}


def test_every_method_answers_every_goal_and_the_validator_agrees(case, trees):
    _, problem, goals = case
    for name, answers in trees.items():
        assert [t.goal for t in answers] == goals, name
        for tree in answers:
            made = derivable(problem, tree.goal)
            checked = validate(problem, tree.goal, tree.units) if tree.has_tree else None
            # compare's and batch's "valid" is exactly what the validator says
            assert judge(problem, tree).valid == (checked is not None and checked.valid), (name, tree.goal)
            if kind(name) == "search":
                assert tree.status in ("found", "not-found"), (name, tree.goal)
                assert tree.has_tree or not tree.units
                continue
            # an ASP method has a tree exactly for the goals that can be made, and it is valid
            assert tree.has_tree == made, (name, tree.goal, tree.status)
            assert checked is None or checked.valid, (name, tree.goal, checked.reason)
            assert tree.status in (("optimal",) if kind(name) == "exact" else ("optimal", "found", "ranked")) or (
                tree.status == "unreachable" and not made
            ), (name, tree.goal, tree.status)
            if tree.has_tree:
                assert tree.cost == measures(problem, tree.goal, tree.units), (name, tree.goal)
            if tree.status == "optimal" and tree.bound is not None:
                # a proven answer's bound is its own cost, on whatever path it was found
                assert tree.gap == 0.0 and all(tree.bound[k] == tree.cost[k] for k in tree.bound if k in tree.cost)


def test_every_optimum_is_no_worse_than_any_valid_tree_of_another_method(case, trees, options):
    _, problem, goals = case
    for name, answers in trees.items():
        if kind(name) != "exact":
            continue
        objective = objective_of(name)
        for i, tree in enumerate(answers):
            if not tree.has_tree:
                continue
            best = value(problem, objective, tree.goal, tree.units, options)
            for other, theirs in trees.items():
                rival = theirs[i]
                if rival.has_tree and validate(problem, rival.goal, rival.units).valid:
                    assert best <= value(problem, objective, rival.goal, rival.units, options), (name, other, tree.goal)


def test_meals_through_the_runner(case, trees, options):
    """A meal of two goals: one valid tree for both from every ASP method, between the
    single optima (at least the larger, at most their sum; for depth: the larger)."""
    _, problem, goals = case
    meal = tuple(g for g in goals if g not in problem.kitchen and derivable(problem, g))[:2]
    assert len(meal) == 2
    for name in methods.names():
        if kind(name) == "search":
            with pytest.raises(InputError, match="meals"):
                next(solve_goals(problem, [meal], name, options))
            continue
        together, *singles = solve_goals(problem, [meal, *meal], name, options)
        assert together.has_tree and together.meal == meal, name
        assert all(validate(problem, g, together.units).valid for g in meal), name
        assert [t.goal for t in singles] == list(meal)
        if kind(name) != "exact":
            continue
        objective = objective_of(name)
        got = value(problem, objective, meal, together.units, options)
        alone = [value(problem, objective, t.goal, t.units, options) for t in singles]
        assert max(alone) <= got <= (max(alone) if objective == "depth" else sum(alone)), (name, got, alone)


@pytest.mark.parametrize("grounding", ["whole", "per-goal"])
def test_batch_workers_build_the_same_runner(case, trees, options, grounding):
    """A batch worker's lines (either grounding) have the trees' status and the validator's "valid"."""
    _, problem, goals = case
    index = {json.dumps(u.to_json(), sort_keys=True): i for i, u in enumerate(problem.units)}
    names = methods.names()
    worker = Worker(BatchSpec(problem, names, options, grounding))
    for name in names:
        for goal, tree in zip(goals, trees[name]):
            record = json.loads(worker.run(goal, name))
            units = [index[json.dumps(u, sort_keys=True)] for u in record["units"]]
            assert record["status"] == tree.status, (name, goal, grounding)
            assert record["valid"] == (tree.has_tree and validate(problem, goal, units).valid), (name, goal)
            if kind(name) == "exact":
                # the canonical tree, whichever grounding and whichever units were grounded
                assert sorted(units) == sorted(tree.units), (name, goal, grounding)


# The goal runner's routes (foon2asp.methods.runner): every route against brute force.
#
# Small random FOONs with real choice, cycles and units with several products: for every
# objective the answer of every route (settled by preparation, clingo on the prepared part,
# clingo on the whole grounding) is an optimal, valid tree of the brute-force optimum; the
# answer says what proved it; the tree is the same on every path; user constraints keep the
# optimum exact, and a goal whose every tree they forbid is ``infeasible``.


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
            assert tree.status == "infeasible" and tree.infeasible_by == ["--rule #1"], (seed, goal)
            assert tree.proven_by == "clingo"
        elif want is None:
            assert tree.status == "unreachable" and tree.proven_by == "fixpoint", (seed, goal)
        else:
            assert tree.status == "optimal" and tree.proven_by == PROVEN_BY[run.route(goal)]
            assert allowed(tree.units) and validate(problem, goal, list(tree.units)).valid
            assert score(problem, goal, tree.units, ("units",)) == want, (seed, goal)
            if allowed(plain(goal).units):  # the rule changes nothing here: the same optimum
                assert tree.asp_cost == plain(goal).asp_cost, (seed, goal)


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
        assert (a.status, a.asp_cost) == (b.status, b.asp_cost), (seed, goal)
        if plain.route(goal) != "prepared":
            assert sorted(a.units) == sorted(b.units), (seed, goal)


def test_a_settled_tree_that_breaks_a_rule_goes_to_clingo():
    """The only tree of a goal breaks the rule: clingo decides the goal."""
    for seed in range(25):
        problem = random_foon(seed)
        plain = GoalRunner("asp", problem, AspOptions())
        for goal in made_objects(problem):
            if plain.route(goal) != "only-tree":
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
    """The 25 goals of ../shared/foon: a goal with a choice in its part (more than one tree) is
    clingo's, also when its landmarks alone make it (their proof verified beside); only goals
    without choice are settled by the only-tree route."""
    import foon2asp

    kb = foon2asp.load(str(shared_foon_dir))
    run = GoalRunner("asp", kb.problem, AspOptions())
    seen = {}
    for goal in kb.goal_ids("all"):
        tree = run(goal)
        _, _, choice = run.parts.relevant(goal)
        if goal not in kb.problem.derivable or goal in kb.problem.kitchen:
            assert tree.proven_by == "fixpoint", goal
        elif choice and real_choice(kb.problem, goal, tree.units):
            assert tree.status == "optimal" and tree.proven_by == "clingo", goal
        elif choice:  # one minimal tree: its landmarks, and still clingo's
            assert tree.status == "optimal" and tree.proven_by == "clingo", goal
            assert bounds_proof(kb.problem, goal, tree.units, sorted(tree.units)) is None, goal
        else:
            assert tree.proven_by == "only-tree", goal
        seen[tree.proven_by] = seen.get(tree.proven_by, 0) + 1
    assert seen == {"clingo": 21, "only-tree": 2, "fixpoint": 2}, seen


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


def test_a_goal_searched_in_rounds_of_loop_cuts_writes_its_facts_once(monkeypatch):
    """A single-shot session grounds its facts again for each round of loop cuts, but writes
    them once."""
    import foon2asp.asp.session as session_mod

    written: list[int] = []

    def counted(grounding):
        written.append(id(grounding))
        return fact_programs(grounding)

    monkeypatch.setattr(session_mod, "fact_programs", counted)
    single = 0
    for seed in range(25):
        problem = random_foon(seed)
        for objective in OBJECTIVES[:3]:
            run = GoalRunner("asp", problem, AspOptions(objective=objective), shortcuts=False)
            for goal in made_objects(problem):
                written.clear()
                tree = run(goal)
                if tree.stats.get("loop_cuts"):
                    single += tree.stats["plan"]["args"][-1] == "--single-shot"
                    assert len(written) == 1, (seed, goal, written)
    assert single >= 2


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
            assert tree.status == "infeasible" and (tree.infeasible_by or []) == want, (seed, goal, want)
            seen[min(len(want), 1)] += 1
    assert seen[0] > 0 and seen[1] > 0, seen
