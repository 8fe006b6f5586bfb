"""Task trees as text, JSON, FOON text or JSON, the unit-list JSON of generated trees, and
drawings (the formats of ``solve --format``)."""

from __future__ import annotations

import json

from foon2asp.foon.problem import Problem
from foon2asp.foon.unitlist import dumps_trees
from foon2asp.report import draw, formats
from foon2asp.report.formats import register
from foon2asp.tree.serialize import to_json, tree_foon, tree_foon_json, tree_json, tree_text
from foon2asp.tree.tasktree import TaskTree

register("trees", "text", "txt")(lambda problem, trees: "\n".join(tree_text(problem, t) for t in trees))
register("trees", "json", "json")(lambda problem, trees: to_json(problem, trees) + "\n")
register("trees", "foon", "foon.txt")(lambda problem, trees: "".join(tree_foon(problem, t) for t in trees))
register("trees", "foon-plain", "foon.txt")(
    lambda problem, trees: "".join(tree_foon(problem, t, "plain") for t in trees)
)


@register("trees", "foon-json", "foon.json")
def _foon_json(problem: Problem, trees: list[TaskTree]) -> str:
    docs = [tree_foon_json(problem, t) for t in trees]
    return json.dumps(docs[0] if len(docs) == 1 else docs, indent=1) + "\n"


register("trees", "units-json", "json")(
    lambda problem, trees: dumps_trees([[problem.units[u] for u in t.units] for t in trees])
)
draw.register_pictures("trees", lambda fmt, problem, trees: draw.render(draw.trees_graph(problem, trees), fmt))
register("trees", "jsonl", "jsonl")(
    lambda problem, trees: "".join(json.dumps(tree_json(problem, t), ensure_ascii=False) + "\n" for t in trees)
)


def render(problem: Problem, trees: list[TaskTree], fmt: str) -> str:
    """``trees`` in the text format ``fmt`` (a name of :func:`foon2asp.report.names` ``("trees")``)."""
    return formats.render("trees", fmt, problem, trees)


def render_bytes(problem: Problem, trees: list[TaskTree], fmt: str) -> bytes:
    """``trees`` in format ``fmt`` as bytes (text formats as UTF-8)."""
    return formats.render_bytes("trees", fmt, problem, trees)
