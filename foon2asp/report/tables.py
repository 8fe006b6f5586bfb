"""Tables: the comparison of ``compare`` and the summary of ``batch``, as text, Markdown, CSV and JSON."""

from __future__ import annotations

import csv
import io
import json
from collections.abc import Callable, Iterable
from functools import partial

from foon2asp.foon.problem import Problem
from foon2asp.outcomes import BatchReport, MealRow, Row
from foon2asp.report.formats import register
from foon2asp.tree.serialize import json_list, number, tree_json
from foon2asp.tree.tasktree import TaskTree


def units_cell(tree: TaskTree) -> str:
    """``25``, ``10 invalid``, ``12 feasible``, ``65 feasible (>= 54)`` (with a lower bound), or the status."""
    if not tree.has_tree:
        return tree.status
    cell = str(len(tree.units))
    if not tree.valid:
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


def grid(head: list[str], body: list[list[str]], markdown: bool, rule: bool = True, right: bool = True) -> list[str]:
    """A table as Markdown or aligned text (``rule``: a dashed line under the heading), the first
    column left-aligned, the others right-aligned (``right``) or left-aligned."""
    if markdown:
        align = "---:" if right else "---"
        out = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] + [align] * (len(head) - 1)) + "|"]
        return out + ["| " + " | ".join(line) + " |" for line in body]
    widths = [max(len(x[i]) for x in [head] + body) for i in range(len(head))]
    lines = [head] + ([["-" * w for w in widths]] if rule else []) + body
    return [
        "  ".join(c.rjust(w) if i and right else c.ljust(w) for i, (c, w) in enumerate(zip(line, widths))).rstrip()
        for line in lines
    ]


def csv_text(rows: Iterable[Iterable[object]]) -> str:
    """``rows`` (the heading first) as CSV."""
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerows(rows)
    return buf.getvalue()


def _table(problem: Problem, rows: list[Row], cell, markdown: bool) -> list[str]:
    names = list(rows[0].trees) if rows else []
    head = ["goal"] + [method_header(n) for n in names]
    body = [[problem.objects[r.goal].label] + [cell(r.trees[n]) for n in names] for r in rows]
    return grid(head, body, markdown)


def summary(rows: list[Row]) -> list[str]:
    """Per method: trees found and valid; and whether the optimum is <= every valid tree."""
    names = list(rows[0].trees) if rows else []
    lines = []
    for n in names:
        trees = [r.trees[n] for r in rows]
        found = sum(t.has_tree for t in trees)
        valid = sum(bool(t.valid) for t in trees)
        total = sum(len(t.units) for t in trees if t.valid)
        lines.append(f"{n}: {found} of {len(trees)} goals with a tree, {valid} valid ({total} units in valid trees)")
    constrained = sorted({c for r in rows if "asp" in r.trees for c in r.trees["asp"].constraints or ()})
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
            if n != "asp" and t.valid and r.trees["asp"].status == "optimal"
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
    head = ["goal", "method", "status", "valid", "units", "success", "depth", "inputs", "time_s", "problem"]
    return csv_text(
        [head]
        + [
            [
                str(problem.objects[r.goal]),
                name,
                t.status,
                str(bool(t.valid)).lower(),
                len(t.units) if t.has_tree else "",
                t.cost.get("success", ""),
                "" if t.cost.get("depth") is None else t.cost["depth"],
                t.cost.get("inputs", ""),
                round(t.time_s, 6),
                t.problem or "",
            ]
            for r in rows
            for name, t in r.trees.items()
        ]
    )


