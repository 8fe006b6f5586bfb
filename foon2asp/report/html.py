"""One self-contained HTML page: the comparison table and a drawing of every tree.

The pages of ``compare``, ``batch --summary`` and ``schedule`` (``--format html``): no scripts,
no external files.
"""

from __future__ import annotations

import html
import math
import re
import time

from foon2asp.foon.foonjson import read_json
from foon2asp.foon.problem import Problem
from foon2asp.outcomes import BatchReport, Row
from foon2asp.report import draw, gantt
from foon2asp.report.formats import register
from foon2asp.report.tables import SUMMARY_COLUMNS, method_header, summary, summary_cell, units_cell
from foon2asp.tree.tasktree import WITH_TREE

_STYLE = """
body { font-family: Helvetica, Arial, sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 1em 0; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.invalid { color: #cc0000; font-weight: bold; }
td.optimum { background: #fff2cc; }
section.goal { border-top: 2px solid #ddd; margin-top: 1.5em; }
div.trees { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
figure.tree { margin: 0; border: 1px solid #ccc; padding: 0.4em; max-width: 100%; min-width: 0;
  box-sizing: border-box; overflow: auto; background: #fff; }
figure.tree.invalid { border: 2px solid #cc0000; }
figure.tree svg { display: block; max-width: 100%; height: auto; }
figure.tree.schedule { width: 100%; }
figure.tree.schedule svg { max-width: none; }
figcaption { font-size: 0.9em; margin-bottom: 0.3em; }
figcaption a { margin-left: 0.8em; font-size: 0.9em; }
figcaption a.close { display: none; }
figure.tree:target { position: fixed; inset: 0; z-index: 10; max-width: none; width: auto; margin: 0;
  border: 0; padding: 1em; overflow: auto; }
figure.tree:target figcaption a.zoom { display: none; }
figure.tree:target figcaption a.close { display: inline; }
figure.tree:target svg { max-width: none !important; min-width: 0 !important; width: auto !important; }
p.problem { color: #cc0000; font-size: 0.85em; max-width: 60em; }
p.time { color: #555; font-size: 0.9em; }
"""

#: the smallest scale a drawing is shown at, in CSS pixels per point of the drawing: its smallest
#: text (10 points in the tree drawings) is then at least 8 px
MIN_PX_PER_POINT = 0.85
#: the smallest text of a page (CSS pixels)
MIN_TEXT_PX = 8.0


def esc(text: object) -> str:
    """``text`` escaped for HTML."""
    return html.escape(str(text), quote=True)


def page(title: str, body: list[str]) -> str:
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{esc(title)}</title>\n<style>{_STYLE}</style>\n</head>\n<body>\n"
        f"<h1>{esc(title)}</h1>\n" + "\n".join(body) + "\n</body>\n</html>\n"
    )


def table(attrs: str, head: list[str], rows: list[str]) -> str:
    """A table: ``head`` its column names, ``rows`` its ``<tr>`` elements."""
    heading = "".join(f"<th>{esc(h)}</th>" for h in head)
    return f"<table {attrs}><thead><tr>{heading}</tr></thead><tbody>\n" + "\n".join(rows) + "\n</tbody></table>"


def row(values: list[object]) -> str:
    """A table row of text cells (None shown as ``-``)."""
    return "<tr>" + "".join(f"<td>{esc('-' if v is None else v)}</td>" for v in values) + "</tr>"


def _svg_width(svg: str) -> float:
    """The width of an SVG document in its own units (points for Graphviz: the viewBox)."""
    found = re.search(r'<svg\b[^>]*\bviewBox="\s*[-\d.]+[\s,]+[-\d.]+[\s,]+([\d.]+)', svg)
    if found:
        return float(found.group(1))
    found = re.search(r'<svg\b[^>]*\bwidth="([\d.]+)', svg)
    return float(found.group(1)) if found else 0.0


