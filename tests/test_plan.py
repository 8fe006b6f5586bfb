"""The plan (methods/plan.py): one table over every kind of request, each row the route, the entry
encoding, the facts and clingo's arguments the plan decides; and the plan carried out gives the
answer the plan's route promises."""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import pytest

import foon2asp
from foon2asp.asp.constraints import ConstraintSpec
from foon2asp.asp.options import AspOptions
from foon2asp.foon.substitutes import Substitute
from foon2asp.methods.plan import ROUTES, plan, request
from foon2asp.methods.runner import GoalRunner
from foon2asp.tree.validate import bounds_proof, validate
from helpers import brute_force, witness_problem
from test_runner import OBJECTIVES, made_objects, optimum, random_foon, score


@pytest.fixture(scope="module")
def demo():
    return foon2asp.load("demo")


@dataclass
class Row:
    """One kind of request and what its plan must say."""

    what: str
    goal: str | tuple[str, ...]
    route: str
    method: str = "asp"
    options: dict = field(default_factory=dict)
    entry: str | None = None
    facts: set[str] = field(default_factory=set)
    no_facts: set[str] = field(default_factory=set)
    args: set[str] = field(default_factory=set)
    no_args: set[str] = field(default_factory=set)
    shared: bool | None = None
    depth: str | None = None
    canonical: str | None = None
    written: set[str] = field(default_factory=set)
    grounding: str = "whole"
    shortcuts: bool = True
    free_first: bool = False


SALAD, EGG, CREAM = "tomato salad", "scrambled egg", "whipped cream"
DEFINES = [("--rule #1", 'fancy(U) :- use(U).\n:- fancy(U), motion(U,"chop").\n')]
NO_CHOP = [("--rule #1", ':- use(U), motion(U,"chop").\n')]
PREFERS = [("--rule #1", '#minimize { 1@5,U : use(U), motion(U,"chop") }.\n')]
SUBS = (Substitute("salt", "pepper"),)

TABLE = [
    Row("units: the landmarks and a landmark set weigh what the bounds tree weighs", SALAD, "bounds"),
    Row("units: the landmarks alone are a tree", EGG, "bounds"),
    Row("units: no shortcuts, so clingo decides", EGG, "prepared", shortcuts=False, entry="solve_closed"),
    Row("a goal the kitchen cannot make", CREAM, "fixpoint"),
    Row(
        "success: a case split over the producers weighs what the bounds tree weighs",
        SALAD,
        "bounds",
        options={"objective": ("success",)},
    ),
    Row(
        "success, no shortcuts: the bounds tree meets the lower bound, clingo decides",
        SALAD,
        "prepared",
        shortcuts=False,
        options={"objective": ("success",)},
        entry="solve_closed",
        facts={"problem", "preparation", "goal"},
        no_facts={"dominated", "chain"},
        written={"neglog"},
        args={"--heuristic=Domain"},
        no_args={"--single-shot"},
        canonical="hint",
    ),
    Row(
        "success, inputs: clingo optimises in one shot",
        SALAD,
        "prepared",
        options={"objective": ("success", "inputs")},
        facts={"input_nodes"},
        written={"neglog"},
        args={"--single-shot"},
        no_args={"--heuristic=Domain"},
    ),
    Row(
        "cost: the motion costs are written",
        SALAD,
        "clingo",
        options={"objective": ("cost",), "motion_costs": {"chop": 50}},
        facts={"motion_costs", "chain"},
        entry="solve",
        shared=True,
    ),
    Row(
        "depth first: rounds on the whole grounding",
        SALAD,
        "clingo",
        options={"objective": ("depth",)},
        entry="solve",
        shared=True,
        depth="first",
        canonical="driver",
    ),
    Row("depth after units", SALAD, "clingo", options={"objective": ("units", "depth")}, depth="later"),
    Row("a depth bound", SALAD, "clingo", options={"max_depth": 4}, depth="bound", facts={"chain"}),
    Row(
        "a meal: one tree for both goals",
        (SALAD, EGG),
        "clingo",
        entry="solve",
        shared=True,
        facts={"dominated", "chain"},
        no_facts={"goal"},
        canonical="session",
    ),
    Row(
        "a rule that only removes trees",
        SALAD,
        "prepared",
        options={"programs": NO_CHOP},
        entry="solve_prepared",
        free_first=True,
        no_args={"--heuristic=Domain"},
        written={"motion"},
    ),
    Row(
        "a rule that changes the objective",
        SALAD,
        "clingo",
        options={"programs": PREFERS},
        entry="solve",
        written={"motion"},
    ),
    Row(
        "a rule with a head of its own only removes trees",
        SALAD,
        "prepared",
        options={"programs": DEFINES},
        free_first=True,
    ),
    Row(
        "a flag: its fact and the facts its rule reads",
        SALAD,
        "prepared",
        options={"programs": ConstraintSpec(forbid_motion=("chop",)).programs()},
        written={"motion"},
        entry="solve_prepared",
        free_first=True,
    ),
    Row("substitutes", SALAD, "clingo", options={"substitutes": SUBS}, facts={"substitutes", "dominated"}),
    Row("the K best trees", SALAD, "clingo", options={"models": 2}, canonical="driver", no_facts={"dominated"}),
    Row("every optimal tree", SALAD, "clingo", options={"all_optimal": True}, canonical="driver"),
    Row(
        "human steps",
        SALAD,
        "clingo",
        options={"objective": ("success",), "human_steps": 1},
        facts={"human_limit", "human_order"},
        no_facts={"dominated"},
    ),
    Row(
        "greedy retrieval",
        SALAD,
        "clingo",
        method="asp-greedy-h1",
        entry="solve_greedy",
        facts={"ranks"},
        no_facts={"chain"},
        args={"--heuristic=Domain"},
        canonical="none",
    ),
    Row(
        "two threads",
        SALAD,
        "prepared",
        shortcuts=False,
        options={"objective": ("success",), "threads": 2},
        entry="solve_prepared",
        facts={"chain"},
        no_args={"--single-shot"},
        canonical="here",
    ),
    Row(
        "per goal: the goal's part alone",
        SALAD,
        "clingo",
        options={"objective": ("depth",)},
        grounding="per-goal",
        shared=False,
        no_facts={"goal"},
    ),
    Row("a search baseline", SALAD, "search", method="gbfs-h1"),
]


