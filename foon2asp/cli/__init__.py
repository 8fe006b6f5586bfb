"""The ``foon2asp`` command line: a thin layer over :mod:`foon2asp.api`."""

from foon2asp.cli import (
    draw,  # noqa: F401  (registers the command)
    export,  # noqa: F401  (registers 'export')
    objects,  # noqa: F401  (registers the command on main)
)
from foon2asp.cli.main import main

__all__ = ["main"]
