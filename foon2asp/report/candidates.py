"""The report of ``consolidate``: text, JSON, HTML (the candidates table and the drawing of the
result, its units coloured by source) and the result as unit-list JSON.

The JSON is a list with one object per goal (or meal): ``{"goal", "status", "cost", "units":
[{..., "sources"}], "candidates": [{"file", "valid", "problem", "cost", "used_units"}],
"missing"}`` (and ``"substitutions"`` when the tree uses any).
"""

from __future__ import annotations

import time

from foon2asp.foon.problem import Problem
from foon2asp.foon.unitlist import dumps_trees
from foon2asp.outcomes import CandidateVerdict, Consolidation
from foon2asp.report import draw
from foon2asp.report.formats import register
from foon2asp.report.html import esc, figure, page, table, time_line
from foon2asp.tree.serialize import json_list, number, tree_text

#: fill colours of the candidate files, in the order given (repeated after the last)
PALETTE = ("#9fc5e8", "#f6b26b", "#b6d7a8", "#d5a6bd", "#ffe599", "#a2c4c9", "#ea9999", "#b4a7d6")


def consolidation_json(problem: Problem, c: Consolidation) -> dict:
    """One goal's object of ``consolidate --format json``."""
    missing = c.missing.missing if c.missing is not None else []
    goals = [problem.objects[g].to_json() for g in c.goals]
    out = {
        "goal": goals[0] if len(goals) == 1 else goals,
        "status": c.tree.status,
        "cost": c.tree.cost,
        "units": [{**problem.units[u].to_json(), "sources": list(c.sources[u])} for u in c.tree.units],
        "candidates": [
            {
                "file": v.candidate.path,
                "valid": v.valid,
                "problem": None if v.valid else v.verdict.problem,
                "cost": v.cost,
                "used_units": v.used,
            }
            for v in c.candidates
        ],
        "missing": [problem.objects[o].to_json() for o in missing],
    }
    if c.tree.substitutions is not None:
        out["substitutions"] = c.tree.substitutions
    return out


def _versus(v: CandidateVerdict, best: dict) -> str:
    """``7 units (+1 vs the optimum), cost 2.1 (+0.3 vs the optimum)``."""
    parts = []
    for key, unit in (("units", " units"), ("cost", "")):
        if key not in v.cost:
            continue
        text = f"{'cost ' if key == 'cost' else ''}{number(v.cost[key])}{unit}"
        if v.valid and key in best:
            diff = v.cost[key] - best[key]
            text += (
                " (= the optimum)"
                if diff == 0
                else f" ({'+' if diff > 0 else ''}{number(round(diff, 2))} vs the optimum)"
            )
        parts.append(text)
    return ", ".join(parts)


def candidate_line(v: CandidateVerdict, best: dict, width: int) -> str:
    verdict = "valid  " if v.valid else "INVALID"
    used = " ".join(map(str, v.used)) or "none"
    line = f"  {v.candidate.path:<{width}}  {verdict}  {_versus(v, best)}; the tree uses its steps: {used}"
    return line + ("" if v.valid else f"\n  {'':<{width}}  why: {v.verdict.problem}")


def consolidation_text(problem: Problem, c: Consolidation) -> str:
    """One goal's report: the tree with each unit's sources, then every candidate's verdict."""
    lines = tree_text(problem, c.tree).rstrip("\n").split("\n")
    top = 2 if len(c.goals) == 1 else 2 + len(c.goals)  # the goal heading and the method line
    head, rest = lines[:top], lines[top:]
    if c.goal_source:
        head[0] += f"  ({c.goal_source})"
    n = len(c.candidates)
    head.append(
        f"Merged: {n} candidate{'s' if n != 1 else ''}, {len(problem.units)} distinct units;"
        f" kitchen: {c.kitchen_source} ({len(c.kitchen)} objects)"
    )
    for k, u in enumerate(c.tree.units):
        head += rest[3 * k : 3 * k + 3] + [f"       from: {', '.join(c.sources[u])}"]
    head += rest[3 * len(c.tree.units) :]
    if c.missing is not None:
        if c.missing.missing:
            added = "; ".join(str(problem.objects[o]) for o in c.missing.missing)
            head.append(f"Missing: add to the kitchen {added} ({c.missing.status})")
        else:
            head.append(f"Missing: no set of objects helps ({c.missing.reason or c.missing.status})")
    head.append("Candidates (each on its own units, in file order, from this kitchen):")
    width = max(len(v.candidate.path) for v in c.candidates)
    head += [candidate_line(v, c.tree.cost, width) for v in c.candidates]
    return "\n".join(head) + "\n"


