"""The ``foon2asp`` command line: a thin layer over :mod:`foon2asp.api`.

:mod:`~foon2asp.cli.main` holds the command group and the error handling; each command is a
module here (importing it registers the command); :mod:`~foon2asp.cli.options` declares the
shared options once, :mod:`~foon2asp.cli.params` the checked option types and
:mod:`~foon2asp.cli.output` the exit codes, warnings and progress bars.
"""

from foon2asp.cli import (  # noqa: F401  (each module registers its command on main)
    batch,
    check,
    compare,
    consolidate,
    draw,
    export,
    facts,
    merge,
    methods,
    missing,
    objects,
    query,
    reachable,
    schedule,
    solve,
)
from foon2asp.cli.main import main

__all__ = ["main"]
