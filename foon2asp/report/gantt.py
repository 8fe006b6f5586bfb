"""Gantt charts of schedules: one lane per agent, units as boxes labelled by their motion.

Drawn from the plain JSON record of a schedule (``ScheduleResult.to_dict()``, the
shape in :mod:`foon2asp.schedule.result`), so any schedule file draws the same.
Units are coloured as in the tree drawings (:mod:`foon2asp.report.draw`): a
robot's unit is blue, a person's unit orange.  The chart is a Graphviz graph
with every node at a fixed position (``neato -n2``): the lanes' names on the
left, a time axis below, one box per unit as wide as it is long; so the
graphviz dependency renders SVG, PNG and PDF like the tree drawings.
"""

from __future__ import annotations

import html
from collections.abc import Mapping, Sequence
from pathlib import Path

import graphviz

from foon2asp.errors import InputError
from foon2asp.report.draw import BINARY, HUMAN_FILL, UNIT_FILL, format_of, require_dot
from foon2asp.report.registry import register

#: points per second of schedule at most, and the widest chart (points) a long schedule is scaled to
POINTS_PER_SECOND = 40.0
MAX_WIDTH = 1400.0
LANE_HEIGHT = 36.0
BOX_HEIGHT = 28.0
LABEL_WIDTH = 80.0
#: the narrowest box drawn (a unit of duration 0 still shows)
MIN_BOX = 3.0

LEGEND = "blue: robot · orange: person · width: duration"


def _seconds(value: object) -> float:
    return float(value) if isinstance(value, int | float) and not isinstance(value, bool) else 0.0


def _ticks(span: float) -> list[float]:
    """Round axis ticks (at most about 12) from 0 to ``span`` seconds."""
    if span <= 0:
        return [0.0]
    for step in (0.1, 0.2, 0.5, 1, 2, 5, 10, 15, 30, 60, 120, 300, 600, 1800, 3600):
        if span / step <= 12:
            break
    n = int(span / step + 1e-9)
    return [round(k * step, 3) for k in range(n + 1)]


def goal_text(record: Mapping) -> str:
    """The goal's label (a meal's labels joined by `` + ``)."""
    goal = record.get("goal") or {}
    names = [g.get("label", "?") for g in record.get("goals", [])] if "goals" in record else [goal.get("label", "?")]
    return " + ".join(str(n) for n in names)


def _title(record: Mapping) -> str:
    line = goal_text(record)
    makespan = record.get("makespan")
    line += f" -- {record.get('status', '?')}"
    if makespan is not None:
        line += f", makespan {makespan:g} s"
    baseline = (record.get("baseline") or {}).get("makespan")
    if baseline is not None:
        line += f" (list scheduling {baseline:g} s)"
    return line


def _new_graph(name: str) -> graphviz.Graph:
    g = graphviz.Graph(name, engine="neato")
    g.attr(fontname="Helvetica", outputorder="nodesfirst", pad="0.2")
    g.attr("node", fontname="Helvetica", fontsize="9", shape="box", style="filled", fixedsize="true", penwidth="0.8")
    return g


def _place(x: float, y: float, w: float, h: float) -> dict:
    return {"pos": f"{x:.2f},{y:.2f}!", "width": f"{w / 72:.4f}", "height": f"{h / 72:.4f}"}


def _text(g: graphviz.Graph, node: str, label: str, x: float, y: float, w: float, size: str, **attrs: str) -> None:
    """A line of text at a fixed place (``label`` is HTML-like, already escaped)."""
    # not fixedsize: a title longer than a short chart widens its node instead of being cut
    g.node(
        node,
        f"<{label}>",
        shape="plaintext",
        style="",
        fontsize=size,
        fixedsize="false",
        **attrs,
        **_place(x, y, w, 14),
    )


