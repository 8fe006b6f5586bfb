"""Task trees as pictures, in FOON's own drawing conventions.

Objects are ellipses, functional units boxes, edges run input -> motion -> output; what is
highlighted is a :class:`Marks`.  Rendering to SVG, PNG or PDF runs Graphviz.
"""

from __future__ import annotations

import re
import shutil
import textwrap
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from html import escape
from pathlib import Path

import graphviz

from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.problem import Problem
from foon2asp.foon.treefiles import TreeFile
from foon2asp.outcomes import Report, record_object
from foon2asp.report.formats import register
from foon2asp.tree.tasktree import TaskTree
from foon2asp.tree.validate import Finding, check_units

#: drawing formats and what ``dot`` calls them
FORMATS = ("dot", "svg", "png", "pdf")
BINARY = ("png", "pdf")

GOAL_FILL = "#ffd966"
KITCHEN_FILL = "#d9ead3"
UNIT_FILL = "#cfe2f3"
HUMAN_FILL = "#f9cb9c"
CYCLE = "#cc0000"

LEGEND = "gold: goal · green: in the kitchen · box: functional unit · orange: human step · red: blocking cycle"


@dataclass
class Marks:
    """What a drawing highlights (unit positions index the drawn list of units)."""

    title: str = ""
    #: the goals (gold)
    goals: frozenset[FoonObject] = frozenset()
    kitchen: frozenset[FoonObject] = frozenset()
    human: frozenset[int] = frozenset()
    #: the blocking cycle: (object, position of the unit that makes it and needs the next pair's
    #: object, None when it is not drawn); the last unit needs the first object
    cycle: tuple[tuple[FoonObject, int | None], ...] = ()
    #: one line under the title (e.g. the problem of an invalid tree)
    note: str = ""
    #: unit position -> fill colours (several: the box is striped, one stripe each; e.g. its sources)
    unit_colors: dict[int, tuple[str, ...]] = field(default_factory=dict)
    #: unit position -> a line added to its tooltip
    unit_notes: dict[int, str] = field(default_factory=dict)
    legend: str = LEGEND


#: texts in a drawing are clipped to these lengths (Graphviz refuses very long strings)
MAX_TEXT = 200
MAX_ROWS = 12
MAX_TOOLTIP = 2000


def _clip(text: str, limit: int = MAX_TEXT) -> str:
    """``text``, cut to ``limit`` characters with an ellipsis when longer."""
    return text if len(text) <= limit else text[: limit - 1] + "\u2026"


def object_label(obj: FoonObject) -> str:
    """An HTML-like Graphviz label: the label in bold, then states, ingredients, container."""
    rows = [f"<B>{escape(_clip(obj.label))}</B>"]
    states = list(obj.states)
    rows += [escape(_clip(s)) for s in states[:MAX_ROWS]]
    if len(states) > MAX_ROWS:
        rows.append(escape(f"\u2026 {len(states) - MAX_ROWS} more states"))
    if obj.ingredients:
        rows.append(escape(_clip("{" + ", ".join(obj.ingredients) + "}", 4 * MAX_TEXT)))
    if obj.container:
        rows.append(escape(f"[{_clip(obj.container)}]"))
    return "<" + "<BR/>".join(rows) + ">"