@pytest.mark.parametrize("row", TABLE, ids=[row.what for row in TABLE])
def test_the_plan_of_every_kind_of_request(demo, row: Row):
    goal = tuple(demo.object_id(g) for g in row.goal) if isinstance(row.goal, tuple) else demo.object_id(row.goal)
    options = AspOptions(**row.options)
    req = request(row.method, demo.problem, options, row.grounding, row.shortcuts)
    found = plan(req, goal)
    assert found.route == row.route
    assert found.proven_by == ROUTES[row.route]
    g = found.grounding
    if row.route in ("prepared", "clingo"):
        assert g is not None
        assert row.facts <= set(g.facts) and not (row.no_facts & set(g.facts)), g.facts
        assert row.args <= set(g.args) and not (row.no_args & set(g.args)), g.args
        assert not (row.written & set(g.leave_out)), g.leave_out
        for name, value in (("entry", row.entry), ("depth", row.depth), ("canonical", row.canonical)):
            if value is not None:
                assert getattr(g, name) == value, name
        if row.shared is not None:
            assert found.shared == row.shared
        assert (found.free_first is not None) == row.free_first
        assert found.describe()["entry"] == f"encodings/{g.entry}.lp"
    else:
        assert g is None
    if row.route == "bounds":
        w = found.witness.fields()
        first = found.ranked[0] if found.ranked[0] in ("success", "inputs") else "units"
        args = (w["landmarks"], w["landmark_sets"], first, w["landmark_cases"], w["derivation_level"])
        assert found.tree and bounds_proof(demo.problem, goal, found.tree, *args) is None
    # the plan is a value: asked again, the same decisions
    again = plan(req, goal)
    assert again.describe() == found.describe()


@pytest.mark.parametrize("row", TABLE, ids=[row.what for row in TABLE])
def test_a_plan_carried_out_answers_as_its_route_says(demo, row: Row):
    goal = tuple(demo.object_id(g) for g in row.goal) if isinstance(row.goal, tuple) else demo.object_id(row.goal)
    run = GoalRunner(row.method, demo.problem, AspOptions(**row.options), row.grounding, row.shortcuts)
    tree = run(goal)
    assert run.counts[row.route] == 1
    if row.route == "fixpoint":
        assert tree.status == "unreachable" and tree.proven_by == "fixpoint"
        return
    assert tree.has_tree
    goals = goal if isinstance(goal, tuple) else (goal,)
    for g in goals:
        assert validate(demo.problem, g, list(tree.units)).valid
    if row.route != "search" and row.method == "asp":
        assert tree.status == "optimal" and tree.proven_by in ("clingo", "bounds", "only-tree")


def test_the_bounds_route_answers_the_landmarks_and_names_them(demo):
    run = GoalRunner("asp", demo.problem, AspOptions())
    tree = run(demo.object_id(EGG))
    assert tree.proven_by == "bounds" and tree.landmarks == sorted(tree.units)
    free = GoalRunner("asp", demo.problem, AspOptions(), shortcuts=False)(demo.object_id(EGG))
    assert free.proven_by == "clingo" and sorted(free.units) == sorted(tree.units)
    assert free.asp_cost == tree.asp_cost


