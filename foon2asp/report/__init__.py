"""Every output format, in one registry (:mod:`foon2asp.report.registry`).

Importing this package registers the formats of every kind of answer.
"""

from foon2asp.report import check, compare, consolidate, draw, gantt, html, pddl, queries, trees
from foon2asp.report.registry import FORMATS, Format, get, names, register, render, render_bytes

__all__ = ["FORMATS", "Format", "get", "names", "register", "render", "render_bytes"]
__all__ += ["check", "compare", "consolidate", "draw", "gantt", "html", "pddl", "queries", "trees"]
