"""Methods: the one registry (ASP objectives and search baselines) and the goal runner.

Nothing below this package imports it: :mod:`foon2asp.asp` and
:mod:`foon2asp.search` do not know they are registered here.
"""

from foon2asp.methods.registry import (
    METHODS,
    Factory,
    Method,
    Runner,
    effective_options,
    get,
    names,
    register,
    runner,
)

__all__ = ["METHODS", "Factory", "Method", "Runner", "effective_options", "get", "names", "register", "runner"]
