"""The prepared part (foon2asp.asp.prepared): closed sets with loop cuts (encodings/closed.lp)
against positive recursion (encodings/prepared.lp), two differently written encodings of the
same trees, on FOONs with choice and cycles; and the loop cut itself."""

from __future__ import annotations

from dataclasses import replace

import pytest

from foon2asp.asp.options import AspOptions
from foon2asp.foon.loaders import Dataset
from foon2asp.foon.problem import Problem, least_fixpoint
from foon2asp.methods.plan import session_of as Session
from foon2asp.methods.runner import GoalRunner
from foon2asp.tree.validate import validate
from synth import preset

#: a user program that changes nothing: the prepared part is then grounded with prepared.lp
NOOP = ("noop", ':- use(U), motion(U,"teleport").\n')


def shared_problem(folder) -> Problem:
    data = Dataset.load(folder)
    return Problem(data.foon, data.kitchen, data.motion, data.utensils)


def prepared_goals(run: GoalRunner, step: int) -> list[int]:
    """Every ``step``-th object some unit makes that takes the prepared route."""
    problem = run.problem
    made = sorted({o for u in range(len(problem.units)) for o in problem.products[u]})
    return [g for g in made if run.route(g) == "prepared"][::step]


def both_encodings(problem: Problem, objective: tuple[str, ...], step: int) -> tuple[int, int]:
    """Every ``step``-th goal that needs a search, solved on its prepared part by closed.lp and
    by prepared.lp: the same optimum, a valid tree; returns (goals, goals that needed a cut)."""
    run = GoalRunner("asp", problem, AspOptions(objective=objective), shortcuts=False)
    goals = prepared_goals(run, step)
    cut = 0
    for g in goals:
        prep = run.preparation(g)
        closed = Session(problem, run.options, prepared=prep).solve(g)
        # prepared.lp optimises (no hint cost to decide at): it must reach what closed.lp answered
        free = replace(prep, known=None)
        recursive = Session(problem, replace(run.options, programs=[NOOP]), prepared=free).solve(g)
        assert closed.status == recursive.status == "optimal", g
        assert closed.asp_cost == recursive.asp_cost, g
        assert validate(problem, g, list(closed.units)).valid, g
        cut += bool(closed.stats.get("loop_cuts"))
    return len(goals), cut


@pytest.mark.parametrize("objective", [("units",), ("success",), ("inputs",)], ids=",".join)
def test_closed_sets_and_positive_recursion_agree_on_the_small_preset(objective):
    goals, _ = both_encodings(preset("small").problem(), objective, 4)
    assert goals > 50


def test_closed_sets_and_positive_recursion_agree_on_the_shared_foon(shared_foon_dir):
    goals, cut = both_encodings(shared_problem(shared_foon_dir), ("units",), 5)
    assert goals > 100 and cut > 5  # the universal FOON's cycles need cuts


def test_a_search_that_meets_the_lower_bound_ends_there(shared_foon_dir):
    """A model that meets the lower bound ends the search (from outside the model callback:
    clasp's core shrinking breaks when a callback stops it); here the second model does,
    on the goal's whole relevant part."""
    problem = shared_problem(shared_foon_dir)
    run = GoalRunner("asp", problem, AspOptions(), shortcuts=False)
    goal = next(g for g, o in enumerate(problem.objects) if str(o) == "bowl, contains {garlic}")
    units, _, _ = run.parts.relevant(goal)
    prep = replace(run.preparation(goal), candidates=tuple(units), known=None)
    assert prep.bound is None and prep.meets is not None
    tree = Session(problem, run.options, prepared=prep).solve(goal)
    assert tree.status == "optimal" and prep.meets(tuple(tree.asp_cost))
    assert validate(problem, goal, list(tree.units)).valid


