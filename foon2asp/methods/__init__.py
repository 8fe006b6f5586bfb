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
    register_asp,
)
from foon2asp.methods.runner import GoalRunner, runner, solve_goals

__all__ = [
    "METHODS",
    "Factory",
    "GoalRunner",
    "Method",
    "Runner",
    "effective_options",
    "get",
    "names",
    "register",
    "register_asp",
    "runner",
    "solve_goals",
]
