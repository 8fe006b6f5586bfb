"""The plan (methods/plan.py): one table over every kind of request, each row the route, the entry
encoding, the facts and clingo's arguments the plan decides; and the plan carried out gives the
answer the plan's route promises."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from types import SimpleNamespace

import pytest

import foon2asp
from foon2asp.asp.constraints import ConstraintSpec
from foon2asp.asp.options import AspOptions
from foon2asp.foon.substitutes import Substitute
from foon2asp.methods.plan import ROUTES, _bounded, landmarks, plan, request
from foon2asp.methods.runner import GoalRunner
from foon2asp.tree.validate import bounds_proof, validate
from helpers import brute_force, real_choice, witness_problem
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
    Row("units: a real choice (chop, or slice and dice) is clingo's", SALAD, "prepared", entry="solve_closed"),
    Row("units: the landmarks alone make it, a choice in its part: clingo's", EGG, "prepared", entry="solve_closed"),
    Row("units: no shortcuts, so clingo decides", EGG, "prepared", shortcuts=False, entry="solve_closed"),
    Row("a goal the kitchen cannot make", CREAM, "fixpoint"),
    Row(
        "success: the bounds tree meets the lower bound, clingo decides",
        SALAD,
        "prepared",
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
        assert tree.status == "optimal" and tree.proven_by in ("clingo", "only-tree")


def test_a_goal_whose_landmarks_alone_make_it_is_still_clingos(demo):
    """The egg has a choice in its part, though its landmarks alone make it (its one minimal
    tree): clingo answers it, with the landmarks, and no landmark witness is claimed."""
    run = GoalRunner("asp", demo.problem, AspOptions())
    egg = demo.object_id(EGG)
    tree = run(egg)
    marks = landmarks(run.request, egg)
    assert run.parts.relevant(egg)[2] and run.route(egg) == "prepared"
    assert tree.proven_by == "clingo" and tree.landmarks is None and sorted(tree.units) == list(marks)
    assert bounds_proof(demo.problem, egg, tree.units, marks) is None
    free = GoalRunner("asp", demo.problem, AspOptions(), shortcuts=False)(egg)
    assert free.proven_by == "clingo" and sorted(free.units) == sorted(tree.units)
    assert free.asp_cost == tree.asp_cost


# --- the bounds route: against brute force, its witness re-verified, forged witnesses refused ---


@pytest.mark.parametrize("objective", [*OBJECTIVES, ("inputs", "success")], ids=",".join)
def test_landmark_proofs_against_brute_force(objective):
    """Over random small FOONs with real choice: every goal with a choice in its part is clingo's,
    those whose landmarks alone make them too (their one minimal tree, the brute-force optimum);
    the checker verifies the landmarks of such a tree and refuses forged ones. Some goal is one
    unless depth is an objective (a tree's depth is no sum of unit weights: more units may be shallower)."""
    settled = 0
    for seed in range(25):
        problem = random_foon(seed)
        run = GoalRunner("asp", problem, AspOptions(objective=objective))
        for goal in made_objects(problem):
            if run.route(goal) in ("prepared", "clingo"):  # a goal with a choice is clingo's
                tree = run(goal)
                assert tree.proven_by == "clingo", (seed, goal)
            if run.route(goal) != "prepared" or "depth" in objective:
                continue
            marks = list(landmarks(run.request, goal))
            if sorted(tree.units) != marks:
                assert real_choice(problem, goal, tree.units), (seed, goal)
                continue
            settled += 1
            assert tree.status == "optimal", (seed, goal)
            assert score(problem, goal, tree.units, objective) == optimum(problem, goal, objective), (seed, goal)
            assert bounds_proof(problem, goal, tree.units, marks) is None, (seed, goal)
            # every landmark is in every tree, by brute force: the tree is the one minimal tree
            every = brute_force(problem, goal)
            assert all(set(marks) <= set(t) for t in every), (seed, goal)
            assert min(every, key=len) == tuple(sorted(marks)) and not real_choice(problem, goal, marks)
            # forged: one landmark left out, or a unit that is no landmark claimed
            if marks:
                assert bounds_proof(problem, goal, tree.units, marks[:-1]) is not None
            spare = [u for u in range(len(problem.units)) if u not in marks and u not in tree.units]
            if spare:
                assert bounds_proof(problem, goal, [*tree.units, spare[0]], [*marks, spare[0]]) is not None
    assert (settled > 0) == ("depth" not in objective)


def test_check_verifies_a_bounds_proof_and_refuses_a_forged_one(demo, tmp_path):
    from helpers import run_cli

    res = run_cli("solve", "--data", "demo", "--goal", EGG, "--format", "json")
    assert res.exit_code == 0, res.output
    (solved,) = json.loads(res.stdout)
    assert solved["proven_by"] == "clingo" and "landmarks" not in solved
    # the same tree claimed as settled by its landmarks (they alone make the egg)
    answer = dict(solved, proven_by="bounds", landmarks=sorted(demo.solve(EGG).unit_ids))
    good = tmp_path / "egg.json"
    good.write_text(json.dumps([answer]))
    res = run_cli("check", good, "--data", "demo", "--format", "json")
    assert res.exit_code == 0, res.output
    (verdict,) = json.loads(res.stdout)
    assert verdict["proof"] == {"proven_by": "bounds", "verified": True, "problem": None}
    assert verdict["optimum"]["proven_by"] == "clingo" and "proof" not in verdict["optimum"]
    for forged in (answer["landmarks"][:-1], [*answer["landmarks"], 0]):
        bad = tmp_path / "forged.json"
        bad.write_text(json.dumps([dict(answer, landmarks=forged)]))
        res = run_cli("check", bad, "--data", "demo", "--format", "json")
        assert res.exit_code == 1, res.output
        (verdict,) = json.loads(res.stdout)
        assert verdict["valid"] is True and verdict["proof"]["verified"] is False and verdict["proof"]["problem"]
    # a tree clingo proved, passed off as settled by its landmarks: one of its units is no landmark
    res = run_cli("solve", "--data", "demo", "--goal", SALAD, "--objective", "success", "--format", "json")
    (salad,) = json.loads(res.stdout)
    assert salad["proven_by"] == "clingo"
    claimed = dict(salad, proven_by="bounds", landmarks=sorted(demo.solve(SALAD, objective="success").unit_ids))
    bad.write_text(json.dumps([claimed]))
    res = run_cli("check", bad, "--data", "demo", "--format", "json")
    assert res.exit_code == 1 and "is no landmark" in json.loads(res.stdout)[0]["proof"]["problem"]


def test_a_tree_from_the_library_claims_no_landmark_proof(demo):
    """Every tree with a choice is clingo's: the library's check finds no landmark proof to verify."""
    tree = demo.solve(EGG)
    report = demo.check(tree)
    assert tree.proven_by == "clingo" and report.valid and report.proof is None
    clingo = demo.check(demo.solve(SALAD, objective="success"))
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


# --- the checkable lower bound (its witness) clingo's search stops at ---


def witness_of(run: GoalRunner, goal: int) -> SimpleNamespace | None:
    """The witness that no tree for ``goal`` weighs less than its bounds tree, with that tree, as
    check reads it from a file (None: the checkable bounds stay below the bounds tree)."""
    bounds, prep = _bounded(run.request, goal)
    target = bounds.weight(prep.hint)
    proof = bounds.witness(goal, target)
    if not prep.hint or proof.bound < target:
        return None
    return SimpleNamespace(goal=goal, units=list(prep.hint), **proof.fields())


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


@pytest.mark.parametrize("objective", [("units",), ("success",), ("inputs",)], ids=",".join)
def test_the_witnessed_lower_bound_against_brute_force(objective):
    """Over random small FOONs with real choice: where the witnessed lower bound (landmarks,
    landmark sets, splits two deep, the derivation level) meets the bounds tree, clingo still
    answers (it decides at that cost), with the brute-force optimum; the witness holds for every
    tree by brute force, the checker verifies it and refuses forged ones."""
    met = 0
    kinds = {"cases": 0, "nested": 0, "level": 0}
    first = objective[0]
    for seed in range(25):
        problem = random_foon(seed)
        run = GoalRunner("asp", problem, AspOptions(objective=objective))
        for goal in made_objects(problem):
            if run.route(goal) != "prepared":
                continue
            claim = witness_of(run, goal)
            if claim is None:
                continue
            met += 1
            tree = run(goal)
            assert tree.status == "optimal" and tree.proven_by == "clingo", (seed, goal)
            assert score(problem, goal, claim.units, objective) == optimum(problem, goal, objective), (seed, goal)
            assert score(problem, goal, tree.units, objective) == optimum(problem, goal, objective), (seed, goal)
            assert witness_problem(problem, claim, first) is None, (seed, goal)
            every = brute_force(problem, goal)
            marks = claim.landmarks
            assert all(set(marks) <= set(t) for t in every), (seed, goal)
            assert all(not set(s).isdisjoint(t) for s in claim.landmark_sets for t in every), (seed, goal)
            if marks:  # forged: a landmark left out
                assert witness_problem(problem, claim, first, landmarks=marks[:-1]) is not None
            spare = [u for u in range(len(problem.units)) if u not in marks and u not in claim.units]
            if spare:  # forged: a unit that is no landmark claimed
                assert witness_problem(problem, claim, first, [*marks, spare[0]], [*claim.units, spare[0]]) is not None
            split = claim.landmark_cases
            if split is not None:
                kinds["cases"] += 1
                kinds["nested"] += holds_for_every_tree(split, every, ())
                claim.landmark_cases = dict(split, cases=split["cases"][1:])  # forged: a maker left out
                assert witness_problem(problem, claim, first) is not None, (seed, goal)
                for c in split["cases"]:
                    if c.get("split"):  # forged: a maker left out one split deeper
                        deeper = dict(c["split"], cases=c["split"]["cases"][1:])
                        claim.landmark_cases = dict(
                            split, cases=[dict(c, split=deeper) if d is c else d for d in split["cases"]]
                        )
                        assert witness_problem(problem, claim, first) is not None, (seed, goal)
                claim.landmark_cases = split
            if claim.derivation_level is not None:
                kinds["level"] += 1
                assert min(len(t) for t in every) >= claim.derivation_level, (seed, goal)
                claim.derivation_level += 1  # forged: a level the FOON does not have
                assert witness_problem(problem, claim, first) is not None, (seed, goal)
    assert met > 0 and kinds["cases"] > 0 and (kinds["level"] > 0) == (objective == ("units",)), kinds
    if objective == ("success",):  # cases split one deeper too
        assert kinds["nested"] > 0, kinds


def test_a_split_one_deeper_is_verified_and_a_forged_one_refused(shared_foon_dir):
    """On ../shared/foon the witnessed bound of some goals splits its cases again; check's
    validator verifies each, and refuses it with a maker of a deeper split's object left out."""
    import foon2asp

    kb = foon2asp.load(str(shared_foon_dir))
    run = GoalRunner("asp", kb.problem, AspOptions())
    nested = 0
    for goal in kb.goal_ids("all-objects")[::3]:
        if run.route(goal) != "prepared":
            continue
        claim = witness_of(run, goal)
        split = None if claim is None else claim.landmark_cases
        deep = [c for c in (split or {}).get("cases", []) if c.get("split")]
        if not deep:
            continue
        nested += 1
        assert witness_problem(kb.problem, claim) is None, goal
        c = deep[0]
        cut = dict(c, split=dict(c["split"], cases=c["split"]["cases"][1:]))
        claim.landmark_cases = dict(split, cases=[cut if d is c else d for d in split["cases"]])
        assert witness_problem(kb.problem, claim) is not None, goal
    assert nested >= 10
