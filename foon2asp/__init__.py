"""foon2asp: minimal, well-founded FOON task trees with answer-set programming.

>>> import foon2asp
>>> kb = foon2asp.load("demo")
>>> kb.solve("tomato salad").cost["units"]
4

See :mod:`foon2asp.api` and docs/api.md.
"""

__version__ = "0.2.0"

from foon2asp.api import (  # noqa: E402
    CheckReport,
    Comparison,
    Consolidation,
    Constraints,
    KnowledgeBase,
    Missing,
    Options,
    Tree,
    TreeVerdict,
    check_tree,
    consolidate,
    load,
)
from foon2asp.errors import InputError  # noqa: E402
from foon2asp.foon.model import FoonObject, Unit  # noqa: E402

__all__ = ["__version__", "load", "consolidate", "check_tree", "KnowledgeBase", "Tree", "CheckReport", "Comparison"]
__all__ += ["Missing", "Consolidation", "TreeVerdict", "Constraints", "Options", "FoonObject", "Unit", "InputError"]
