"""Comparing methods goal by goal: tree size, validity, success product, depth."""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from foon2asp.asp.options import AspOptions
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import Substitute, judged_on
from foon2asp.methods.runner import solve_goals
from foon2asp.outcomes import MealRow, Row
from foon2asp.tree.tasktree import TaskTree
from foon2asp.tree.validate import check_units, validate

DEFAULT_METHODS = ("ids", "gbfs-h1", "gbfs-h2", "asp")
Methods = tuple[str, ...] | list[str]


def judge(problem: Problem, tree: TaskTree, substitutes: Iterable[Substitute] = ()) -> TaskTree:
    """Mark ``tree`` valid or invalid (its ``valid`` and ``problem``); with ``substitutes``, what
    they may stand in for counts as had."""
    if not tree.has_tree:
        tree.valid = False
        return tree
    problem = judged_on(problem, substitutes, tree.meal)
    validation, finding = check_units(problem, tree.goal, tree.units)
    tree.valid = validation.valid
    if finding is not None:
        tree.problem = finding.message
    return tree


def compare_iter(
    problem: Problem, goals: list[int], method_names: Methods = DEFAULT_METHODS, options: AspOptions | None = None
) -> Iterator[Row]:
    """Run each method on each goal, judging every tree by the validator: each row as soon as
    every method has its goal's tree."""
    options = options or AspOptions()
    answers = {name: solve_goals(problem, goals, name, options) for name in dict.fromkeys(method_names)}
    for g in goals:
        trees = {name: judge(problem, next(trees_of), options.substitutes) for name, trees_of in answers.items()}
        for name, tree in trees.items():
            tree.method = name
        yield Row(g, trees)


def compare_meal(problem: Problem, goals: list[int], method: str = "asp", options: AspOptions | None = None) -> MealRow:
    """The meal's optimum (one tree for all ``goals``) and each goal's own optimum, all judged."""
    meal = tuple(dict.fromkeys(goals))
    options = options or AspOptions()
    trees = solve_goals(problem, [meal, *meal], method, options)
    tree = next(trees)
    seen = judged_on(problem, options.substitutes, meal) if tree.has_tree else problem
    tree.valid = tree.has_tree and all(validate(seen, g, tree.units).valid for g in meal)
    singles = [judge(problem, single, options.substitutes) for single in trees]
    return MealRow(meal, tree, singles)
