"""The comparison table of ``compare``: text, Markdown, CSV and JSON."""

from __future__ import annotations

import csv
import io
import json

from foon2asp.foon.problem import Problem
from foon2asp.report import registry
from foon2asp.report.registry import register
from foon2asp.tree.results import MealRow, Row
from foon2asp.tree.serialize import json_list, number, tree_json
from foon2asp.tree.tasktree import TaskTree


def _label(problem: Problem, goal: int) -> str:
    return problem.objects[goal].label


def units_cell(tree: TaskTree) -> str:
    """``25``, ``10 invalid``, ``12 feasible``, ``65 feasible (>= 54)`` (with a lower bound), or the status."""
    if not tree.has_tree:
        return tree.status
    cell = str(len(tree.units))
    if not tree.extra.get("valid"):
        cell += " invalid"
    if tree.status == "feasible":
        cell += " feasible"
        if tree.bound is not None and "units" in tree.bound and tree.bound["units"] < len(tree.units):
            cell += f" (>= {tree.bound['units']})"
    return cell


def quality_cell(tree: TaskTree) -> str:
    """``1.02e-10 / 13``: success product / depth, and ``/ cost 1.35`` with a motion-cost table."""
    if not tree.has_tree:
        return "-"
    depth = tree.cost.get("depth")
    cell = f"{number(tree.cost.get('success', 0))} / {depth if depth is not None else '-'}"
    return cell + (f" / cost {number(tree.cost['cost'])}" if "cost" in tree.cost else "")


def method_header(name: str) -> str:
    """The column heading of a method."""
    return "asp optimum" if name == "asp" else name


def _grid(head: list[str], body: list[list[str]], markdown: bool, rule: bool = True) -> list[str]:
    """A table as Markdown or aligned text (``rule``: a dashed line under the heading), the first
    column left-aligned, the others right-aligned."""
    if markdown:
        out = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|"]
        return out + ["| " + " | ".join(line) + " |" for line in body]
    widths = [max(len(x[i]) for x in [head] + body) for i in range(len(head))]
    lines = [head] + ([["-" * w for w in widths]] if rule else []) + body
    return [
        "  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in enumerate(zip(line, widths))).rstrip()
        for line in lines
    ]


def _table(problem: Problem, rows: list[Row], cell, markdown: bool) -> list[str]:
    names = list(rows[0].trees) if rows else []
    head = ["goal"] + [method_header(n) for n in names]
    body = [[_label(problem, r.goal)] + [cell(r.trees[n]) for n in names] for r in rows]
    return _grid(head, body, markdown)


def summary(rows: list[Row]) -> list[str]:
    """Per method: trees found and valid; and whether the optimum is <= every valid tree."""
    names = list(rows[0].trees) if rows else []
    lines = []
    for n in names:
        trees = [r.trees[n] for r in rows]
        found = sum(t.has_tree for t in trees)
        valid = sum(bool(t.extra.get("valid")) for t in trees)
        total = sum(len(t.units) for t in trees if t.extra.get("valid"))
        lines.append(f"{n}: {found} of {len(trees)} goals with a tree, {valid} valid ({total} units in valid trees)")
    constrained = sorted({c for r in rows if "asp" in r.trees for c in r.trees["asp"].extra.get("constraints", ())})
    if "asp" in names and constrained and len(names) > 1:
        lines.append(
            f"asp obeys the constraints ({', '.join(constrained)}); the other methods are unconstrained,"
            " so no conclusion is drawn from comparing them"
        )
    elif "asp" in names:
        compared = [
            (t, r.trees["asp"])
            for r in rows
            for n, t in r.trees.items()
            if n != "asp" and t.extra.get("valid") and r.trees["asp"].status == "optimal"
        ]
        worse = sum(len(t.units) < len(best.units) for t, best in compared)
        if worse:
            lines.append(f"WARNING: {worse} valid tree(s) smaller than the asp optimum")
        else:
            lines.append(f"asp optimum <= every valid tree: yes ({len(compared)} valid trees compared)")
    return lines


def render_table(problem: Problem, rows: list[Row], markdown: bool = False) -> str:
    """Units per goal and method (Table I), then success product / depth, then a summary."""
    out = ["Units per task tree ('invalid': not derivable from the kitchen; see 'foon2asp check')", ""]
    out += _table(problem, rows, units_cell, markdown)
    out += ["", "Success product / depth", ""]
    out += _table(problem, rows, quality_cell, markdown)
    out += [""] + [("- " if markdown else "") + line for line in summary(rows)]
    return "\n".join(out) + "\n"


