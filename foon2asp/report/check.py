"""The report of ``check``: text and JSON."""

from __future__ import annotations

import json

from foon2asp.foon.problem import Problem
from foon2asp.foon.treefiles import TreeFile
from foon2asp.report.registry import register
from foon2asp.tree.diagnose import Finding, describe_unit
from foon2asp.tree.results import Report
from foon2asp.tree.serialize import number


def _cost_text(cost: dict) -> str:
    depth = cost.get("depth")
    return (
        f"{cost.get('units')} units, success {number(cost.get('success'))}, "
        f"depth {depth if depth is not None else '- (goal not made)'}"
    )


def cycle_lines(
    problem: Problem, finding: Finding, tree: TreeFile | None = None, ids: list[int | None] | None = None
) -> list[str]:
    """The cycle of ``finding`` as indented lines, one object or unit per line."""
    lines = []
    for o, u in finding.cycle:
        lines.append(f"    {problem.objects[o]}")
        lines.append(f"      is made in this tree by {describe_unit(problem, u, tree, ids)}, which needs")
    lines.append(f"    {problem.objects[finding.cycle[0][0]]}   (back to the start)")
    return lines


def report_text(problem: Problem, report: Report) -> str:
    """The human-readable report of one tree."""
    tree, ids = report.tree, report.ids
    head = f"Tree: {tree.path}" + (f" (line {tree.line})" if tree.line and tree.line > 1 else "")
    if tree.method:
        head += f"  method {tree.method}"
    source = f"  ({report.goal_source})" if report.goal_source else ""
    if report.goals:
        lines = [head, f"Meal of {len(report.goals)} goals{source}:"]
        lines += [f"  + {problem.objects[g]}" for g in report.goals]
    else:
        lines = [head, f"Goal: {problem.objects[report.goal]}{source}"]
    n_known = sum(u is not None for u in ids)
    lines.append(f"Units: {len(ids)} read, {n_known} found in the FOON, {len(ids) - n_known} unknown")
    lines.append(f"Verdict: {'VALID' if report.valid else 'INVALID'}")
    if report.finding:
        f = report.finding
        if f.kind == "cycle":
            lines.append("Problem: circular support -- these units need each other and nothing starts the cycle:")
            lines += cycle_lines(problem, f, tree, ids)
        else:
            lines.append(f"Problem: {f.message}")
    v = report.validation
    if v is not None:
        if report.valid:
            if report.order_problem is None:
                lines.append("Order: the steps as written are executable")
            else:
                lines.append(f"Order: not executable as written ({report.order_problem})")
                lines.append("Executable order (steps): " + " ".join(_steps(v.order, ids)))
        else:
            lines.append(f"Units that can fire (in order, steps): {' '.join(_steps(v.order, ids)) or '-'}")
            if v.stuck:
                lines.append(f"Units that never fire (steps): {' '.join(_steps(v.stuck, ids))}")
    lines.append(f"Size: {_cost_text(report.cost)}")
    opt = report.optimum
    if opt is not None:
        if opt.has_tree:
            diff = report.cost["units"] - opt.cost["units"]
            rel = "the optimum" if report.valid and diff == 0 else f"{diff:+d} units vs optimum" if report.valid else ""
            lines.append(
                f"ASP optimum: {_cost_text(opt.cost)} ({opt.status})" + (f"; this tree is {rel}" if rel else "")
            )
        else:
            why = ": no well-founded tree exists for this goal" if opt.status == "unreachable" else ""
            lines.append(f"ASP optimum: none ({opt.status}{why})")
    return "\n".join(lines) + "\n"


def _steps(units: list[int], ids: list[int | None]) -> list[str]:
    return [str(ids.index(u) + 1) for u in units]


def report_json(problem: Problem, report: Report) -> dict:
    """The report as plain data (``check --format json``)."""
    v = report.validation
    out = {
        "tree": report.tree.path,
        **(
            {"goals": [problem.objects[g].to_json() for g in report.goals]}
            if report.goals
            else {"goal": problem.objects[report.goal].to_json()}
        ),
        "goal_source": report.goal_source,
        "method": report.tree.method,
        "valid": report.valid,
        "problem": report.finding.kind if report.finding else None,
        "message": report.finding.message if report.finding else None,
        "cycle": [
            {"object": problem.objects[o].to_json(), "unit": u, "motion": problem.units[u].motion}
            for o, u in (report.finding.cycle if report.finding else [])
        ],
        "unknown_steps": [tu.step for tu, u in zip(report.tree.units, report.ids) if u is None],
        "order_as_written_ok": report.order_problem is None if v is not None and report.valid else None,
        "executable_order_steps": [int(s) for s in _steps(v.order, report.ids)] if v is not None else [],
        "cost": report.cost,
    }
    if report.optimum is not None:
        out["optimum"] = {"status": report.optimum.status, "cost": report.optimum.cost}
    return out


@register("check", "text", "txt", "readable report per tree")
def check_text(problem: Problem, reports: list[Report]) -> str:
    return "\n".join(report_text(problem, r) for r in reports)


@register("check", "json", "json", "a list of reports")
def check_json(problem: Problem, reports: list[Report]) -> str:
    return json.dumps([report_json(problem, r) for r in reports], indent=2) + "\n"
