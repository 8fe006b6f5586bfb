"""Writers for task trees: readable text, FOON text (official or ID-less), FOON JSON and JSON."""

from __future__ import annotations

import json

from foon2asp.foon import foonjson
from foon2asp.foon.parser import format_units, id_map
from foon2asp.foon.problem import Problem
from foon2asp.tree.gap import gap_text, number
from foon2asp.tree.tasktree import TaskTree


def tree_json(problem: Problem, tree: TaskTree) -> dict:
    """The stable JSON shape of one result (a meal has ``"goals"`` instead of ``"goal"``)."""
    goals = [problem.objects[g].to_json() for g in tree.meal]
    out = {
        **({"goals": goals} if tree.is_meal else {"goal": goals[0]}),
        "method": tree.method,
        "status": tree.status,
        "cost": tree.cost,
        "units": [problem.units[u].to_json() for u in tree.units],
        "time_s": round(tree.time_s, 6),
        "proven_by": tree.proven_by,
    }
    if tree.bound is not None:
        out["bound"] = tree.bound
        out["gap"] = tree.gap
    if tree.stats:
        out["stats"] = tree.stats
    out.update(tree.optional())
    return out


def json_list(records: list[dict]) -> str:
    """A JSON list with one record per line, each encoded without indentation (by the C encoder)."""
    return "[\n" + ",\n".join(json.dumps(r) for r in records) + "\n]" if records else "[]"


def to_json(problem: Problem, trees: list[TaskTree]) -> str:
    return json_list([tree_json(problem, t) for t in trees])


def goal_heading(problem: Problem, tree: TaskTree) -> str:
    """``Goal: OBJ``, or for a meal ``Meal of N goals:`` and one ``  + OBJ`` line per goal."""
    if tree.is_meal:
        return f"Meal of {len(tree.goals)} goals:\n" + "\n".join(f"  + {problem.objects[g]}" for g in tree.goals)
    return f"Goal: {problem.objects[tree.goal]}"


def tree_text(problem: Problem, tree: TaskTree) -> str:
    status = tree.status + (f" ({gap})" if (gap := gap_text(tree)) else "")
    if tree.proven_by:
        status += f" (proven by {tree.proven_by})"
    head = f"{goal_heading(problem, tree)}\nMethod: {tree.method}  Status: {status}"
    if tree.cost:
        head += "  (" + ", ".join(f"{k} {number(v)}" for k, v in tree.cost.items()) + ")"
    if tree.rank is not None:
        head += f"  Rank: {tree.rank}"
    if tree.human_steps:
        head += f"  Human steps: {len(tree.human_steps)}"
    if tree.reason:
        head += f"  ({tree.reason})"
    lines = [head]
    if tree.valid is False:  # judged by the independent validator (search baselines)
        lines.append(f"INVALID: {tree.problem or 'the tree is not derivable from the kitchen'}")
    lines += [f"uses {s['used']} for {s['needed']}" for s in tree.substitutions or ()]
    human = set(tree.human_steps or ())
    for step, u in enumerate(tree.units, 1):
        unit = problem.units[u]
        who = " [human]" if u in human else ""
        lines.append(f"  {step:>3}. {unit.motion}{who}")
        lines.append(f"       in:  {'; '.join(map(str, unit.inputs))}")
        lines.append(f"       out: {'; '.join(map(str, unit.outputs))}")
    if not tree.units and tree.has_tree:
        lines.append("  (already in the kitchen: no steps)")
    return "\n".join(lines) + "\n"


def tree_header(problem: Problem, tree: TaskTree) -> str:
    """``task tree for <goal> (<method>, <status>, <n> units)``: the comment line a FOON file starts with
    (``meal for <goal> + <goal> ...`` for a meal)."""
    goal = " + ".join(str(problem.objects[g]) for g in tree.meal)
    what = "meal" if tree.is_meal else "task tree"
    return f"{what} for {goal} ({tree.method}, {tree.status}, {len(tree.units)} units)"


def tree_foon(problem: Problem, tree: TaskTree, dialect: str = "official") -> str:
    """The tree as FOON text: ``official`` (ids of the FOON, as FOON_view and foon_api load it) or ``plain``."""
    ids = id_map(problem.foon) if dialect == "official" else None
    return format_units((problem.units[u] for u in tree.units), tree_header(problem, tree), ids)


def tree_foon_json(problem: Problem, tree: TaskTree) -> dict:
    """The tree in foon_api's JSON schema (``{"comment", "functional_units"}``)."""
    units = (problem.units[u] for u in tree.units)
    return foonjson.to_foon_json(units, id_map(problem.foon), tree_header(problem, tree))