# --- the bounds route: against brute force, its witness re-verified, forged witnesses refused ---


def holds_for_every_tree(split: dict, every: list, using: tuple[int, ...]) -> int:
    """Asserts by brute force that every tree using the units ``using`` uses a case's unit of
    ``split``, and with it the case's units and a unit of each of its sets, its deeper splits
    too; returns how many deeper splits there are."""
    trees = [t for t in every if all(u in t for u in using)]
    assert all(any(c["unit"] in t for c in split["cases"]) for t in trees), (split, using)
    deeper = 0
    for c in split["cases"]:
        mine = [t for t in trees if c["unit"] in t]
        assert all(set(c["landmarks"]) <= set(t) for t in mine), (c, using)
        assert all(not set(s).isdisjoint(t) for s in c["landmark_sets"] for t in mine), (c, using)
        if c.get("split"):
            deeper += 1 + holds_for_every_tree(c["split"], every, (*using, c["unit"]))
    return deeper


@pytest.mark.parametrize("objective", [*OBJECTIVES, ("inputs", "success")], ids=",".join)
def test_the_bounds_route_against_brute_force_with_its_witness(objective):
    """Over random small FOONs with real choice: every goal the bounds route settles has the
    brute-force optimum, its landmarks verified by the checker; some goal takes the route unless
    depth is an objective (a tree's depth is no sum of unit weights: more units may be shallower)."""
    settled = 0
    kinds = {"cases": 0, "nested": 0, "level": 0}
    for seed in range(25):
        problem = random_foon(seed)
        run = GoalRunner("asp", problem, AspOptions(objective=objective))
        for goal in made_objects(problem):
            if run.route(goal) != "bounds":
                continue
            settled += 1
            tree = run(goal)
            assert tree.status == "optimal" and tree.proven_by == "bounds", (seed, goal)
            assert score(problem, goal, tree.units, objective) == optimum(problem, goal, objective), (seed, goal)
            marks, sets = tree.landmarks, tree.landmark_sets or []
            first = objective[0] if objective[0] in ("success", "inputs") else "units"
            assert witness_problem(problem, tree, first) is None, (seed, goal)
            # every landmark is in every tree, and every tree uses a unit of each set, by brute force
            every = brute_force(problem, goal)
            assert all(set(marks) <= set(t) for t in every), (seed, goal)
            assert all(not set(s).isdisjoint(t) for s in sets for t in every), (seed, goal)
            # forged: one landmark left out, or a unit that is no landmark claimed
            if marks:
                assert witness_problem(problem, tree, first, landmarks=marks[:-1]) is not None
            spare = [u for u in range(len(problem.units)) if u not in marks and u not in tree.units]
            if spare:
                forged = witness_problem(problem, tree, first, [*marks, spare[0]], [*tree.units, spare[0]])
                assert forged is not None
            split = tree.landmark_cases
            if split is not None:  # every tree uses a case's unit, and with it the case's units and sets
                kinds["cases"] += 1
                kinds["nested"] += holds_for_every_tree(split, every, ())
                tree.landmark_cases = dict(split, cases=split["cases"][1:])  # forged: a maker left out
                assert witness_problem(problem, tree, first) is not None, (seed, goal)
                for c in split["cases"]:
                    if c.get("split"):  # forged: a maker left out one split deeper
                        deeper = dict(c["split"], cases=c["split"]["cases"][1:])
                        cases = [dict(c, split=deeper) if d is c else d for d in split["cases"]]
                        tree.landmark_cases = dict(split, cases=cases)
                        assert witness_problem(problem, tree, first) is not None, (seed, goal)
                tree.landmark_cases = split
            if tree.derivation_level is not None:
                kinds["level"] += 1
                assert min(len(t) for t in every) >= tree.derivation_level, (seed, goal)
                tree.derivation_level += 1  # forged: a level the FOON does not have
                assert witness_problem(problem, tree, first) is not None, (seed, goal)
    assert (settled > 0) == ("depth" not in objective)
    if objective in (("units",), ("success",), ("inputs",)):  # the case split settles goals, levels with units
        assert kinds["cases"] > 0 and (kinds["level"] > 0) == (objective == ("units",)), kinds
    if objective == ("success",):  # cases split one deeper too
        assert kinds["nested"] > 0, kinds


