"""foon2asp: minimal, well-founded FOON task trees with answer-set programming.

>>> import foon2asp
>>> kb = foon2asp.load("demo")
>>> kb.solve("tomato salad").cost["units"]
4

See :mod:`foon2asp.api` and docs/api.md.
"""

__version__ = "0.2.0"

import importlib

TYPE_CHECKING = False  # typing's, without importing typing
if TYPE_CHECKING:
    from foon2asp.api import (
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
    )
    from foon2asp.api.load import load
    from foon2asp.errors import InputError
    from foon2asp.foon.model import FoonObject, Unit

__all__ = ["__version__", "load", "consolidate", "check_tree", "KnowledgeBase", "Tree", "CheckReport", "Comparison"]
__all__ += ["Missing", "Consolidation", "TreeVerdict", "Constraints", "Options", "FoonObject", "Unit", "InputError"]

#: where the exported names live: imported on first use, so that ``import foon2asp.errors`` (and the
#: command line's first moments, which take Ctrl-C) need not load the library
_HOMES = {"InputError": "foon2asp.errors", "FoonObject": "foon2asp.foon.model", "Unit": "foon2asp.foon.model"}


def __getattr__(name: str):
    """An exported name, or a submodule (as if imported), each imported on first use."""
    if name in __all__:
        value = getattr(importlib.import_module(_HOMES.get(name, "foon2asp.api")), name)
        globals()[name] = value
        return value
    if not name.startswith("__"):
        try:
            return importlib.import_module(f"{__name__}.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
