"""The ``foon2asp`` command line: a thin layer over :mod:`foon2asp.api`."""

from foon2asp.cli import explore_command, file_commands, goal_commands  # noqa: F401  (importing them registers the commands on main)
from foon2asp.cli.main import main

__all__ = ["main"]
