"""Hard FOONs with real choice (bench/synth.py presets), the default solver settings and
batch's automatic grounding.

The optima are checked against references written without the solver: a depth-first search over
trees with one producer per needed object (pruned by the cost so far and a packing bound),
itself checked against tests/helpers.brute_force on small parts, and for depth the goal's level
in the least fixpoint of the kitchen (the earliest round anything can make it).
"""

from __future__ import annotations

import math

import pytest
from click.testing import CliRunner

import foon2asp
from foon2asp.api import KnowledgeBase
from foon2asp.asp import control as control_mod
from foon2asp.asp import options as settings
from foon2asp.asp.facts import neglog_weight
from foon2asp.asp.options import AspOptions
from foon2asp.asp.session import Session
from foon2asp.cli.main import main
from foon2asp.foon.problem import Problem
from foon2asp.methods import parts as grounding
from foon2asp.tree.upper import cheapest_tree
from foon2asp.tree.validate import validate
from helpers import best, goal_part
from synth import PRESETS, preset, shape

WEIGHT = {"units": lambda problem, u: 1, "success": lambda problem, u: neglog_weight(problem.rates[u])}


_REFERENCE: dict[tuple[int, int, str], float | None] = {}


def reference(problem: Problem, goal: int, objective: str) -> float | None:
    """The least total weight of a well-founded tree for ``goal`` (None: no tree), by search."""
    key = (id(problem), goal, objective)
    if key not in _REFERENCE:
        _REFERENCE[key] = _search(problem, goal, objective)
    return _REFERENCE[key]


def _search(problem: Problem, goal: int, objective: str) -> float | None:
    w = WEIGHT[objective]
    kitchen = problem.kitchen
    maxprod = max(len(p) for p in problem.products)
    cheapest = {o: min(w(problem, u) for u in us) for o, us in problem.producers.items()}
    start = cheapest_tree(problem, [goal], objective=objective)
    if start is None:
        return None
    found = [sum(w(problem, u) for u in start)]

    def search(made: frozenset, units: frozenset, cost: float, todo: set) -> None:
        todo = {o for o in todo if o not in made}
        if not todo:
            if validate(problem, goal, sorted(units)).valid:
                found[0] = min(found[0], cost)
            return
        # each open object needs a unit; one unit makes at most maxprod of them
        if cost + sum(cheapest.get(o, math.inf) for o in todo) / maxprod >= found[0]:
            return
        o = min(todo, key=lambda o: (len(problem.producers.get(o, ())), o))
        for u in problem.producers.get(o, ()):
            if u not in units:
                needs = {i for i in problem.required[u] if i not in kitchen}
                search(made | set(problem.products[u]), units | {u}, cost + w(problem, u), todo | needs)

    search(frozenset(), frozenset(), 0, {goal})
    return found[0]


def min_depth(problem: Problem, goal: int) -> int | None:
    return problem.derivation_levels()[0].get(goal)


@pytest.fixture(scope="module")
def tiny() -> KnowledgeBase:
    syn = preset("tiny")
    return KnowledgeBase(syn.dataset(), syn.problem())


@pytest.fixture(scope="module")
def small() -> KnowledgeBase:
    syn = preset("small")
    return KnowledgeBase(syn.dataset(), syn.problem())


# ---- the generator ---------------------------------------------------------------


def test_presets_are_seeded_and_have_real_choice():
    a, b = preset("small"), preset("small")
    assert [str(u) for u in a.foon.units] == [str(u) for u in b.foon.units]
    assert a.goals == b.goals
    assert set(PRESETS) >= {"tiny", "small", "hard-4k", "hard-10k"}
    s = shape(a.problem())
    assert s["units"] == 404 and s["objects"] == 466
    assert s["producers_per_object"] > 1.4 and s["cycles"] >= 2
    hard = preset("hard-4k")
    h = shape(hard.problem())
    assert 4000 <= h["units"] <= 4010 and 5000 <= h["objects"] <= 5200 and h["cycles"] >= 2
    assert len(hard.goals) == 21  # 20 goals with choice and one that nothing can make
    with pytest.raises(foon2asp.InputError):
        preset("nope")


