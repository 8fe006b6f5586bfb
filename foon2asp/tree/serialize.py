"""Writers for task trees: readable text, FOON text and JSON."""

from __future__ import annotations

import json

from foon2asp.foon.parser import format_units
from foon2asp.foon.problem import Problem
from foon2asp.tree.tasktree import TaskTree


def tree_json(problem: Problem, tree: TaskTree) -> dict:
    """The stable JSON shape of one result."""
    out = {
        "goal": problem.objects[tree.goal].to_json(),
        "method": tree.method,
        "status": tree.status,
        "cost": tree.cost,
        "units": [problem.units[u].to_json() for u in tree.units],
        "time_s": round(tree.time_s, 6),
    }
    if tree.stats:
        out["stats"] = tree.stats
    for key, value in tree.extra.items():
        if key not in out and not key.startswith("_"):
            out[key] = value
    return out


def json_list(records: list[dict], indent: int | None = 2) -> str:
    """A JSON list with one record per line (``indent=None``: all on one line).

    Each record is encoded by ``json.dumps`` without indentation, which uses
    the C encoder; ``indent`` would switch the whole list to the much slower
    pure-Python encoder.
    """
    if indent is None:
        return json.dumps(records)
    if not records:
        return "[]"
    return "[\n" + ",\n".join(json.dumps(r) for r in records) + "\n]"


def to_json(problem: Problem, trees: list[TaskTree], indent: int | None = 2) -> str:
    return json_list([tree_json(problem, t) for t in trees], indent)


def _cost_text(cost: dict) -> str:
    return ", ".join(f"{k} {v}" for k, v in cost.items())


def tree_text(problem: Problem, tree: TaskTree) -> str:
    goal = problem.objects[tree.goal]
    head = f"Goal: {goal}\nMethod: {tree.method}  Status: {tree.status}"
    if tree.cost:
        head += f"  ({_cost_text(tree.cost)})"
    if "rank" in tree.extra:
        head += f"  Rank: {tree.extra['rank']}"
    if tree.extra.get("human_steps"):
        head += f"  Human steps: {len(tree.extra['human_steps'])}"
    if tree.extra.get("reason"):
        head += f"  ({tree.extra['reason']})"
    lines = [head]
    human = set(tree.extra.get("human_steps", []))
    for step, u in enumerate(tree.units, 1):
        unit = problem.units[u]
        who = " [human]" if u in human else ""
        lines.append(f"  {step:>3}. {unit.motion}{who}")
        lines.append(f"       in:  {'; '.join(map(str, unit.inputs))}")
        lines.append(f"       out: {'; '.join(map(str, unit.outputs))}")
    if not tree.units and tree.status in ("optimal", "ranked", "feasible", "found"):
        lines.append("  (already in the kitchen: no steps)")
    return "\n".join(lines) + "\n"


def tree_foon(problem: Problem, tree: TaskTree) -> str:
    goal = problem.objects[tree.goal]
    header = f"task tree for {goal} ({tree.method}, {tree.status}, {len(tree.units)} units)"
    return format_units((problem.units[u] for u in tree.units), header)
