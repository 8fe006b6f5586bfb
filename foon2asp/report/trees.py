"""Task trees as text, JSON or FOON text (the formats of ``solve --format``)."""

from __future__ import annotations

import json

from foon2asp.foon.problem import Problem
from foon2asp.report.registry import get, register
from foon2asp.tree.serialize import to_json, tree_foon, tree_json, tree_text
from foon2asp.tree.tasktree import TaskTree


@register("trees", "text", "txt", "readable steps")
def trees_text(problem: Problem, trees: list[TaskTree]) -> str:
    return "\n".join(tree_text(problem, t) for t in trees)


@register("trees", "json", "json", "a list of results in the stable JSON shape")
def trees_json(problem: Problem, trees: list[TaskTree]) -> str:
    return to_json(problem, trees) + "\n"


@register("trees", "foon", "foon.txt", "FOON text, units separated by //")
def trees_foon(problem: Problem, trees: list[TaskTree]) -> str:
    return "".join(tree_foon(problem, t) for t in trees)


@register("trees", "jsonl", "jsonl", "JSON lines: one result per line, written as each goal is solved")
def trees_jsonl(problem: Problem, trees: list[TaskTree]) -> str:
    return "".join(json.dumps(tree_json(problem, t), ensure_ascii=False) + "\n" for t in trees)


def render(problem: Problem, trees: list[TaskTree], fmt: str) -> str:
    """``trees`` in format ``fmt`` (a name of :func:`foon2asp.report.names` ``("trees")``)."""
    return get("trees", fmt).render(problem, trees)
