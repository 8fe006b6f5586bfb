"""Gantt charts of schedules: one lane per agent, units as boxes labelled by their motion.

Drawn from a schedule's JSON record (``ScheduleResult.to_dict()``) as a Graphviz graph whose
nodes sit at fixed positions; charts drawn together share one time scale.
"""

from __future__ import annotations

import html
from collections.abc import Mapping, Sequence
from pathlib import Path

import graphviz

from foon2asp.report.draw import HUMAN_FILL, UNIT_FILL, format_of, register_pictures, render, svg_text

#: points per second of schedule at most, and the widest chart (points) a long schedule is scaled to
POINTS_PER_SECOND = 40.0
MAX_WIDTH = 1400.0
LANE_HEIGHT = 36.0
BOX_HEIGHT = 28.0
LABEL_WIDTH = 80.0
#: the narrowest box drawn (a unit of duration 0 still shows)
MIN_BOX = 3.0
#: font size (points) of a box's label, of a label beside or under a short box, and of the axis
#: and the legend; the height of a row of labels under a lane.  No text is smaller than
#: :data:`MIN_FONT`, so that a page showing a chart at 0.8 px per point shows its text at 8 px
BOX_FONT = 10.0
SIDE_FONT = 10.0
AXIS_FONT = 10.0
MIN_FONT = min(BOX_FONT, SIDE_FONT, AXIS_FONT)
ROW_HEIGHT = 13.0
#: the margin around a chart, and right of the time axis (half the width of its last number) (points)
PAD = 14.4
RIGHT_MARGIN = 15.0

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
    g.attr(fontname="Helvetica", outputorder="nodesfirst", pad=f"{PAD / 72:g}")
    g.attr(
        "node",
        fontname="Helvetica",
        fontsize=f"{BOX_FONT:g}",
        shape="box",
        style="filled",
        fixedsize="true",
        penwidth="0.8",
    )
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


def schedule_span(record: Mapping) -> float:
    """The seconds from 0 to the end of the last unit of a schedule record."""
    return max((_seconds(e.get("end")) for e in record.get("schedule") or []), default=0.0)


def time_scale(span: float, fill: bool = False) -> float:
    """Points per second of a chart spanning ``span`` seconds: :data:`POINTS_PER_SECOND`, at most
    :data:`MAX_WIDTH` wide; ``fill``: exactly that wide."""
    if fill or span * POINTS_PER_SECOND > MAX_WIDTH:
        return MAX_WIDTH / span if span > 0 else POINTS_PER_SECOND
    return POINTS_PER_SECOND


def chart_width(span: float, fill: bool = False) -> float:
    """The width (points) of a chart whose time axis spans ``span`` seconds, lane names and margins
    included: every text of the chart lies within it."""
    return LABEL_WIDTH + max(span * time_scale(span, fill), 200.0) + RIGHT_MARGIN + 2 * PAD


def _unit(entry: Mapping) -> Mapping:
    """The unit of a schedule entry (empty when the record has none)."""
    unit = entry.get("unit")
    return unit if isinstance(unit, Mapping) else {}


def _text_width(text: str, size: float) -> float:
    """A generous estimate of the width (points) of ``text`` in Helvetica of ``size`` points."""
    return 0.72 * size * len(text) + 4


def _label_places(
    boxes: list[tuple[float, float, str]], limit: float = float("inf")
) -> tuple[list[tuple[str, float, int]], int]:
    """Where the label of each box (left, right, text) of one lane goes: ``("in", 0, 0)``,
    ``("beside", x, 0)`` or ``("under", x, row)``, no label reaching past ``limit``; and the
    number of rows under the lane."""
    rows: list[float] = []  # where each row under the lane is free again
    order = sorted(range(len(boxes)), key=lambda i: boxes[i][0])
    found: dict[int, tuple[str, float, int]] = {}
    for n, i in enumerate(order):
        left, right, text = boxes[i]
        if right - left >= _text_width(text, BOX_FONT):
            found[i] = ("in", 0.0, 0)
            continue
        need = _text_width(text, SIDE_FONT)
        following = [boxes[j][0] for j in order[n + 1 :] if boxes[j][0] >= right - 1e-6]
        if min([*following, limit + 2]) - right >= need + 2:
            found[i] = ("beside", right + 2, 0)
            continue
        need = _text_width("^ " + text, SIDE_FONT)
        x = max(0.0, min(left, limit - need))  # a label under a box near the end ends at the limit
        row = next((r for r, free in enumerate(rows) if free <= x), len(rows))
        if row == len(rows):
            rows.append(0.0)
        rows[row] = x + need + 2
        found[i] = ("under", x, row)
    places = [found[i] for i in range(len(boxes))]
    return places, len(rows)


