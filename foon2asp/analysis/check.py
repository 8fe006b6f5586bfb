"""Checking a task tree from a file: does it exist in the FOON, is it well-founded?

Each unit of a tree file is matched to a FOON unit by :meth:`Unit.key` and judged by the
independent validator (:mod:`foon2asp.tree.validate`); :func:`check_alone` judges a tree
without a FOON.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from pathlib import Path

from foon2asp.errors import InputError, shown
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.problem import Problem, required_flags
from foon2asp.foon.treefiles import TreeFile, read_trees
from foon2asp.outcomes import AloneReport, Report
from foon2asp.tree.tasktree import Goals, meal_of, measures
from foon2asp.tree.validate import (
    Finding,
    bounds_proof,
    check_order,
    check_units,
    derivable_objects,
    describe_unit,
    judge_alone,
    validate,
)


def nearest_hint(problem: Problem, unit: Unit) -> str:
    """Which objects of ``unit`` the most similar FOON unit (same motion) lacks."""
    ins, outs = set(unit.inputs), set(unit.outputs)
    same = [i for i, other in enumerate(problem.units) if other.motion == unit.motion]
    if not same:
        return f"; no FOON unit has the motion {unit.motion!r}"

    def shared(i: int) -> int:
        return len(ins & set(problem.units[i].inputs)) + len(outs & set(problem.units[i].outputs))

    best = max(same, key=shared)  # the first of the most similar
    if not shared(best):
        return ""
    other = problem.units[best]
    extra = [f"input {o}" for o in unit.inputs if o not in other.inputs]
    extra += [f"output {o}" for o in unit.outputs if o not in other.outputs]
    lack = [f"input {o}" for o in other.inputs if o not in ins] + [
        f"output {o}" for o in other.outputs if o not in outs
    ]
    path, line = problem.foon.origins[best]
    where = f"{path}:{line}" if path else f"unit {best}"
    parts = (["has " + " | ".join(extra)] if extra else []) + (["lacks " + " | ".join(lack)] if lack else [])
    return f"; compared with the nearest FOON unit ({where}) it " + " and ".join(parts) if parts else ""


def infer_goal(problem: Problem, tree: TreeFile, goal_objects: list[FoonObject]) -> int:
    """The goal of a tree file that does not name it: the tree's only sink, else an entry of
    ``goal_objects`` it makes, else the single product of its last unit; raises InputError."""
    units = [tu.unit for tu in tree.units]
    made = list(dict.fromkeys(o for u in units for o in u.outputs if not o.is_bare()))
    needed = {
        o for u in units for o, f in zip(u.inputs, required_flags(u, problem.utensils, problem.utensil_rule)) if f
    }
    tops = [o for o in made if o not in needed]
    goal_set = set(goal_objects)
    last = [o for o in units[-1].outputs if not o.is_bare()] if units else []
    for pool in (
        tops if len(tops) == 1 else [],
        [o for o in tops if o in goal_set],
        [o for o in made if o in goal_set],
        [o for o in last if o in tops],
        last,
    ):
        pool = list(dict.fromkeys(pool))
        if len(pool) == 1 and pool[0] in problem.foon.object_ids:
            return problem.foon.object_ids[pool[0]]
    hint = ""
    if len(last) == 1 and last[0] not in problem.foon.object_ids:
        hint = f" (the last unit makes {last[0]}, which is not a FOON object)"
    elif not last and tree.units:
        tu = tree.units[-1]
        bare = " | ".join(str(o) for o in tu.unit.outputs) or "nothing"
        hint = (
            f" (its last unit, step {tu.step} at {tree.where(tu)} ({tu.unit.motion}), makes no object: it outputs"
            f" {bare}, with no states, ingredients or container)"
        )
    listing = ""
    if 1 < len(tops) <= 10:
        listing = "; it makes " + " | ".join(str(o) for o in tops) + " without using them"
    raise InputError(
        f"cannot tell which object is the goal of this tree{hint}{listing}; use --goal TEXT or --goals FILE", tree.path
    )


Derivable = Callable[[], set[FoonObject]]


def lazy_derivable(problem: Problem) -> Derivable:
    """The objects derivable from the kitchen with any units of the FOON, computed when first asked."""
    return cache(lambda: derivable_objects(problem))


def no_tree(
    problem: Problem, tree: TreeFile, goal: int, derivable: Derivable | None = None, what: str = "the goal"
) -> Report:
    """The report on a file with no units for ``goal``: finding ``unreachable`` when the FOON
    confirms no tree exists, else ``no-tree``; ``what`` names the goal in the message."""
    derivable = derivable or lazy_derivable(problem)
    if problem.objects[goal] not in derivable():
        kind = "unreachable"
        words = (
            f"unreachable: no tree to check (confirmed: {what} is not derivable from the kitchen"
            " with any units of the FOON)"
        )
    else:
        kind = "no-tree"
        words = f"no tree to check, but {what} is derivable from the kitchen: the file gives no units for it"
    return Report(tree, goal, [], False, Finding(kind, words, obj=goal), None, None, {})


def check_tree(problem: Problem, tree: TreeFile, goal: Goals, derivable: Derivable | None = None) -> Report:
    """Match the units of ``tree`` to the FOON and judge them for ``goal`` (a meal: valid when
    every goal is made; the first goal with a problem is explained)."""
    meal = meal_of(goal)
    if len(meal) > 1:
        derivable = derivable or lazy_derivable(problem)
        if not tree.units:
            # a meal is unreachable when one of its dishes is
            empty = [
                no_tree(problem, tree, g, derivable, str(problem.objects[g])) for g in meal if g not in problem.kitchen
            ]
            if empty:
                first = next((r for r in empty if r.finding and r.finding.kind == "unreachable"), empty[0])
                first.goals = meal
                return first
        reports = [check_tree(problem, tree, g, derivable) for g in meal]
        first = next((r for r in reports if not r.valid), reports[0])
        first.goals = meal
        first.valid = all(r.valid for r in reports)
        first.order_problem = next((r.order_problem for r in reports if r.order_problem), None)
        known = list(dict.fromkeys(u for u in first.ids if u is not None))
        first.cost = measures(problem, meal, known)
        return first
    goal = meal[0]
    if not tree.units and goal not in problem.kitchen:
        return no_tree(problem, tree, goal, derivable)
    ids = [problem.foon.unit_id(tu.unit) for tu in tree.units]
    unknown = [tu for tu, u in zip(tree.units, ids) if u is None]
    known = list(dict.fromkeys(u for u in ids if u is not None))
    if unknown:
        tu = unknown[0]
        more = f" ({len(unknown)} units are unknown)" if len(unknown) > 1 else ""
        found: Finding | None = Finding(
            "unknown-unit",
            f"unknown unit: step {tu.step} at {tree.where(tu)} ({tu.unit.motion}) is not in the FOON"
            f"{nearest_hint(problem, tu.unit)}{more}",
        )
        validation, order_problem = validate(problem, goal, known), None
    else:
        validation, found = check_units(problem, goal, known, lambda u: describe_unit(problem, u, tree, ids))
        order_problem = check_order(problem, goal, known)
    valid = validation.valid and not unknown
    found_report = Report(tree, goal, ids, valid, found, validation, order_problem, measures(problem, goal, known))
    if tree.proven_by == "bounds":
        objective = (tree.method or "").removeprefix("asp-").split(",")[0]
        objective = objective if objective in ("success", "inputs") else "units"
        why = bounds_proof(
            problem,
            goal,
            known,
            tree.landmarks or [],
            tree.landmark_sets,
            objective,
            tree.landmark_cases,
            tree.derivation_level,
        )
        if tree.landmarks is None:
            why = "a bounds proof without its landmarks"
        found_report.proof = {"proven_by": "bounds", "verified": why is None, "problem": why}
    return found_report


def tree_goal(
    data,
    problem: Problem,
    tree: TreeFile,
    goal_label: str | tuple[str, ...] | None,
    among: list[int] | None = None,
) -> tuple[Goals, str]:
    """The goal of ``tree`` (several labels: a meal) and where it came from: ``goal_label``,
    else the one of ``among`` the tree makes, else the one the file names, else :func:`infer_goal`."""
    if isinstance(goal_label, str):
        goal_label = (goal_label,)
    if goal_label:
        meal = meal_of(goals_mod.resolve_goal(data, problem, label) for label in goal_label)
        return (meal if len(meal) > 1 else meal[0]), "--goal"
    if among is not None:
        chosen = _among(problem, tree, among)
        if chosen is not None:
            return chosen, "--goals"
    if tree.goal is not None:
        return goals_mod.goal_id(problem, tree.goal, tree.path, tree.line), "named in the file"
    return infer_goal(problem, tree, [obj for obj, _ in data.goals]), "inferred from the units"


def _among(problem: Problem, tree: TreeFile, among: list[int]) -> int | None:
    """The one goal of ``among`` the tree names or makes (preferring products no unit of it needs)."""
    if tree.goal is not None and problem.foon.object_ids.get(tree.goal) in among:
        return problem.foon.object_ids[tree.goal]
    oid = problem.foon.object_ids
    made = [oid[o] for tu in tree.units for o in tu.unit.outputs if o in oid]
    needed = {oid[o] for tu in tree.units for o in tu.unit.inputs if o in oid}
    wanted = set(among)
    for pool in ([o for o in made if o in wanted and o not in needed], [o for o in made if o in wanted]):
        pool = list(dict.fromkeys(pool))
        if len(pool) == 1:
            return pool[0]
    return None


def check_trees(
    data,
    problem: Problem,
    trees: list[TreeFile],
    goal_label: str | tuple[str, ...] | None = None,
    among: list[int] | None = None,
) -> list[Report]:
    """Check each of ``trees`` for its goal (:func:`tree_goal`)."""
    derivable = lazy_derivable(problem)
    reports = []
    for tree in trees:
        goal, source = tree_goal(data, problem, tree, goal_label, among)
        report = check_tree(problem, tree, goal, derivable)
        report.goal_source = source
        reports.append(report)
    return reports


def alone_goal(tree: TreeFile, text: str) -> FoonObject:
    """The object ``text`` names in ``tree``: an object's full text, else the one object of the tree
    made with that label."""
    units = [tu.unit for tu in tree.units]
    parsed = goals_mod.parse_object_text(text.strip())
    if parsed is not None:
        return parsed
    label = " ".join(text.split()).lower()
    made = list(dict.fromkeys(o for u in units for o in u.outputs if not o.is_bare() and o.label == label))
    if len(made) == 1:
        return made[0]
    if made:
        listing = " | ".join(str(o) for o in made[:10])
        raise InputError(
            f"label {shown(text)} names {len(made)} objects of the tree; give one with its text: {listing}"
        )
    if any(o.label == label for u in units for o in u.inputs + u.outputs):
        return FoonObject.make(label)
    raise InputError(f"no object of the tree is labelled {shown(text)}", tree.path)


def check_alone(
    path: str | Path,
    goal_texts: tuple[str, ...] = (),
    kitchen: list[FoonObject] | None = None,
    utensils: frozenset[str] = frozenset(),
    utensil_rule: str = "starter",
    strict: bool = False,
    kitchen_source: str = "its leaves",
) -> list[AloneReport]:
    """Judge every tree of the file ``path`` on its own: the kitchen is its leaves (or ``kitchen``),
    the goal ``goal_texts`` (several: a meal), else the file's, else the products of its last unit."""
    reports = []
    for tree in read_trees(path, strict=strict):
        units = [tu.unit for tu in tree.units]
        goal: FoonObject | tuple[FoonObject, ...] | None = None
        source = "the products of its last unit"
        if goal_texts:
            goal = tuple(dict.fromkeys(alone_goal(tree, t) for t in goal_texts))
            source = "--goal"
        elif tree.goal is not None:
            goal, source = (tree.goal,), "named in the file"
        verdict = judge_alone(units, goal, kitchen, utensils, utensil_rule, [tu.step for tu in tree.units])
        reports.append(AloneReport(tree, verdict, source, kitchen_source))
    return reports