def build_graph(units: list[Unit], marks: Marks, name: str = "task_tree", prefix: str = "") -> graphviz.Digraph:
    """The drawing of ``units`` (in executable order) as a Graphviz graph (node names start with ``prefix``)."""
    g = graphviz.Digraph(name)
    g.attr(rankdir="TB", fontname="Helvetica", fontsize="12", labelloc="t", nodesep="0.25", ranksep="0.35")
    title = [escape(_clip(marks.title, MAX_TOOLTIP))] if marks.title else []
    note = textwrap.wrap(
        " ".join(_clip(marks.note, MAX_TOOLTIP).split()), 90, break_long_words=False, break_on_hyphens=False
    )
    title += [f'<FONT COLOR="{CYCLE}">{escape(line)}</FONT>' for line in note]
    title.append(f'<FONT POINT-SIZE="9">{escape(marks.legend)}</FONT>')
    g.attr(label="<" + "<BR/>".join(title) + ">")
    g.attr("node", fontname="Helvetica", fontsize="10")
    g.attr("edge", arrowsize="0.6")
    cycle = marks.cycle
    made = {(k, o) for o, k in cycle if k is not None}
    needed = {(cycle[(i + 1) % len(cycle)][0], k) for i, (_, k) in enumerate(cycle) if k is not None}
    ids: dict[FoonObject, str] = {}
    for unit in units:
        for obj in unit.inputs + unit.outputs:
            if obj not in ids:
                ids[obj] = f"{prefix}o{len(ids) + 1}"
    for obj, node in ids.items():
        attrs = {"shape": "ellipse", "style": "filled", "fillcolor": "white", "margin": "0.05,0.02"}
        classes = ["object"]
        if obj in marks.kitchen:
            attrs["fillcolor"] = KITCHEN_FILL
            classes.append("kitchen")
        if obj in marks.goals:
            attrs.update(fillcolor=GOAL_FILL, peripheries="2", penwidth="2")
            classes.append("goal")
        if any(obj == o for o, _ in cycle):
            attrs.update(color=CYCLE, penwidth="2.5", fontcolor=CYCLE)
            classes.append("cycle")
        g.node(node, object_label(obj), tooltip=_clip(str(obj), MAX_TOOLTIP), **{"class": " ".join(classes)}, **attrs)
    for k, unit in enumerate(units):
        node = f"{prefix}u{k + 1}"
        text = f"{k + 1}. {_clip(unit.motion)}"
        attrs = {"shape": "box", "style": "filled", "fillcolor": UNIT_FILL}
        classes = ["unit"]
        colors = marks.unit_colors.get(k)
        if colors:
            attrs["fillcolor"] = ":".join(colors)
            if len(colors) > 1:
                attrs["style"] = "striped"
        if k in marks.human:
            text += "\n[human]"
            attrs.update(fillcolor=HUMAN_FILL, style="filled")
            classes.append("human")
        if any(k == p for _, p in cycle):
            attrs.update(color=CYCLE, penwidth="2.5", fontcolor=CYCLE)
            classes.append("cycle")
        tip = str(unit) + (f" -- {marks.unit_notes[k]}" if k in marks.unit_notes else "")
        g.node(node, text, tooltip=_clip(tip, MAX_TOOLTIP), **{"class": " ".join(classes)}, **attrs)
        edges = [(ids[o], node, (o, k) in needed) for o in dict.fromkeys(unit.inputs)]
        edges += [(node, ids[o], (k, o) in made) for o in dict.fromkeys(unit.outputs)]
        for tail, head, red in edges:
            g.edge(tail, head, **({"color": CYCLE, "penwidth": "2.5"} if red else {}))
    return g


def checked_marks(
    problem: Problem,
    title: str,
    goals: Iterable[FoonObject],
    units: list[Unit],
    ids: list[int | None],
    finding: Finding | None,
) -> Marks:
    """Marks of ``units`` checked against ``problem`` (``ids``: their FOON unit ids, None when not
    in the FOON): the kitchen items, and the problem and blocking cycle of ``finding``."""
    position = {u: k for k, u in enumerate(ids) if u is not None}
    return Marks(
        title=title,
        goals=frozenset(goals),
        kitchen=frozenset(o for u in units for o in u.inputs if problem.foon.object_ids.get(o) in problem.kitchen),
        note=finding.message if finding is not None else "",
        cycle=tuple((problem.objects[o], position.get(u)) for o, u in finding.cycle) if finding else (),
    )