def figure(
    svg: str,
    fig_id: str,
    classes: str,
    caption: str,
    attrs: str = "",
    note: str = "",
    width: str = "",
    back: str = "",
    min_scale: float = MIN_PX_PER_POINT,
) -> str:
    """An SVG document as an inline figure, ids prefixed with ``fig_id``, never under ``min_scale``
    px per point, with a ``full size`` link (``close`` goes back to ``#back``).
    ``caption`` and ``note`` are HTML, ``attrs`` more attributes, ``width`` a CSS width."""
    style = f"min-width: {math.ceil(min_scale * _svg_width(svg))}px" + (f"; width: {width}" if width else "")
    inline = draw.inline_svg(svg, f"{fig_id}-").replace("<svg", f'<svg style="{style}"', 1)
    links = f'<a class="zoom" href="#{esc(fig_id)}">full size</a><a class="close" href="#{esc(back)}">close</a>'
    return (
        f'<figure class="{esc(classes)}"{attrs} id="{esc(fig_id)}">'
        f"<figcaption>{caption}{links}</figcaption>{note}{inline}</figure>"
    )


def time_line(parts: list[tuple[str, float]], note: str = "") -> str:
    """``Time: 12.3 s in all: solving 8.6 s, drawing this page 3.7 s`` as a paragraph."""
    total = sum(seconds for _, seconds in parts)
    listed = ", ".join(f"{what} {seconds:.2f} s" for what, seconds in parts)
    return f'<p class="time">Time: {total:.2f} s in all: {esc(listed)}{esc(note)}.</p>'


def _tree_figure(
    svg: str, fig_id: str, method: str, units: int, valid: bool | None, label: str, problem: str, back: str
) -> str:
    """The figure of one task tree: framed in red with its problem in words when it is invalid."""
    state = "invalid" if valid is False else "valid" if valid else "unjudged"
    verdict = {"invalid": "<b>INVALID</b>", "valid": "valid", "unjudged": "not judged"}[state]
    caption = f"{label}<b>{esc(method)}</b>: {units} units, {verdict}"
    note = f'<p class="problem">{esc(problem)}</p>' if problem and valid is False else ""
    attrs = f' data-method="{esc(method)}" data-units="{units}"'
    return figure(svg, fig_id, f"tree {state}", caption, attrs, note, back=back)


def compare_html(problem: Problem, rows: list[Row]) -> str:
    """Table I and, per goal, the drawing of every tree."""
    draw.require_dot()
    names = list(rows[0].trees) if rows else []
    lines = []
    for k, r in enumerate(rows, 1):
        cells = []
        for n in names:
            t = r.trees[n]
            cls = ["num"]
            if t.has_tree and not t.valid:
                cls.append("invalid")
            if n == "asp":
                cls.append("optimum")
            cells.append(f'<td class="{" ".join(cls)}">{esc(units_cell(t))}</td>')
        label = problem.objects[r.goal].label
        lines.append(f'<tr><td><a href="#goal-{k}">{esc(label)}</a></td>' + "".join(cells) + "</tr>")
    top = [
        "<p>Units per task tree. <b>invalid</b>: the tree is not derivable from the kitchen using only its own "
        "units (see <code>foon2asp check</code>); the optimum is proven by the ASP solver.</p>",
        f'<p class="legend">{esc(draw.LEGEND)}</p>',
        table('id="units"', ["goal", *map(method_header, names)], lines),
        "<ul>" + "".join(f"<li>{esc(line)}</li>" for line in summary(rows)) + "</ul>",
    ]
    body = ["<h2>Task trees</h2>"]
    started = time.perf_counter()
    for k, r in enumerate(rows, 1):
        body.append(f'<section class="goal" id="goal-{k}"><h3>{esc(problem.objects[r.goal])}</h3>')
        body.append('<div class="trees">')
        for n, t in r.trees.items():
            if not t.has_tree:
                body.append(
                    f'<figure class="tree none"><figcaption><b>{esc(n)}</b>: {esc(t.status)}</figcaption></figure>'
                )
                continue
            valid = bool(t.valid)
            svg = draw.svg_text(draw.trees_graph(problem, [t]))
            body.append(_tree_figure(svg, f"g{k}-{n}", n, len(t.units), valid, "", t.problem or "", f"goal-{k}"))
        body.append("</div></section>")
    solving = {n: sum(r.trees[n].time_s for r in rows) for n in names}
    each = ", ".join(f"{method_header(n)} {seconds:.2f} s" for n, seconds in solving.items())
    timing = time_line(
        [("solving", sum(solving.values())), ("drawing this page", time.perf_counter() - started)],
        f" (solving: each method's times per goal, summed: {each}; loading the data is not counted)",
    )
    return page("foon2asp: task trees compared", top + [timing] + body)