def test_a_written_preset_loads_with_the_same_optima(tmp_path, tiny):
    preset("tiny").write(tmp_path / "tiny")
    kb = foon2asp.load(tmp_path / "tiny")
    assert (len(kb.problem.units), len(kb.problem.objects), len(kb.goals)) == (62, 89, 7)
    here = [t.cost.get("units") for t in kb.solve("all")]
    there = [t.cost.get("units") for t in tiny.solve("all")]
    assert here == there and here[-1] is None and all(here[:-1])


def test_the_reference_agrees_with_brute_force_on_small_parts(tiny):
    p = tiny.problem
    checked = 0
    for g in tiny.goal_ids("all-objects"):
        found = goal_part(p, g)
        if found is None:
            continue
        sub, sg = found
        for objective, key in (("units", lambda m: m["units"]), ("depth", lambda m: m["depth"])):
            want, _ = best(sub, sg, key)
            got = reference(sub, sg, objective) if objective != "depth" else min_depth(sub, sg)
            assert got == want, (g, objective)
        checked += 1
    assert checked >= 10


# ---- default answers are proven optima ------------------------------------------------


@pytest.mark.parametrize("name", ["tiny", "small"])
def test_default_answers_are_optimal_and_match_the_reference(name, tiny, small):
    kb = tiny if name == "tiny" else small
    p = kb.problem
    goals = kb.goal_ids("all")
    for objective in ("units", "success", "depth"):
        trees = kb.solve(goals, objective=objective, time_limit=60)
        for g, t in zip(goals, trees):
            if objective == "depth":
                want = min_depth(p, g)
            else:
                want = reference(p, g, objective)
            if want is None:
                assert t.status == "unreachable", (name, objective, g)
                continue
            assert t.status == "optimal", (name, objective, g, t.status)
            assert validate(p, g, t.unit_ids).valid
            if objective == "depth":
                assert t.cost["depth"] == want, (name, g)
            else:
                assert sum(WEIGHT[objective](p, u) for u in t.unit_ids) == want, (name, objective, g)


def test_cheapest_tree_is_valid_and_an_upper_bound(small):
    p = small.problem
    for g in small.goal_ids("all"):
        units = cheapest_tree(p, [g])
        want = reference(p, g, "units")
        if want is None:
            assert units is None
            continue
        assert units is not None and validate(p, g, units).valid
        assert len(units) >= want


def test_a_time_out_still_reports_a_valid_tree():
    """usc finds no tree before its proof; on a hard goal cut short the answer is a
    cheapest-first tree marked feasible (or the optimum, should the machine be fast)."""
    syn = preset("hard-4k")
    p = syn.problem()
    g = p.foon.object_ids[syn.goals[8]]  # optimum about 50 units in a part of ~2,900
    tree = Session(p, AspOptions(time_limit=1, units=p.units_for([g]))).solve(g)
    assert tree.status in ("feasible", "optimal")
    assert validate(p, g, tree.units).valid
    if tree.status == "feasible" and "fallback" in tree.extra:
        assert tree.extra["fallback"] == "cheapest-first" and "note" in tree.extra
        assert len(tree.units) < 200


def test_no_fallback_under_user_constraints():
    """A user program may rule out the cheapest-first tree: then no tree is made up (a tree
    clingo found is its own, so it satisfies the program)."""
    syn = preset("hard-4k")
    p = syn.problem()
    g = p.foon.object_ids[syn.goals[8]]
    user = ("user", "% a user program (it could forbid anything)\n")
    tree = Session(p, AspOptions(programs=[user], time_limit=1, units=p.units_for([g]))).solve(g)
    assert tree.status in ("unknown", "optimal", "feasible")
    assert "fallback" not in tree.extra


# ---- the defaults live in one place and every command uses them -------------------------


def test_default_settings():
    assert settings.DEFAULT_OPT_STRATEGY == "usc,oll,succinct,stratify"
    assert "--opt-strategy=usc,oll,succinct,stratify" in AspOptions().args()
    two = AspOptions(threads=2).args()
    assert "--parallel-mode=2" in two and not any(a.startswith("--opt-strategy") for a in two)
    config = next(a for a in two if a.startswith("--configuration="))
    with open(config.split("=", 1)[1], encoding="utf-8") as fh:
        assert fh.read() == settings.PORTFOLIO
    assert "[bbsign]: --opt-strategy=bb --opt-heuristic=sign,model" in settings.PORTFOLIO
    assert "[usc]: --opt-strategy=usc,oll,succinct,stratify" in settings.PORTFOLIO
    mine = AspOptions(opt_strategy="bb", threads=2).args()
    assert "--opt-strategy=bb" in mine and not any(a.startswith("--configuration") for a in mine)
    kb = foon2asp.load("demo")
    assert kb.options().args() == AspOptions().args()
    assert kb.options(threads=2, opt_strategy="usc,k").args()[-2:] == ["--opt-strategy=usc,k", "--parallel-mode=2"]


