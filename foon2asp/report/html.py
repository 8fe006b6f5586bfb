"""One self-contained HTML page: the comparison table and a drawing of every tree.

``compare --format html`` writes the earlier work's Table I (units per tree
for each method beside the proven optimum, invalid trees marked) and, for
each goal, the drawing of every tree as inline SVG; an invalid tree is
flagged with the cycle that blocks it (in words and in red in its drawing).
``batch --summary html`` writes the per-method summary and the drawing of
every tree in the results (and with ``--schedule`` the Gantt chart of each
schedule); ``schedule --format html`` the Gantt charts of the schedules.  No
scripts, no external files.
"""

from __future__ import annotations

import html
import json

from foon2asp.foon.foonjson import parse_json
from foon2asp.foon.problem import Problem
from foon2asp.report import draw, gantt
from foon2asp.report.compare import summary, units_cell
from foon2asp.report.registry import register
from foon2asp.report.summary import _COLUMNS, _cell
from foon2asp.tree.results import BatchReport, Row

_STYLE = """
body { font-family: Helvetica, Arial, sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 1em 0; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.invalid { color: #cc0000; font-weight: bold; }
td.optimum { background: #fff2cc; }
section.goal { border-top: 2px solid #ddd; margin-top: 1.5em; }
div.trees { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
figure.tree { margin: 0; border: 1px solid #ccc; padding: 0.4em; max-width: 100%; overflow: auto; }
figure.tree.invalid { border: 2px solid #cc0000; }
figure.tree svg { max-width: 48em; height: auto; }
figcaption { font-size: 0.9em; margin-bottom: 0.3em; }
p.problem { color: #cc0000; font-size: 0.85em; max-width: 48em; }
"""


def _esc(text: object) -> str:
    return html.escape(str(text), quote=True)


def page(title: str, body: list[str]) -> str:
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{_esc(title)}</title>\n<style>{_STYLE}</style>\n</head>\n<body>\n"
        f"<h1>{_esc(title)}</h1>\n" + "\n".join(body) + "\n</body>\n</html>\n"
    )


def _header(name: str) -> str:
    return "asp optimum" if name == "asp" else name


def compare_html(problem: Problem, rows: list[Row]) -> str:
    """Table I and, per goal, the drawing of every tree."""
    draw.require_dot()
    names = list(rows[0].trees) if rows else []
    body = [
        "<p>Units per task tree. <b>invalid</b>: the tree is not derivable from the kitchen using only its own "
        "units (see <code>foon2asp check</code>); the optimum is proven by the ASP solver.</p>",
        f'<p class="legend">{_esc(draw.LEGEND)}</p>',
        '<table id="units">',
        "<thead><tr><th>goal</th>" + "".join(f"<th>{_esc(_header(n))}</th>" for n in names) + "</tr></thead>",
        "<tbody>",
    ]
    for k, r in enumerate(rows, 1):
        cells = []
        for n in names:
            t = r.trees[n]
            cls = ["num"]
            if t.has_tree and not t.extra.get("valid"):
                cls.append("invalid")
            if n == "asp":
                cls.append("optimum")
            cells.append(f'<td class="{" ".join(cls)}">{_esc(units_cell(t))}</td>')
        label = problem.objects[r.goal].label
        body.append(f'<tr><td><a href="#goal-{k}">{_esc(label)}</a></td>' + "".join(cells) + "</tr>")
    body += ["</tbody>", "</table>", "<ul>" + "".join(f"<li>{_esc(line)}</li>" for line in summary(rows)) + "</ul>"]
    body.append("<h2>Task trees</h2>")
    for k, r in enumerate(rows, 1):
        body.append(f'<section class="goal" id="goal-{k}"><h3>{_esc(problem.objects[r.goal])}</h3>')
        body.append('<div class="trees">')
        for n, t in r.trees.items():
            if not t.has_tree:
                body.append(
                    f'<figure class="tree none"><figcaption><b>{_esc(n)}</b>: {_esc(t.status)}</figcaption></figure>'
                )
                continue
            valid = bool(t.extra.get("valid"))
            caption = f"<b>{_esc(n)}</b>: {len(t.units)} units, " + ("valid" if valid else "<b>INVALID</b>")
            svg = draw.inline_svg(draw.svg_text(draw.trees_graph(problem, [t])), f"g{k}-{_esc(n)}-")
            problem_text = f'<p class="problem">{_esc(t.extra["problem"])}</p>' if t.extra.get("problem") else ""
            state = "valid" if valid else "invalid"
            body.append(
                f'<figure class="tree {state}" data-method="{_esc(n)}" data-units="{len(t.units)}">'
                f"<figcaption>{caption}</figcaption>{problem_text}{svg}</figure>"
            )
        body.append("</div></section>")
    return page("foon2asp: task trees compared", body)


