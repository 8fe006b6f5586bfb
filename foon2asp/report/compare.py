"""The comparison table of ``compare``: text, Markdown, CSV and JSON."""

from __future__ import annotations

import csv
import io
import json

from foon2asp.analysis.compare import Row
from foon2asp.foon.problem import Problem
from foon2asp.report.registry import get, register
from foon2asp.tree.serialize import json_list, tree_json
from foon2asp.tree.tasktree import TaskTree


def _label(problem: Problem, goal: int) -> str:
    return problem.objects[goal].label


def units_cell(tree: TaskTree) -> str:
    """``25``, ``10 invalid``, ``12 feasible``, or the status when there is no tree."""
    if not tree.has_tree:
        return tree.status
    cell = str(len(tree.units))
    if not tree.extra.get("valid"):
        cell += " invalid"
    if tree.status == "feasible":
        cell += " feasible"
    return cell


def quality_cell(tree: TaskTree) -> str:
    """``1.02e-10 / 13``: success product / depth (``-`` when the goal is never made)."""
    if not tree.has_tree:
        return "-"
    depth = tree.cost.get("depth")
    return f"{tree.cost.get('success', 0):.3g} / {depth if depth is not None else '-'}"


def _header(name: str) -> str:
    return "asp optimum" if name == "asp" else name


def _table(problem: Problem, rows: list[Row], cell, markdown: bool) -> list[str]:
    names = list(rows[0].trees) if rows else []
    head = ["goal"] + [_header(n) for n in names]
    body = [[_label(problem, r.goal)] + [cell(r.trees[n]) for n in names] for r in rows]
    if markdown:
        out = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] + ["---:"] * len(names)) + "|"]
        out += ["| " + " | ".join(line) + " |" for line in body]
        return out
    widths = [max(len(x[i]) for x in [head] + body) for i in range(len(head))]

    def fmt(line: list[str]) -> str:
        cells = (c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in enumerate(zip(line, widths)))
        return "  ".join(cells).rstrip()

    return [fmt(head), fmt(["-" * w for w in widths])] + [fmt(line) for line in body]


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
    if "asp" in names:
        worse = [
            (r, n)
            for r in rows
            for n, t in r.trees.items()
            if n != "asp"
            and t.extra.get("valid")
            and r.trees["asp"].status == "optimal"
            and len(t.units) < len(r.trees["asp"].units)
        ]
        checked = sum(
            1
            for r in rows
            for n, t in r.trees.items()
            if n != "asp" and t.extra.get("valid") and r.trees["asp"].status == "optimal"
        )
        if worse:
            lines.append(f"WARNING: {len(worse)} valid tree(s) smaller than the asp optimum")
        else:
            lines.append(f"asp optimum <= every valid tree: yes ({checked} valid trees compared)")
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


register("compare", "text", "txt", "aligned table, goals x methods")(lambda problem, rows: render_table(problem, rows))
register("compare", "markdown", "md", "Markdown table, goals x methods")(
    lambda problem, rows: render_table(problem, rows, markdown=True)
)
register("compare", "csv", "csv", "one row per goal and method")(render_csv)
register("compare", "json", "json", "solve-shaped results, each with valid")(render_json)
register("compare", "jsonl", "jsonl", "JSON lines: one solve-shaped result with valid per goal and method")(
    lambda problem, rows: "".join(json.dumps(tree_json(problem, t)) + "\n" for r in rows for t in r.trees.values())
)


def render(problem: Problem, rows: list[Row], fmt: str) -> str:
    return get("compare", fmt).render(problem, rows)