def test_check_verifies_a_bounds_proof_and_refuses_a_forged_one(demo, tmp_path):
    from helpers import run_cli

    res = run_cli("solve", "--data", "demo", "--goal", EGG, "--format", "json")
    assert res.exit_code == 0, res.output
    (answer,) = json.loads(res.stdout)
    assert answer["proven_by"] == "bounds" and sorted(answer["landmarks"]) == sorted(demo.solve(EGG).unit_ids)
    good = tmp_path / "egg.json"
    good.write_text(json.dumps([answer]))
    res = run_cli("check", good, "--data", "demo", "--format", "json")
    assert res.exit_code == 0, res.output
    (verdict,) = json.loads(res.stdout)
    assert verdict["proof"] == {"proven_by": "bounds", "verified": True, "problem": None}
    assert verdict["optimum"]["proof"]["verified"] is True
    for forged in (answer["landmarks"][:-1], [*answer["landmarks"], 0]):
        bad = tmp_path / "forged.json"
        bad.write_text(json.dumps([dict(answer, landmarks=forged)]))
        res = run_cli("check", bad, "--data", "demo", "--format", "json")
        assert res.exit_code == 1, res.output
        (verdict,) = json.loads(res.stdout)
        assert verdict["valid"] is True and verdict["proof"]["verified"] is False and verdict["proof"]["problem"]
    # a tree clingo proved, passed off as settled by its landmarks: one of its units is no landmark
    res = run_cli("solve", "--data", "demo", "--goal", SALAD, "--objective", "success,inputs", "--format", "json")
    (salad,) = json.loads(res.stdout)
    assert salad["proven_by"] == "clingo"
    claimed = dict(salad, proven_by="bounds", landmarks=sorted(demo.solve(SALAD, objective="success,inputs").unit_ids))
    bad.write_text(json.dumps([claimed]))
    res = run_cli("check", bad, "--data", "demo", "--format", "json")
    assert res.exit_code == 1 and "is no landmark" in json.loads(res.stdout)[0]["proof"]["problem"]


def test_a_tree_from_the_library_has_its_bounds_proof_checked(demo):
    tree = demo.solve(EGG)
    report = demo.check(tree)
    assert tree.proven_by == "bounds" and report.valid
    assert report.proof == {"proven_by": "bounds", "verified": True, "problem": None}
    clingo = demo.check(demo.solve(SALAD, objective="success,inputs"))
    assert clingo.proof is None


def test_a_depth_bound_that_alone_rules_out_every_tree_is_not_blamed_on_the_constraints(demo):
    """Under --max-depth, trees exist but none is shallow enough: the answer is unreachable by the
    depth bound, not infeasible by constraints that are not what rules the trees out."""
    shallow = demo.solve(EGG, max_depth=1, forbid_motions=["mix", "fry"])
    assert shallow.status == "unreachable" and "depth <= 1" in (shallow.raw.reason or "")
    deep = demo.solve(EGG, max_depth=5, forbid_motions=["beat", "fry"])
    assert deep.status == "infeasible"
    assert deep.raw.infeasible_by == ["--forbid-motion beat", "--forbid-motion fry"]


def test_a_tree_asked_of_programs_clingo_cannot_decide_in_time_is_not_allowed(demo):
    """The check of a settled tree against the user's programs honours the time limit: a program
    clingo cannot decide in time does not let the tree pass as satisfying it."""
    from foon2asp.asp.programs_check import ProgramsCheck

    pigeons = "h(1..11). p(1..10). 1 { at(H,P) : p(P) } 1 :- h(H). :- at(H1,P), at(H2,P), H1 < H2.\n"
    tree = demo.solve(EGG).unit_ids
    assert not ProgramsCheck(demo.problem, [("--rule #1", pigeons)], time_limit=0.5).allows(tree)
    assert ProgramsCheck(demo.problem, [("--rule #1", ':- use(U), motion(U,"teleport").\n')]).allows(tree)


def test_a_split_one_deeper_is_verified_and_a_forged_one_refused(shared_foon_dir):
    """On ../shared/foon some goals are settled by a split whose cases split again; check's
    validator verifies each, and refuses it with a maker of a deeper split's object left out."""
    import foon2asp

    kb = foon2asp.load(str(shared_foon_dir))
    run = GoalRunner("asp", kb.problem, AspOptions())
    nested = 0
    for goal in kb.goal_ids("all-objects")[::3]:
        if run.route(goal) != "bounds":
            continue
        tree = run(goal)
        split = tree.landmark_cases
        deep = [c for c in (split or {}).get("cases", []) if c.get("split")]
        if not deep:
            continue
        nested += 1
        assert witness_problem(kb.problem, tree) is None, goal
        c = deep[0]
        cut = dict(c, split=dict(c["split"], cases=c["split"]["cases"][1:]))
        tree.landmark_cases = dict(split, cases=[cut if d is c else d for d in split["cases"]])
        assert witness_problem(kb.problem, tree) is not None, goal
    assert nested >= 10
