"""From models to task trees: a model is read straight into the :class:`TaskTree` the library
returns, and the library's :class:`foon2asp.api.Tree` is the one view over it."""

from __future__ import annotations

import pytest

import foon2asp
from foon2asp.asp import control as control_mod
from foon2asp.asp.answers import finish, solve_shot
from foon2asp.asp.control import Control
from foon2asp.tree.tasktree import NO_GOAL, TaskTree

#: choose units 1..3; unit 2 is needed; unit 3 is a person's step; fewest units first
PROGRAM = """
{ use(1..3) }.
:- not use(2).
human(U) :- use(U), U = 3.
#minimize { 1,U : use(U) }.
"""

#: two optimal trees, {1} and {2}
TWO = """
1 { use(1); use(2) } 1.
#minimize { 1,U : use(U) }.
#project use/1.
"""


def grounded(text: str) -> Control:
    control = Control()
    control.add("program", text)
    control.ground()
    return control


def test_no_record_between_the_model_and_the_tree():
    assert not hasattr(control_mod, "ModelRead")
    assert not hasattr(control_mod, "read_model")


def test_a_shot_holds_the_trees_its_models_were_read_into():
    shot = solve_shot(grounded(PROGRAM))
    assert shot.finished and not shot.unsat
    (tree,) = shot.answers
    assert type(tree) is TaskTree and tree is shot.last
    assert tree.units == [2] and tree.asp_cost == [1] and tree.status == "optimal" and tree.proven
    assert tree.goal == NO_GOAL and tree.method == "" and tree.human_steps is None and tree.cost == {}


def test_all_optimal_trees_are_trees_in_id_order():
    shot = solve_shot(grounded(TWO), "optN", 5)
    assert [type(t) for t in shot.answers] == [TaskTree, TaskTree]
    assert [(t.units, t.asp_cost, t.status) for t in shot.answers] == [([1], [1], "optimal"), ([2], [1], "optimal")]


def test_a_first_model_is_not_proven():
    shot = solve_shot(grounded(PROGRAM), "first")
    (tree,) = shot.answers
    assert 2 in tree.units and tree.status == "feasible" and not tree.proven


def test_finishing_fills_the_same_record():
    kb = foon2asp.load("demo")
    answer = kb.solve("scrambled egg")
    problem, goal, done = kb.problem, answer.goal_id, answer.unit_ids
    assert done != sorted(done)  # executable order is not id order here
    # the units as a model gives them: by id, one a person does
    read = TaskTree(NO_GOAL, "", "optimal", sorted(done), asp_cost=[len(done)], human_steps=[max(done)])
    tree = finish(problem, "asp", goal, "optimal", read, 0.5, {"models": 1}, human_steps=True)
    assert tree is read
    assert (tree.goal, tree.goals, tree.method, tree.status, tree.time_s) == (goal, (), "asp", "optimal", 0.5)
    assert tree.units == done and tree.cost["units"] == len(done) and tree.asp_cost == [len(done)]
    assert tree.human_steps == [max(done)] and tree.human_step_numbers == [done.index(max(done)) + 1]
    plain = finish(
        problem, "asp", goal, "optimal", TaskTree(NO_GOAL, "", "optimal", sorted(done), human_steps=[1]), 0, {}
    )
    assert plain.human_steps is None and plain.human_step_numbers is None


@pytest.mark.parametrize(
    "settings",
    [
        {},
        {"objective": "success"},
        {"models": 2},
        {"all_optimal": True},
        {"objective": "depth"},
        {"objective": "units,depth"},
        {"objective": "units,success", "human_steps": 1},
        {"forbid_motions": ["pour"]},
    ],
)
def test_the_library_tree_views_the_record_the_solver_read(monkeypatch, settings):
    made: list[TaskTree] = []
    read = TaskTree.from_model

    def from_model(cls, model, proven=None):
        tree = read(model, proven)
        made.append(tree)
        return tree

    monkeypatch.setattr(TaskTree, "from_model", classmethod(from_model))
    kb = foon2asp.load("demo")
    # every goal with a choice is clingo's; each asked alone, so none is decided with others (whose
    # answer is its bounds tree, read from no model of its own: tests/test_decisions.py)
    trees = [kb.solve(g, shortcuts=False, **settings) for g in kb.goal_ids("all")]
    solved = [t for t in trees if t.raw.stats.get("plan", {}).get("route") in ("clingo", "prepared") and t.has_tree]
    assert not any(t.raw.stats["plan"].get("decided_with") for t in solved)
    assert solved, "no goal was answered by clingo"
    for tree in solved:
        for one in tree.with_alternatives:
            assert any(one.raw is t for t in made), f"{one.goal.label}: not the tree a model was read into"
            assert type(one.raw) is TaskTree and one.raw.goal == one.goal_id and one.raw.method.startswith("asp")
