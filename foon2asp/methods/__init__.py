"""Methods: the one registry (ASP objectives and search baselines), the plan and the goal runner.

Nothing below this package imports it: :mod:`foon2asp.asp` and
:mod:`foon2asp.search` do not know they are registered here.
"""

from foon2asp.methods.registry import METHODS, get, names, register
from foon2asp.methods.runner import runner

__all__ = ["METHODS", "get", "names", "register", "runner"]