def schedules_body(records: list[dict], timed: bool = True) -> list[str]:
    """A table of the schedules' makespans and the Gantt chart of each, on one time scale;
    ``timed``: then how long scheduling and drawing took."""
    draw.require_dot()
    started = time.perf_counter()
    head = ["goal", "status", "makespan s", "list scheduling s", "lower bound before the search s", "agents"]
    cells = [
        [
            gantt.goal_text(r),
            r.get("status"),
            r.get("makespan"),
            (r.get("baseline") or {}).get("makespan"),
            (r.get("bounds") or {}).get("lower"),
            ", ".join(map(str, r.get("agents", []))),
        ]
        for r in records
    ]
    body = [table('id="schedules"', head, [row(c) for c in cells])]
    span = max((gantt.schedule_span(r) for r in records), default=0.0)
    nominal = gantt.chart_width(span, fill=True)
    for k, r in enumerate(records, 1):
        if r.get("schedule"):
            svg = gantt.gantt_svg(r, span, fill=True)
            # as wide as the page for a chart of the nominal width: every chart on the same scale
            width = f"{100 * _svg_width(svg) / nominal:.3f}%"
            attrs = f' data-goal="{esc(gantt.goal_text(r))}"'
            caption = f"<b>{esc(gantt.goal_text(r))}</b>"
            # narrowed down to the scale at which its smallest text is 8 px, then scrolled
            scale = MIN_TEXT_PX / gantt.MIN_FONT
            body.append(
                figure(svg, f"s{k}", "tree schedule", caption, attrs, width=width, back="schedules", min_scale=scale)
            )
    if timed:
        scheduling = sum(float(r.get("time_s") or 0.0) for r in records)
        body.append(
            time_line(
                [("scheduling", scheduling), ("drawing the charts", time.perf_counter() - started)],
                " (scheduling: the schedules' own times, summed; loading the data is not counted)",
            )
        )
    return body


def summary_html(
    rows: list[dict],
    report: BatchReport | None = None,
    schedules: list[dict] | None = None,
    problem: Problem | None = None,
) -> str:
    """The batch summary table, the drawing of every tree in the results and the Gantt chart of
    each of ``schedules``; with ``problem`` the drawings show kitchen items and blocking cycles."""
    top = []
    if report is not None:
        top.append(
            f"<p>{report.done} new result(s), {report.skipped} already done, with {report.workers} worker(s)"
            + (f"; results in {esc(report.output)}" if report.output else "")
            + "</p>"
        )
    body = [table('id="summary"', SUMMARY_COLUMNS, [row([summary_cell(r[c]) for c in SUMMARY_COLUMNS]) for r in rows])]
    started = time.perf_counter()
    records = report.records if report is not None else []
    trees = [r for r in records if r.get("status") in WITH_TREE and r.get("units")]
    if trees:
        draw.require_dot()
        body.append('<h2>Task trees</h2><div class="trees">')
    for k, r in enumerate(trees, 1):
        units = read_json(r["units"], "results").units
        goal = r.get("goal") or {}
        method = r.get("requested_method", r.get("method", "?"))
        marks = draw.record_marks(r, units, problem)
        svg = draw.svg_text(draw.build_graph(units, marks))
        label = f"<b>{esc(goal.get('label', '?'))}</b>: "
        body.append(
            _tree_figure(
                svg, f"r{k}", method, len(units), r.get("valid"), label, str(r.get("problem") or ""), "summary"
            )
        )
    if trees:
        body.append("</div>")
    if schedules:
        body += ["<h2>Schedules</h2>", *schedules_body(schedules, timed=False)]
    if report is not None:
        parts = [("solving", report.elapsed_s)]
        if schedules:
            parts.append(("scheduling", sum(float(s.get("time_s") or 0.0) for s in schedules)))
        top.append(
            time_line(
                parts + [("drawing this page", time.perf_counter() - started)],
                " (solving: the new results, wall clock"
                + ("; scheduling: the schedules' own times, summed" if schedules else "")
                + "; loading the data is not counted)",
            )
        )
    return page("foon2asp: batch summary", top + body)


register("compare", "html", "html")(compare_html)
register("summary", "html", "html")(summary_html)
register("schedule", "html", "html")(lambda records: page("foon2asp: schedules", schedules_body(list(records))))
