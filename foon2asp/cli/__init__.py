"""The ``foon2asp`` command line: a thin layer over :mod:`foon2asp.api`."""

from foon2asp.cli import objects  # noqa: F401  (registers the command on main)
from foon2asp.cli.main import main

__all__ = ["main"]