@pytest.fixture()
def recorded(monkeypatch):
    """The arguments of every optimising clingo control made meanwhile."""
    calls: list[list[str]] = []
    real = control_mod.Control.__init__

    def spy(self, args=(), *rest, **kw):
        if "--opt-mode=opt" in args:
            calls.append(list(args))
        real(self, args, *rest, **kw)

    monkeypatch.setattr(control_mod.Control, "__init__", spy)
    return calls


def _strategy(args: list[str]) -> list[str]:
    return [a for a in args if a.startswith(("--opt-strategy", "--configuration", "--parallel-mode"))]


@pytest.mark.parametrize(
    "command",
    [
        ["solve", "--goals", "all"],
        ["compare", "--goals", "all"],
        ["missing", "--goals", "all"],
        ["batch", "--goals", "all", "--output", "{tmp}/r.jsonl", "--no-shortcuts"],
        ["check", "{tmp}/tree.txt"],
    ],
)
def test_every_command_solves_with_the_default(command, tmp_path, recorded, monkeypatch):
    # the small preset: real choice, so the bounds do not answer every goal without the solver
    data = preset("small").write(tmp_path / "small")
    runner = CliRunner()
    if command[0] == "check":
        res = runner.invoke(main, ["solve", "--data", str(data), "--goals", "all", "--format", "foon"])
        (tmp_path / "tree.txt").write_text(res.output)
        recorded.clear()
    args = [a.replace("{tmp}", str(tmp_path)) for a in command] + ["--data", str(data)]
    res = runner.invoke(main, args)
    assert res.exit_code in (0, 1), res.output
    assert recorded, "no optimising solver call"
    for call in recorded:
        assert _strategy(call) == [f"--opt-strategy={settings.DEFAULT_OPT_STRATEGY}", "--configuration=trendy"], call
        assert "--opt-usc-shrink=bin" in call
    if command[0] != "check":  # check's optimum takes no solver options
        recorded.clear()
        again = [a.replace("r.jsonl", "r2.jsonl") for a in args]
        res = runner.invoke(main, [*again, "--threads", "2"])
        assert res.exit_code in (0, 1), res.output
        assert recorded
        for call in recorded:
            assert _strategy(call)[0] == "--parallel-mode=2" and _strategy(call)[1].startswith("--configuration=")


# ---- batch picks its grounding ----------------------------------------------------------


def test_auto_grounding_is_per_goal_on_the_shared_foon(shared_foon_dir):
    kb = foon2asp.load(shared_foon_dir)
    mode, reason = grounding.choose_grounding(kb.problem, kb.goal_ids("all-objects"))
    assert mode == "per-goal" and "under 10 %" in reason


def test_auto_grounding_is_whole_on_a_hard_preset(monkeypatch):
    syn = preset("hard-4k")
    p = syn.problem()
    goals = [p.foon.object_ids[g] for g in syn.goals]
    mode, reason = grounding.choose_grounding(p, goals)
    assert mode == "whole" and "10 % or more" in reason
    monkeypatch.setattr(grounding, "AUTO_MAX_WHOLE", 1000)
    assert grounding.choose_grounding(p, goals)[0] == "per-goal"


def test_batch_reports_the_grounding_it_chose(tmp_path, tiny):
    report = tiny.batch("all", None)
    assert report.grounding == "whole" and "viable units" in report.grounding_reason
    assert [r["status"] for r in report.records] == ["optimal"] * 6 + ["unreachable"]
    res = CliRunner().invoke(main, ["batch", "--data", "demo", "--goals", "all", "-o", str(tmp_path / "r.jsonl")])
    assert "grounding: " in res.output and "(auto: " in res.output
    fixed = tiny.batch("all", None, grounding="per-goal")
    assert fixed.grounding == "per-goal" and fixed.grounding_reason == ""
    assert [r["units"] for r in fixed.records] == [r["units"] for r in report.records]