def test_a_goal_whose_hint_meets_the_bound_is_decided_at_the_hint(shared_foon_dir):
    """clingo decides "a tree of at most the hint's cost?" and answers the hint, the same
    optimum as an optimisation over the same part."""
    problem = shared_problem(shared_foon_dir)
    run = GoalRunner("asp", problem, AspOptions(), shortcuts=False)
    decided = 0
    for g in prepared_goals(run, 10):
        prep = run.preparation(g)
        if prep.bound is None:
            continue
        decided += 1
        tree = Session(problem, run.options, prepared=prep).solve(g)
        optimised = Session(problem, run.options, prepared=replace(prep, known=None)).solve(g)
        assert tree.status == optimised.status == "optimal", g
        assert tuple(tree.asp_cost) == prep.bound == tuple(optimised.asp_cost), g
        assert sorted(tree.units) == sorted(prep.hint), g
    assert decided > 50


def test_a_loop_cut_holds_for_every_tree_and_not_for_the_set_it_cuts(shared_foon_dir):
    """For closed sets that are no trees: the cut's objects are needed and not derived, its
    outside units make one of them from inputs outside the cut, and the set uses none of them."""
    problem = shared_problem(shared_foon_dir)
    run = GoalRunner("asp", problem, AspOptions(), shortcuts=False)
    checked = 0
    for g in prepared_goals(run, 8):
        prep = run.preparation(g)
        tree = run(g)
        assert prep.cut(problem, tree.units) is None  # the answer is a tree
        if not tree.stats.get("loop_cuts"):
            continue
        # a closed set that is no tree: the tree plus a unit that needs what only it makes
        for u in prep.candidates:
            bigger = sorted({*tree.units, u})
            cut = prep.cut(problem, bigger)
            if cut is None:
                continue
            missing, outside = cut
            derived, _ = least_fixpoint(problem.kitchen, problem.required, problem.products, bigger)
            assert missing and not any(o in derived or o in problem.kitchen for o in missing)
            assert all(set(missing) & set(problem.products[p]) for p in outside)
            assert not any(set(missing) & set(problem.required[p]) for p in outside)
            assert not set(outside) & set(bigger)
            checked += 1
            break
    assert checked > 0


def test_a_prepared_session_answers_its_goal_again():
    """Its control solves once (single-shot): a second solve grounds it afresh, same answer."""
    problem = preset("small").problem()
    run = GoalRunner("asp", problem, AspOptions(), shortcuts=False)
    goals = prepared_goals(run, 7)[:6]
    assert goals
    for g in goals:
        session = Session(problem, run.options, prepared=replace(run.preparation(g), known=None))
        first, again = session.solve(g), session.solve(g)
        assert first.status == again.status == "optimal"
        assert (again.units, again.cost) == (first.units, first.cost)


def test_after_a_loop_cut_the_rounds_go_on_one_multi_shot_control(shared_foon_dir, monkeypatch):
    """A single-shot search that needs loop cuts is grounded twice, whatever the number of cuts:
    once single-shot, then once as a multi-shot control (the plan's ``cut_args``) to which every
    further cut is added; its answers are the optima of positive recursion."""
    from foon2asp.asp import session as session_mod

    problem = shared_problem(shared_foon_dir)
    run = GoalRunner("asp", problem, AspOptions(), shortcuts=False)
    controls: list[tuple[str, ...]] = []
    grounded = session_mod.Session._grounded

    def counted(self, args=None):
        controls.append(tuple(self.grounding.args if args is None else args))
        return grounded(self, args)

    monkeypatch.setattr(session_mod.Session, "_grounded", counted)
    several = 0
    for g in prepared_goals(run, 1):
        grounding = run.plan(g).grounding
        if not grounding.single_shot:  # a decision at the bounds tree's cost: one multi-shot control
            continue
        controls.clear()
        tree = run(g)
        cuts = tree.stats.get("loop_cuts", 0)
        assert "--single-shot" in controls[0] and grounding.cut_args == controls[0][:-1], g
        if not cuts:
            assert len(controls) == 1, g
            continue
        assert len(controls) == 2 and "--single-shot" not in controls[1], (g, cuts, controls)
        if cuts < 2:
            continue
        several += 1
        prep = run.preparation(g)
        recursive = Session(problem, replace(run.options, programs=[NOOP]), prepared=replace(prep, known=None)).solve(g)
        assert tree.status == recursive.status == "optimal" and tree.asp_cost == recursive.asp_cost, g
        assert validate(problem, g, list(tree.units)).valid, g
    assert several >= 10
