"""The report of ``check``: text and JSON, for a tree checked against a FOON (:class:`Report`)
or judged on its own (:class:`AloneReport`: kitchen = its leaves, no FOON)."""

from __future__ import annotations

import json

from foon2asp.foon.problem import Problem
from foon2asp.foon.treefiles import TreeFile
from foon2asp.outcomes import AloneReport, Report
from foon2asp.report.formats import register
from foon2asp.tree.serialize import number
from foon2asp.tree.validate import describe_unit


def unreachable(report: Report | AloneReport) -> bool:
    """The file gives no tree for the goal and the FOON confirms none exists (neither valid nor invalid)."""
    return isinstance(report, Report) and report.finding is not None and report.finding.kind == "unreachable"


def answered(report: Report | AloneReport) -> bool:
    """A valid tree, or a confirmed unreachable goal: what ``check`` exits 0 for."""
    return report.valid or unreachable(report)


def _cost_text(cost: dict) -> str:
    depth = cost.get("depth")
    text = (
        f"{cost.get('units')} units, success {number(cost.get('success'))}, "
        f"depth {depth if depth is not None else '- (goal not made)'}"
    )
    return text + (f", cost {number(cost['cost'])}" if "cost" in cost else "")


def _cycle_lines(cycle: list[tuple[object, str]]) -> list[str]:
    """A cycle of (object, what makes it) as the lines of a ``Problem: circular support``."""
    lines = ["Problem: circular support -- these units need each other and nothing starts the cycle:"]
    for o, maker in cycle:
        lines += [f"    {o}", f"      is made {maker}, which needs"]
    return lines + [f"    {cycle[0][0]}   (back to the start)"]


def _tree_head(tree: TreeFile) -> str:
    head = f"Tree: {tree.path}" + (f" (line {tree.line})" if tree.line and tree.line > 1 else "")
    return head + (f"  method {tree.method}" if tree.method else "")


def _goal_lines(goals: list, source: str) -> list[str]:
    source = f"  ({source})" if source else ""
    if len(goals) > 1:
        return [f"Meal of {len(goals)} goals{source}:"] + [f"  + {g}" for g in goals]
    return [f"Goal: {goals[0] if goals else '-'}{source}"]


def _steps(numbers: list[int]) -> str:
    return " ".join(map(str, numbers)) or "-"


def _fire_lines(can: list[int], never: list[int]) -> list[str]:
    return [f"Units that can fire (in order, steps): {_steps(can)}"] + (
        [f"Units that never fire (steps): {_steps(never)}"] if never else []
    )


def report_text(problem: Problem, report: Report) -> str:
    """The human-readable report of one tree."""
    tree, ids = report.tree, report.ids
    lines = [_tree_head(tree), *_goal_lines([problem.objects[g] for g in report.meal], report.goal_source)]
    n_known = sum(u is not None for u in ids)
    lines.append(f"Units: {len(ids)} read, {n_known} found in the FOON, {len(ids) - n_known} unknown")
    f = report.finding
    gone = unreachable(report)
    lines.append(f"Verdict: {f.message if f is not None and gone else 'VALID' if report.valid else 'INVALID'}")
    lines += [f"uses {s['used']} for {s['needed']}" for s in report.substitutions or []]
    if f is not None and not gone:
        if f.kind == "cycle":
            lines += _cycle_lines(
                [(problem.objects[o], "in this tree by " + describe_unit(problem, u, tree, ids)) for o, u in f.cycle]
            )
        else:
            lines.append(f"Problem: {f.message}")
    v = report.validation
    if v is not None:
        order = [ids.index(u) + 1 for u in v.order]
        if report.valid:
            if report.order_problem is None:
                lines.append("Order: the steps as written are executable")
            else:
                lines.append(f"Order: not executable as written ({report.order_problem})")
                lines.append(f"Executable order (steps): {_steps(order)}")
        else:
            lines += _fire_lines(order, [ids.index(u) + 1 for u in v.stuck])
    if report.cost:
        lines.append(f"Size: {_cost_text(report.cost)}")
    if report.proof is not None:
        p = report.proof
        lines.append(
            "Proof: " + ("its landmarks prove it optimal (verified)" if p["verified"] else f"refused: {p['problem']}")
        )
    opt = report.optimum
    if opt is not None:
        if opt.has_tree:
            diff = report.cost["units"] - opt.cost["units"]
            rel = "the optimum" if report.valid and diff == 0 else f"{diff:+d} units vs optimum" if report.valid else ""
            by = ""
            if report.optimum_proof is not None:  # proven by its landmarks, checked here again
                by = ", proven by bounds: " + ("landmarks verified" if report.optimum_proof["verified"] else "refused")
            lines.append(
                f"ASP optimum: {_cost_text(opt.cost)} ({opt.status}{by})" + (f"; this tree is {rel}" if rel else "")
            )
        else:
            why = ": no well-founded tree exists for this goal" if opt.status == "unreachable" else ""
            lines.append(f"ASP optimum: none ({opt.status}{why})")
    return "\n".join(lines) + "\n"


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
        # null: no tree to judge, the goal confirmed unreachable ("problem": "unreachable")
        "valid": None if unreachable(report) else report.valid,
        "problem": report.finding.kind if report.finding else None,
        "message": report.finding.message if report.finding else None,
        "cycle": [
            {"object": problem.objects[o].to_json(), "unit": u, "motion": problem.units[u].motion}
            for o, u in (report.finding.cycle if report.finding else [])
        ],
        "unknown_steps": [tu.step for tu, u in zip(report.tree.units, report.ids) if u is None],
        "order_as_written_ok": report.order_problem is None if v is not None and report.valid else None,
        "executable_order_steps": [report.ids.index(u) + 1 for u in v.order] if v is not None else [],
        "cost": report.cost,
    }
    if report.substitutions is not None:
        out["substitutions"] = report.substitutions
    if report.proof is not None:
        out["proof"] = report.proof
    if report.optimum is not None:
        optimum: dict = {"status": report.optimum.status, "cost": report.optimum.cost}
        optimum["proven_by"] = report.optimum.proven_by
        if report.optimum_proof is not None:
            optimum["proof"] = report.optimum_proof
        if report.optimum.substitutions is not None:
            optimum["substitutions"] = report.optimum.substitutions
        out["optimum"] = optimum
    return out