def add_chart(g: graphviz.Graph, record: Mapping, prefix: str = "", top: float = 0.0) -> float:
    """Add the chart of one schedule record to ``g``, its title at height ``top``; the height used."""
    agents = [str(a) for a in record.get("agents", [])]
    entries = list(record.get("schedule") or [])
    span = max((_seconds(e.get("end")) for e in entries), default=0.0)
    scale = POINTS_PER_SECOND if span * POINTS_PER_SECOND <= MAX_WIDTH else MAX_WIDTH / max(span, 1e-9)
    width = LABEL_WIDTH + max(span * scale, 200.0)
    _text(g, f"{prefix}title", html.escape(_title(record)), width / 2, top, width, "12")
    _text(g, f"{prefix}legend", html.escape(LEGEND), width / 2, top - 14, width, "8")
    lane = {a: k for k, a in enumerate(agents)}

    def y(k: int) -> float:
        return top - 30 - LANE_HEIGHT * k - LANE_HEIGHT / 2

    for k, agent in enumerate(agents):
        _text(g, f"{prefix}lane{k}", html.escape(agent), LABEL_WIDTH / 2, y(k), LABEL_WIDTH, "11")
    for i, e in enumerate(entries):
        agent = str(e.get("agent"))
        if agent not in lane:
            continue
        start, end = _seconds(e.get("start")), _seconds(e.get("end"))
        w = max(MIN_BOX, (end - start) * scale)
        unit = e.get("unit") if isinstance(e.get("unit"), Mapping) else {}
        motion = str(unit.get("motion", "?"))
        human = agent.rsplit("-", 1)[0] == "human"
        outs = "; ".join(str(o.get("label", "")) for o in unit.get("outputs", []) if isinstance(o, Mapping))
        g.node(
            f"{prefix}u{i}",
            f"<{html.escape(motion)}>" if w >= 6.5 * len(motion) + 4 else "",
            fillcolor=HUMAN_FILL if human else UNIT_FILL,
            tooltip=f"{motion} ({agent}, {start:g}-{end:g} s) -> {outs}".replace("\\", "\\\\"),
            **{"class": "unit human" if human else "unit"},
            **_place(LABEL_WIDTH + (start + end) / 2 * scale, y(lane[agent]), w, BOX_HEIGHT),
        )
    bottom = y(len(agents) - 1) - LANE_HEIGHT / 2 - 8
    for j, t in enumerate(_ticks(span)):
        _text(g, f"{prefix}t{j}", f"{t:g}", LABEL_WIDTH + t * scale, bottom, 30, "8")
    _text(g, f"{prefix}axis", "s", LABEL_WIDTH - 20, bottom, 30, "8")
    return top - bottom + 20


def gantt_graph(record: Mapping) -> graphviz.Graph:
    """The chart of one schedule record as a Graphviz graph with fixed node positions."""
    g = _new_graph("schedule")
    add_chart(g, record)
    return g


def charts(records: Sequence[Mapping]) -> graphviz.Graph:
    """The charts of several schedule records, one under the other, in one graph."""
    g = _new_graph("schedules")
    top = 0.0
    for k, record in enumerate(records):
        top -= add_chart(g, record, f"s{k}_", top) + 20
    return g


def render(graph: graphviz.Graph, fmt: str) -> bytes:
    """``graph`` as ``fmt``: ``dot`` source, or svg/png/pdf at its fixed positions (``neato -n2``)."""
    if fmt == "dot":
        return graph.source.encode("utf-8")
    require_dot()
    try:
        return graph.pipe(format=fmt, neato_no_op=2)
    except graphviz.ExecutableNotFound:
        raise InputError("Graphviz is not installed: install it (Debian: apt-get install graphviz)") from None
    except graphviz.CalledProcessError as exc:
        err = (exc.stderr or b"").decode("utf-8", "replace").strip().splitlines()
        raise InputError(f"Graphviz 'neato' failed: {err[-1] if err else exc}") from None


def gantt_svg(record: Mapping) -> str:
    """The chart of one schedule as an SVG document."""
    return render(gantt_graph(record), "svg").decode("utf-8")


def draw_gantt(record: Mapping, path: str | Path) -> Path:
    """Write the chart of ``record`` to ``path``; the format follows the extension (.svg, .png, .pdf, .dot)."""
    path = Path(path)
    path.write_bytes(render(gantt_graph(record), format_of(path)))
    return path


def _chart(fmt: str):
    def render_chart(records: Sequence[Mapping]) -> str | bytes:
        out = render(charts(list(records)), fmt)
        return out if fmt in BINARY else out.decode("utf-8")

    return render_chart


for _fmt, _what in (
    ("dot", "Graphviz source of the Gantt chart"),
    ("svg", "the Gantt chart as SVG (needs Graphviz)"),
    ("png", "the Gantt chart as PNG (needs Graphviz)"),
    ("pdf", "the Gantt chart as PDF (needs Graphviz)"),
):
    register("schedule", _fmt, _fmt, _what, binary=_fmt in BINARY)(_chart(_fmt))