def schedules_body(records: list[dict]) -> list[str]:
    """A table of the schedules' makespans and the Gantt chart of each (schedule JSON records)."""
    draw.require_dot()
    body = [
        '<table id="schedules"><thead><tr><th>goal</th><th>status</th><th>makespan s</th>'
        "<th>list scheduling s</th><th>lower bound s</th><th>agents</th></tr></thead><tbody>"
    ]
    for r in records:
        cells = [
            gantt.goal_text(r),
            r.get("status"),
            r.get("makespan"),
            (r.get("baseline") or {}).get("makespan"),
            (r.get("bounds") or {}).get("lower"),
            ", ".join(map(str, r.get("agents", []))),
        ]
        body.append("<tr>" + "".join(f"<td>{_esc('-' if c is None else c)}</td>" for c in cells) + "</tr>")
    body.append("</tbody></table>")
    for k, r in enumerate(records, 1):
        if r.get("schedule"):
            svg = draw.inline_svg(gantt.gantt_svg(r), f"s{k}-")
            body.append(f'<figure class="tree schedule" data-goal="{_esc(gantt.goal_text(r))}">{svg}</figure>')
    return body


def schedule_html(records: list[dict]) -> str:
    """``schedule --format html``: the schedules' table and their Gantt charts."""
    return page("foon2asp: schedules", schedules_body(list(records)))


def summary_html(rows: list[dict], report: BatchReport | None = None, schedules: list[dict] | None = None) -> str:
    """The batch summary table, the drawing of every tree in the results and the Gantt chart of
    each of ``schedules`` (``batch --schedule``)."""
    body = []
    if report is not None:
        body.append(
            f"<p>{report.done} new result(s), {report.skipped} already done, {report.elapsed_s:.2f} s "
            f"with {report.workers} worker(s)"
            + (f"; results in {_esc(report.output)}" if report.output else "")
            + "</p>"
        )
    body.append(
        '<table id="summary"><thead><tr>' + "".join(f"<th>{_esc(c)}</th>" for c in _COLUMNS) + "</tr></thead><tbody>"
    )
    for row in rows:
        body.append("<tr>" + "".join(f"<td>{_esc(_cell(row[c]))}</td>" for c in _COLUMNS) + "</tr>")
    body.append("</tbody></table>")
    records = report.records if report is not None else []
    trees = [r for r in records if r.get("status") in ("optimal", "feasible", "found") and r.get("units")]
    if trees:
        draw.require_dot()
        body.append('<h2>Task trees</h2><div class="trees">')
    for k, r in enumerate(trees, 1):
        units = parse_json(json.dumps(r["units"]), "results").units
        goal = r.get("goal") or {}
        method = r.get("requested_method", r.get("method", "?"))
        top = draw._top_product(units)
        marks = draw.Marks(
            title=f"{goal.get('label', '?')} -- {method}, {r.get('status')}, {len(units)} units", goal=top
        )
        svg = draw.inline_svg(draw.svg_text(draw.build_graph(units, marks)), f"r{k}-")
        body.append(
            f'<figure class="tree" data-method="{_esc(method)}" data-units="{len(units)}">'
            f"<figcaption><b>{_esc(goal.get('label', '?'))}</b>: {_esc(method)}, {len(units)} units</figcaption>{svg}</figure>"
        )
    if trees:
        body.append("</div>")
    if schedules:
        body += ["<h2>Schedules</h2>", *schedules_body(schedules)]
    return page("foon2asp: batch summary", body)


register("compare", "html", "html", "one self-contained HTML page: the table and a drawing of every tree")(compare_html)
register("summary", "html", "html", "HTML page: the summary and a drawing of every tree")(summary_html)
register("schedule", "html", "html", "HTML page: the schedules and their Gantt charts")(schedule_html)
