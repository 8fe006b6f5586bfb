"""Every output format, in one registry (:mod:`foon2asp.report.formats`).

Importing this package registers the formats of every kind of answer.
"""

from foon2asp.report import candidates, draw, gantt, html, pddl, query_answers, tables, tree_formats, verdicts
from foon2asp.report.formats import FORMATS, Format, get, names, register, render, render_bytes

__all__ = ["FORMATS", "Format", "get", "names", "register", "render", "render_bytes"]
__all__ += ["verdicts", "tables", "candidates", "draw", "gantt", "html", "pddl", "query_answers", "tree_formats"]