def render_csv(problem: Problem, rows: list[Row]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["goal", "method", "status", "valid", "units", "success", "depth", "inputs", "time_s", "problem"])
    for r in rows:
        for name, t in r.trees.items():
            c = t.cost
            w.writerow(
                [
                    str(problem.objects[r.goal]),
                    name,
                    t.status,
                    str(bool(t.extra.get("valid"))).lower(),
                    len(t.units) if t.has_tree else "",
                    c.get("success", ""),
                    "" if c.get("depth") is None else c["depth"],
                    c.get("inputs", ""),
                    round(t.time_s, 6),
                    t.extra.get("problem", ""),
                ]
            )
    return buf.getvalue()


def render_json(problem: Problem, rows: list[Row]) -> str:
    """A flat list of ``solve``-shaped results, each with ``"valid"``."""
    return json_list([tree_json(problem, t) for r in rows for t in r.trees.values()]) + "\n"


def _meal_lines(problem: Problem, row: MealRow, markdown: bool) -> list[str]:
    head = ["", "units", "success", "inputs", "depth"]

    def cells(cost: dict, status: str) -> list[str]:
        if not cost:
            return [status, "-", "-", "-"]
        depth = cost.get("depth")
        return [str(cost["units"]), number(cost["success"]), str(cost["inputs"]), "-" if depth is None else str(depth)]

    body = [[_label(problem, t.goal) + " (alone)"] + cells(t.cost, t.status) for t in row.singles]
    total = row.total()
    body.append(["sum of single optima"] + cells(total, "-"))
    status = "" if row.meal.status == "optimal" else f" ({row.meal.status})"
    body.append([f"meal, together{status}"] + cells(row.meal.cost, row.meal.status))
    out = _grid(head, body, markdown, rule=False)
    if total and row.meal.has_tree:
        saved = total["units"] - row.meal.cost["units"]
        valid = "valid" if row.meal.extra.get("valid") else "INVALID"
        out += ["", f"{'- ' if markdown else ''}shared units counted once: {saved} unit(s) fewer together ({valid})"]
    elif row.meal.extra.get("reason"):
        out += ["", f"{'- ' if markdown else ''}{row.meal.extra['reason']}"]
    return out


def render_meal(problem: Problem, row: MealRow, markdown: bool = False) -> str:
    """The meal's optimum beside each goal's own optimum and their sum."""
    out = [f"Meal of {len(row.goals)} goals: one tree for all, beside the single optima", ""]
    return "\n".join(out + _meal_lines(problem, row, markdown)) + "\n"


def meal_json(problem: Problem, row: MealRow) -> dict:
    return {
        "goals": [problem.objects[g].to_json() for g in row.goals],
        "meal": tree_json(problem, row.meal),
        "singles": [tree_json(problem, t) for t in row.singles],
        "sum_of_singles": row.total(),
    }


def meal_csv(problem: Problem, row: MealRow) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["row", "status", "units", "success", "inputs", "depth"])
    lines = [(str(problem.objects[t.goal]), t.status, t.cost) for t in row.singles]
    lines += [("sum of single optima", "", row.total()), ("meal", row.meal.status, row.meal.cost)]
    for name, status, cost in lines:
        w.writerow([name, status, *(cost.get(k, "") for k in ("units", "success", "inputs", "depth"))])
    return buf.getvalue()


def _text(problem: Problem, rows) -> str:
    return render_meal(problem, rows) if isinstance(rows, MealRow) else render_table(problem, rows)


def _markdown(problem: Problem, rows) -> str:
    return render_meal(problem, rows, True) if isinstance(rows, MealRow) else render_table(problem, rows, True)


def _csv(problem: Problem, rows) -> str:
    return meal_csv(problem, rows) if isinstance(rows, MealRow) else render_csv(problem, rows)


def _json(problem: Problem, rows) -> str:
    if isinstance(rows, MealRow):
        return json.dumps(meal_json(problem, rows)) + "\n"
    return render_json(problem, rows)


register("compare", "text", "txt", "aligned table, goals x methods (a meal: beside the single optima)")(_text)
register("compare", "markdown", "md", "Markdown table, goals x methods (a meal: beside the single optima)")(_markdown)
register("compare", "csv", "csv", "one row per goal and method")(_csv)
register("compare", "json", "json", "solve-shaped results, each with valid")(_json)


def _jsonl(problem: Problem, rows) -> str:
    if isinstance(rows, MealRow):
        return json.dumps(meal_json(problem, rows)) + "\n"
    return "".join(json.dumps(tree_json(problem, t)) + "\n" for r in rows for t in r.trees.values())


register("compare", "jsonl", "jsonl", "JSON lines: one solve-shaped result with valid per goal and method")(_jsonl)


def render(problem: Problem, rows: list[Row], fmt: str) -> str:
    return registry.render("compare", fmt, problem, rows)