def tree_marks(problem: Problem, tree: TaskTree) -> Marks:
    """Marks of a solved tree: goals, kitchen items, human steps, and its blocking cycle."""
    finding = None
    for goal in tree.meal if tree.units else ():  # a meal is valid when every dish is made
        _, finding = check_units(problem, goal, tree.units)
        if finding is not None:
            break
    title = f"{problem.objects[tree.goal]} -- {tree.method}, {tree.status}, {len(tree.units)} units"
    title += ", INVALID" if finding else ""
    units = [problem.units[u] for u in tree.units]
    marks = checked_marks(problem, title, [problem.objects[g] for g in tree.meal], units, list(tree.units), finding)
    human = set(tree.human_steps or ())
    marks.human = frozenset(k for k, u in enumerate(tree.units) if u in human)
    return marks


def _graph(drawings: list[tuple[list[Unit], Marks]]) -> graphviz.Digraph:
    """One drawing (units, marks) as a graph; several as one graph with a cluster each."""
    if len(drawings) == 1:
        return build_graph(*drawings[0])
    g = graphviz.Digraph("task_trees")
    g.attr(fontname="Helvetica")
    for k, (units, marks) in enumerate(drawings, 1):
        g.subgraph(build_graph(units, marks, f"cluster_{k}", f"t{k}_"))
    return g


def trees_graph(problem: Problem, trees: list[TaskTree]) -> graphviz.Digraph:
    """One tree as a graph; several as one graph with a cluster per tree."""
    return _graph([([problem.units[u] for u in t.units], tree_marks(problem, t)) for t in trees])


def _top_product(units: list[Unit]) -> list[FoonObject]:
    """Without data: the one product of the last unit that no unit of the tree needs (none or one)."""
    if not units:
        return []
    needed = {o for u in units for o in u.inputs}
    tops = [o for o in dict.fromkeys(units[-1].outputs) if not o.is_bare() and o not in needed]
    return tops if len(tops) == 1 else []


def record_marks(record: dict, units: list[Unit], problem: Problem | None = None) -> Marks:
    """Marks of a result record (a line of a batch's results) whose units are ``units``: its goals
    and verdict; with ``problem`` also its kitchen items and an invalid tree's blocking cycle."""
    goals = [g for g in (record.get("goals") or [record.get("goal")]) if isinstance(g, dict)]
    made = [o for o in map(record_object, goals) if o is not None]
    label = " + ".join(str(g.get("label", "?")) for g in goals) or "?"
    method = record.get("requested_method", record.get("method", "?"))
    title = f"{label} -- {method}, {record.get('status')}, {len(units)} units"
    title += ", INVALID" if record.get("valid") is False else ""
    note = str(record.get("problem") or "")
    if problem is None:
        return Marks(title=title, goals=frozenset(made or _top_product(units)), note=note)
    ids = [problem.foon.unit_id(u) for u in units]
    oid = problem.foon.object_ids
    finding = None
    if record.get("valid") is False and None not in ids:
        known = [u for u in ids if u is not None]
        found = (check_units(problem, oid[g], known)[1] for g in made if g in oid)
        finding = next((f for f in found if f is not None and f.cycle), None)
    marks = checked_marks(problem, title, made or _top_product(units), units, ids, finding)
    marks.note = note
    return marks


def tree_file_marks(tree: TreeFile, problem: Problem | None = None, report: Report | None = None) -> Marks:
    """Marks of a tree read from a file; with ``problem`` and its ``report``: goal, kitchen items,
    verdict and cycle."""
    units = [tu.unit for tu in tree.units]
    if problem is None or report is None:
        top = [tree.goal] if tree.goal else _top_product(units)
        return Marks(title=f"{top[0] if top else tree.path} -- {len(units)} units", goals=frozenset(top))
    goal = problem.objects[report.meal[0]]
    title = f"{goal} -- {len(units)} units, {'valid' if report.valid else 'INVALID'}"
    return checked_marks(problem, title, [goal], units, report.ids, report.finding)