def add_chart(
    g: graphviz.Graph,
    record: Mapping,
    prefix: str = "",
    top: float = 0.0,
    span: float | None = None,
    fill: bool = False,
) -> float:
    """Add the chart of one schedule record to ``g``, its title at height ``top``; the height used.
    ``span``: the seconds the time axis covers (default: this schedule's); ``fill``: see :func:`time_scale`."""
    agents = [str(a) for a in record.get("agents", [])]
    entries = list(record.get("schedule") or [])
    span = schedule_span(record) if span is None else max(span, schedule_span(record))
    scale = time_scale(span, fill)
    width = chart_width(span, fill) - 2 * PAD
    _text(g, f"{prefix}title", html.escape(_title(record)), width / 2, top, width, "12")
    _text(g, f"{prefix}legend", html.escape(LEGEND), width / 2, top - 15, width, f"{AXIS_FONT:g}")
    lane = {a: k for k, a in enumerate(agents)}

    boxes: list[tuple[int, int, float, float, str, str, bool]] = []  # entry, lane, left, right, motion, tooltip, human
    for i, e in enumerate(entries):
        agent = str(e.get("agent"))
        if agent not in lane:
            continue
        start, end = _seconds(e.get("start")), _seconds(e.get("end"))
        w = max(MIN_BOX, (end - start) * scale)
        middle = LABEL_WIDTH + (start + end) / 2 * scale
        unit = _unit(e)
        motion = str(unit.get("motion", "?"))
        outs = "; ".join(str(o.get("label", "")) for o in unit.get("outputs", []) if isinstance(o, Mapping))
        tooltip = f"{motion} ({agent}, {start:g}-{end:g} s) -> {outs}".replace("\\", "\\\\")
        human = agent.rsplit("-", 1)[0] == "human"
        boxes.append((i, lane[agent], middle - w / 2, middle + w / 2, motion, tooltip, human))
    places: dict[int, tuple[str, float, int]] = {}
    rows = [0] * len(agents)
    for k in range(len(agents)):
        mine = [b for b in boxes if b[1] == k]
        found, rows[k] = _label_places([(b[2], b[3], b[4]) for b in mine], width)
        places.update({b[0]: p for b, p in zip(mine, found)})
    lane_tops = [top - 30.0]
    for k in range(len(agents)):
        lane_tops.append(lane_tops[-1] - LANE_HEIGHT - ROW_HEIGHT * rows[k])

    def y(k: int) -> float:
        return lane_tops[k] - LANE_HEIGHT / 2

    for k, agent in enumerate(agents):
        _text(g, f"{prefix}lane{k}", html.escape(agent), LABEL_WIDTH / 2, y(k), LABEL_WIDTH, "11")
    for i, k, left, right, motion, tooltip, human in boxes:
        where, x, row = places[i]
        g.node(
            f"{prefix}u{i}",
            f"<{html.escape(motion)}>" if where == "in" else "",
            fillcolor=HUMAN_FILL if human else UNIT_FILL,
            tooltip=tooltip,
            fontsize=f"{BOX_FONT:g}",
            **{"class": "unit human" if human else "unit"},
            **_place((left + right) / 2, y(k), right - left, BOX_HEIGHT),
        )
        if where == "in":
            continue
        text = motion if where == "beside" else "^ " + motion
        need = _text_width(text, SIDE_FONT)
        height = y(k) if where == "beside" else lane_tops[k] - LANE_HEIGHT - ROW_HEIGHT * row - ROW_HEIGHT / 2 + 3
        # a left-aligned cell exactly as wide as the estimate: the text starts at x
        cell = (
            f'<TABLE BORDER="0" CELLBORDER="0" CELLPADDING="0" CELLSPACING="0" FIXEDSIZE="TRUE"'
            f' WIDTH="{need:.0f}" HEIGHT="{ROW_HEIGHT - 1:.0f}"><TR><TD ALIGN="LEFT">{html.escape(text)}</TD></TR></TABLE>'
        )
        attrs = {"tooltip": tooltip, "class": f"label {where}"}
        _text(g, f"{prefix}u{i}label", cell, x + need / 2, height, need, f"{SIDE_FONT:g}", **attrs)
    bottom = lane_tops[len(agents)] - 8 if agents else top - 38
    for j, t in enumerate(_ticks(span)):
        _text(g, f"{prefix}t{j}", f"{t:g}", LABEL_WIDTH + t * scale, bottom, 2 * RIGHT_MARGIN, f"{AXIS_FONT:g}")
    _text(g, f"{prefix}axis", "s", LABEL_WIDTH - 20, bottom, 2 * RIGHT_MARGIN, f"{AXIS_FONT:g}")
    return top - bottom + 20


def gantt_graph(record: Mapping, span: float | None = None, fill: bool = False) -> graphviz.Graph:
    """The chart of one schedule record as a Graphviz graph (``span``, ``fill``: as :func:`add_chart`)."""
    g = _new_graph("schedule")
    add_chart(g, record, span=span, fill=fill)
    return g


def charts(records: Sequence[Mapping]) -> graphviz.Graph:
    """The charts of several schedule records, one under the other, in one graph, on one time scale."""
    g = _new_graph("schedules")
    span = max((schedule_span(r) for r in records), default=0.0)
    top = 0.0
    for k, record in enumerate(records):
        top -= add_chart(g, record, f"s{k}_", top, span) + 20
    return g


def gantt_svg(record: Mapping, span: float | None = None, fill: bool = False) -> str:
    """The chart of one schedule as an SVG document (``span``, ``fill``: as :func:`add_chart`)."""
    return svg_text(gantt_graph(record, span, fill))


def draw_gantt(record: Mapping, path: str | Path) -> Path:
    """Write the chart of ``record`` to ``path``; the format follows the extension (.svg, .png, .pdf, .dot)."""
    path = Path(path)
    path.write_bytes(render(gantt_graph(record), format_of(path)))
    return path


register_pictures("schedule", lambda fmt, records: render(charts(list(records)), fmt))