def render_meal(problem: Problem, row: MealRow, markdown: bool = False) -> str:
    """The meal's optimum beside each goal's own optimum and their sum."""

    def cells(cost: dict, status: str) -> list[str]:
        if not cost:
            return [status, "-", "-", "-"]
        depth = cost.get("depth")
        return [str(cost["units"]), number(cost["success"]), str(cost["inputs"]), "-" if depth is None else str(depth)]

    body = [[problem.objects[t.goal].label + " (alone)"] + cells(t.cost, t.status) for t in row.singles]
    total = row.total()
    body.append(["sum of single optima"] + cells(total, "-"))
    status = "" if row.meal.status == "optimal" else f" ({row.meal.status})"
    body.append([f"meal, together{status}"] + cells(row.meal.cost, row.meal.status))
    out = [f"Meal of {len(row.goals)} goals: one tree for all, beside the single optima", ""]
    out += grid(["", "units", "success", "inputs", "depth"], body, markdown, rule=False)
    if total and row.meal.has_tree:
        saved = total["units"] - row.meal.cost["units"]
        valid = "valid" if row.meal.valid else "INVALID"
        out += ["", f"{'- ' if markdown else ''}shared units counted once: {saved} unit(s) fewer together ({valid})"]
    elif row.meal.reason:
        out += ["", f"{'- ' if markdown else ''}{row.meal.reason}"]
    return "\n".join(out) + "\n"


def meal_json(problem: Problem, row: MealRow) -> str:
    doc = {
        "goals": [problem.objects[g].to_json() for g in row.goals],
        "meal": tree_json(problem, row.meal),
        "singles": [tree_json(problem, t) for t in row.singles],
        "sum_of_singles": row.total(),
    }
    return json.dumps(doc) + "\n"


def meal_csv(problem: Problem, row: MealRow) -> str:
    lines = [(str(problem.objects[t.goal]), t.status, t.cost) for t in row.singles]
    lines += [("sum of single optima", "", row.total()), ("meal", row.meal.status, row.meal.cost)]
    keys = ("units", "success", "inputs", "depth")
    return csv_text(
        [["row", "status", *keys]] + [[name, status, *(cost.get(k, "") for k in keys)] for name, status, cost in lines]
    )


def _register(name: str, ext: str, table: Callable[..., str], meal: Callable[..., str]) -> None:
    """Register format ``name`` of ``compare``: ``table`` renders rows of goals, ``meal`` a meal's row."""
    register("compare", name, ext)(
        lambda problem, rows: meal(problem, rows) if isinstance(rows, MealRow) else table(problem, rows)
    )


_register("text", "txt", render_table, render_meal)
_register("markdown", "md", partial(render_table, markdown=True), partial(render_meal, markdown=True))
_register("csv", "csv", render_csv, meal_csv)
_register(
    "json",
    "json",
    lambda problem, rows: json_list([tree_json(problem, t) for r in rows for t in r.trees.values()]) + "\n",
    meal_json,
)
_register(
    "jsonl",
    "jsonl",
    lambda problem, rows: "".join(json.dumps(tree_json(problem, t)) + "\n" for r in rows for t in r.trees.values()),
    meal_json,
)


SUMMARY_COLUMNS = (
    "method results statuses trees valid units_min units_median units_mean units_max time_total_s time_median_ms"
).split()


def summary_cell(value) -> str:
    if value is None:
        return "-"
    if isinstance(value, dict):
        return " ".join(f"{k}={v}" for k, v in value.items())
    return str(value)


def render_summary(rows: list[dict], fmt: str = "text", report: BatchReport | None = None) -> str:
    """The summary as aligned text, a Markdown table or CSV."""
    table = [[summary_cell(row[c]) for c in SUMMARY_COLUMNS] for row in rows]
    if fmt == "csv":
        return csv_text([SUMMARY_COLUMNS] + table)
    head = ""
    if report is not None:
        head = (
            f"{report.done} new result(s), {report.skipped} already done, "
            f"{report.elapsed_s:.2f} s with {report.workers} worker(s)"
            + (f"; results in {report.output}" if report.output else "")
            + (f"\ngrounding: {report.grounding}" if report.grounding else "")
            + (f" (auto: {report.grounding_reason})" if report.grounding_reason else "")
            + "\n"
        )
    lines = grid(SUMMARY_COLUMNS, table, fmt == "markdown", rule=False, right=False)
    return (head + "\n" if head and fmt == "markdown" else head) + "\n".join(lines) + "\n"


for _fmt, _ext in (("text", "txt"), ("markdown", "md"), ("csv", "csv")):
    register("summary", _fmt, _ext)(lambda rows, report=None, _f=_fmt: render_summary(rows, _f, report))