register("consolidate", "text", "txt")(
    lambda problem, results: "\n".join(consolidation_text(problem, c) for c in results)
)
register("consolidate", "json", "json")(
    lambda problem, results: json_list([consolidation_json(problem, c) for c in results]) + "\n"
)
register("consolidate", "units-json", "json")(
    lambda problem, results: dumps_trees([[problem.units[u] for u in c.tree.units] for c in results])
)


def colors(results: list[Consolidation]) -> dict[str, str]:
    """The fill colour of each candidate file."""
    files = list(dict.fromkeys(v.candidate.path for c in results for v in c.candidates))
    return {f: PALETTE[k % len(PALETTE)] for k, f in enumerate(files)}


def result_graph(problem: Problem, c: Consolidation, fill: dict[str, str], prefix: str = ""):
    """The drawing of the tree, each unit filled with the colours of the files holding it."""
    marks = draw.tree_marks(problem, c.tree)
    marks.unit_colors = {k: tuple(fill[f] for f in c.sources[u]) for k, u in enumerate(c.tree.units)}
    marks.unit_notes = {k: "from " + ", ".join(c.sources[u]) for k, u in enumerate(c.tree.units)}
    marks.legend = (
        "gold: goal · green: in the kitchen · units coloured by the candidate files holding them (striped: several)"
    )
    units = [problem.units[u] for u in c.tree.units]
    return draw.build_graph(units, marks, prefix=prefix)


def _table(c: Consolidation, fill: dict[str, str]) -> str:
    rows = []
    for v in c.candidates:
        swatch = f'<span style="background:{fill[v.candidate.path]}">&nbsp;&nbsp;&nbsp;</span> '
        cls = "valid" if v.valid else "invalid"
        rows.append(
            f'<tr class="{cls}"><td>{swatch}{esc(v.candidate.path)}</td>'
            f'<td class="{cls}">{"valid" if v.valid else "INVALID"}</td>'
            f'<td class="num">{esc(v.cost.get("units"))}</td><td class="num">{esc(number(v.cost.get("cost", "-")))}</td>'
            f"<td>{esc(' '.join(map(str, v.used)) or '-')}</td><td>{esc(v.verdict.problem or '')}</td></tr>"
        )
    head = ["candidate", "verdict", "units", "cost", "steps the tree uses", "why not executable on its own"]
    return table('class="candidates"', head, rows)


@register("consolidate", "html", "html")
def consolidate_html(problem: Problem, results: list[Consolidation]) -> str:
    fill = colors(results)
    body = [""]  # the time it took, once the drawings are made
    started = time.perf_counter()
    for k, c in enumerate(results, 1):
        goal = " + ".join(str(problem.objects[g]) for g in c.goals)
        cost = ", ".join(f"{key} {number(val)}" for key, val in c.tree.cost.items())
        body.append(f'<section class="goal" id="goal-{k}"><h2>{esc(goal)}</h2>')
        body.append(
            f"<p>{esc(c.goal_source)}; {esc(c.tree.method)}: <b>{esc(c.tree.status)}</b>"
            + (f" ({esc(cost)})" if cost else "")
            + "</p>"
        )
        body.append(_table(c, fill))
        if c.missing is not None:
            added = "; ".join(str(problem.objects[o]) for o in c.missing.missing) or "nothing helps"
            body.append(f'<p class="problem">unreachable from this kitchen; to add: {esc(added)}</p>')
        if c.tree.has_tree and c.tree.units:
            draw.require_dot()
            svg = draw.svg_text(result_graph(problem, c, fill))
            caption = f"<b>{esc(goal)}</b>: {len(c.tree.units)} units, {esc(c.tree.status)}"
            body.append(figure(svg, f"c{k}", "tree valid", caption, back=f"goal-{k}"))
        body.append("</section>")
    body[0] = time_line(
        [("solving", sum(c.tree.time_s for c in results)), ("drawing this page", time.perf_counter() - started)],
        " (solving: the solver's times per goal, summed; reading and merging the candidates are not counted)",
    )
    return page("foon2asp: candidate trees consolidated", body)