#: what judging a tree on its own cannot see, said whenever its leaves stand for the kitchen
LEAVES_CAVEAT = (
    "a missing step cannot be detected without a kitchen: whatever no unit of the tree makes is"
    " assumed to be in the kitchen (give --kitchen FILE, or --data or --foon to check against a FOON)"
)


def assumes_leaves(report: AloneReport) -> bool:
    """Is the kitchen of this verdict the tree's own leaves (no kitchen was given)?"""
    return report.kitchen_source == "its leaves"


def alone_text(report: AloneReport) -> str:
    """The human-readable verdict on a tree judged on its own."""
    tree, v = report.tree, report.verdict
    lines = [_tree_head(tree), f"Judged on its own: kitchen = {report.kitchen_source} ({len(v.kitchen)} objects)"]
    if assumes_leaves(report):
        lines.append("Assumed in the kitchen (its leaves): " + ("; ".join(map(str, v.kitchen)) or "-"))
        lines.append(f"Note: {LEAVES_CAVEAT}")
    lines += _goal_lines(list(v.goals), report.goal_source)
    lines.append(f"Units: {len(tree.units)}")
    lines.append(f"Verdict: {'VALID' if report.valid else 'INVALID'}")
    if report.valid:
        lines.append("Order: every unit fires in the order written")
        return "\n".join(lines) + "\n"
    if v.cycle:
        lines += _cycle_lines([(o, f"by step {v.step(p)} ({tree.units[p - 1].unit.motion})") for o, p in v.cycle])
    else:
        lines.append(f"Problem: {v.problem}")
    b = v.blocked
    if b is not None and v.kind != "order":
        later = f"only step {v.step(b.made_by)} makes it" if b.made_by else "no unit makes it"
        lines.append(
            f"First unit that cannot fire in order: step {v.step(b.step)} ({b.unit.motion}) waits for {b.waits_for} ({later})"
        )
    order = [v.step(p) for p in v.order]
    if v.valid:
        lines.append(f"As a set: the units make the goal in another order (steps {_steps(order)})")
    else:
        lines += _fire_lines(order, [v.step(p) for p in v.stuck])
    return "\n".join(lines) + "\n"


def alone_json(report: AloneReport) -> dict:
    """The verdict as plain data: the keys of :func:`report_json` that apply, and ``judged``,
    ``kitchen``, ``kitchen_assumed``, ``note``, ``valid_as_set``, ``blocked``, ``stuck``."""
    tree, v = report.tree, report.verdict
    b = v.blocked
    goal = (
        {"goals": [g.to_json() for g in v.goals]}
        if len(v.goals) > 1
        else {"goal": v.goals[0].to_json() if v.goals else None}
    )
    return {
        "tree": tree.path,
        **goal,
        "goal_source": report.goal_source,
        "method": tree.method,
        "valid": report.valid,
        "problem": v.kind,
        "message": v.problem if not report.valid else None,
        "cycle": [
            {"object": o.to_json(), "unit": v.step(p), "motion": tree.units[p - 1].unit.motion} for o, p in v.cycle
        ],
        "judged": "on its own",
        "kitchen_source": report.kitchen_source,
        "kitchen": [o.to_json() for o in v.kitchen],
        "kitchen_assumed": assumes_leaves(report),
        "note": LEAVES_CAVEAT if assumes_leaves(report) else None,
        "valid_as_set": v.valid,
        "blocked": None
        if b is None
        else {
            "step": v.step(b.step),
            "motion": b.unit.motion,
            "waits_for": b.waits_for.to_json(),
            "made_by": None if b.made_by is None else v.step(b.made_by),
        },
        "stuck": [v.step(p) for p in v.stuck],
        "executable_order_steps": [v.step(p) for p in v.order],
        "units": len(tree.units),
    }


def _one(problem: Problem | None, report: Report | AloneReport, as_json: bool = False):
    """One report as ``check`` prints it (``as_json``: as ``check --format json`` lists it)."""
    if isinstance(report, AloneReport):
        return alone_json(report) if as_json else alone_text(report)
    assert problem is not None
    return report_json(problem, report) if as_json else report_text(problem, report)


@register("check", "text", "txt")
def check_text(problem: Problem | None, reports: list[Report | AloneReport]) -> str:
    out = "\n".join(_one(problem, r) for r in reports)
    if len(reports) < 2:
        return out
    gone = sum(unreachable(r) for r in reports)
    valid = sum(r.valid for r in reports)
    out += f"\nChecked {len(reports)} trees: {valid} valid, {len(reports) - valid - gone} invalid"
    return out + (f", {gone} unreachable (no tree to check)" if gone else "") + "\n"


@register("check", "json", "json")
def check_json(problem: Problem | None, reports: list[Report | AloneReport]) -> str:
    return json.dumps([_one(problem, r, as_json=True) for r in reports], indent=2) + "\n"