def file_graph(
    trees: list[TreeFile], reports: list[Report] | None = None, problem: Problem | None = None
) -> graphviz.Digraph:
    """The drawing of the trees of a tree file (a cluster per tree when there are several), with
    their verdicts when ``reports`` are given."""
    return _graph(
        [
            ([tu.unit for tu in t.units], tree_file_marks(t, problem, reports[k] if reports else None))
            for k, t in enumerate(trees)
        ]
    )


def require_dot() -> None:
    """Fail with one line when Graphviz's ``dot`` is not installed."""
    if shutil.which("dot") is None:
        raise InputError(
            "Graphviz 'dot' is not installed: install it (Debian: apt-get install graphviz) to draw task trees"
        )


def render(graph: graphviz.Graph | graphviz.Digraph, fmt: str) -> bytes:
    """``graph`` as ``fmt``: ``dot`` source, or svg/png/pdf laid out by its engine (``neato``: at
    the nodes' fixed positions)."""
    if fmt == "dot":
        return graph.source.encode("utf-8")
    if fmt not in FORMATS:
        raise InputError(f"unknown drawing format {fmt!r} (have {', '.join(FORMATS)})")
    require_dot()
    engine = graph.engine
    try:
        if engine == "neato":
            return graph.pipe(format=fmt, neato_no_op=2)
        return graph.pipe(format=fmt, quiet=True)
    except graphviz.ExecutableNotFound:
        raise InputError(
            f"Graphviz '{engine}' is not installed: install it (Debian: apt-get install graphviz)"
        ) from None
    except graphviz.CalledProcessError as exc:
        err = (exc.stderr or b"").decode("utf-8", "replace").strip().splitlines()
        raise InputError(f"Graphviz '{engine}' failed: {err[-1] if err else exc}") from None


def register_pictures(kind: str, picture: Callable[..., bytes]) -> None:
    """Register the formats dot, svg, png and pdf of answers of ``kind``, ``picture(fmt, *answer)`` rendering one."""
    for fmt in FORMATS:

        def render_picture(*answer: object, fmt: str = fmt) -> str | bytes:
            out = picture(fmt, *answer)
            return out if fmt in BINARY else out.decode("utf-8")

        register(kind, fmt, fmt, binary=fmt in BINARY)(render_picture)


def svg_text(graph: graphviz.Graph | graphviz.Digraph) -> str:
    return render(graph, "svg").decode("utf-8")


def inline_svg(svg: str, prefix: str) -> str:
    """An SVG document as an element to put in HTML: no XML prolog, ids made unique with ``prefix``."""
    start = svg.find("<svg")
    svg = svg[start:] if start >= 0 else svg
    svg = re.sub(r'\bid="([^"]*)"', lambda m: f'id="{prefix}{m.group(1)}"', svg)
    return re.sub(r'href="#([^"]*)"', lambda m: f'href="#{prefix}{m.group(1)}"', svg)


def format_of(path: str | Path) -> str:
    """The drawing format of a file name (``.svg``, ``.png``, ``.pdf``, ``.dot``/``.gv``)."""
    ext = Path(path).suffix.lower().lstrip(".")
    ext = "dot" if ext == "gv" else ext
    if ext not in FORMATS:
        raise InputError(f"cannot tell the drawing format from {str(path)!r}: use .svg, .png, .pdf or .dot")
    return ext


def tree_svg(problem: Problem, tree: TaskTree) -> str:
    """The drawing of ``tree`` as an SVG document (for ``_repr_svg_`` in notebooks)."""
    return svg_text(trees_graph(problem, [tree]))


def draw_tree(problem: Problem, tree: TaskTree, path: str | Path) -> Path:
    """Write the drawing of ``tree`` to ``path``; the format follows the extension."""
    path = Path(path)
    path.write_bytes(render(trees_graph(problem, [tree]), format_of(path)))
    return path
