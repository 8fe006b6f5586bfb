"""The ``foon2asp`` command line: a thin layer over :mod:`foon2asp.api`.

:mod:`~foon2asp.cli.main` holds the command group, the error handling, the exit codes, warnings
and progress bars, :mod:`~foon2asp.cli.goals` and :mod:`~foon2asp.cli.files` the commands
(importing them registers them), :mod:`~foon2asp.cli.options` the options they share.
"""

from foon2asp.cli import files, goals  # noqa: F401  (importing them registers the commands on main)
from foon2asp.cli.main import main

__all__ = ["main"]
