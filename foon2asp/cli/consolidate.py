"""``foon2asp consolidate``: candidate trees of one recipe -> one proven-best tree per goal."""

from __future__ import annotations

import sys

import click

from foon2asp import api
from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import (
    GOAL_HELP,
    KITCHEN_HELP,
    constraint_options,
    file_options,
    format_option,
    gap_option,
    match_options,
    objective_option,
    strategy_options,
    time_limit_option,
    together_option,
)
from foon2asp.cli.output import EXIT_CODES, emit, exit_code, warn_all


@main.command(epilog=EXIT_CODES)
@click.argument("trees", nargs=-1, required=True, type=click.Path(), metavar="TREES...")
@click.option("--goal", "goal", multiple=True, metavar="TEXT", help=GOAL_HELP)
@click.option(
    "--goals",
    "goals",
    metavar="FILE|all",
    help="A FILE of goal objects, or 'all': every product of a candidate's last unit. Default: the product of"
    " the candidates' last units that most of them share.",
)
@click.option("--kitchen", type=click.Path(), help=KITCHEN_HELP + " Default: leaves.")
@file_options
@constraint_options
@objective_option()
@format_option("consolidate")
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), help="A FILE to write the report to (default: stdout)."
)
@time_limit_option("Seconds per goal; the best tree so far is reported as 'feasible'.")
@gap_option
@together_option("A meal: one tree that makes every goal.")
@strategy_options
@match_options
@guarded
def consolidate(trees, goal, fmt, output, options, match, **given):
    """Merge candidate task trees of one recipe (TREES: files in any form 'check' reads, e.g. the
    unit-list JSON of generated trees) into one FOON and find, for each goal, its proven-best tree.

    The kitchen is every object no unit makes (--kitchen leaves) unless --kitchen FILE is given.
    Each unit of the tree names the files it comes from; each candidate gets a verdict: is it
    executable on its own (its units, in file order, from that kitchen), why not, its measures
    beside the optimum's and which of its units the tree uses.  An unreachable goal comes with
    the fewest objects to add to the kitchen ('missing').
    """
    # given: --goals, --kitchen, the file options and --together, as api.consolidate names them
    found = api.consolidate(list(trees), list(goal) or None, options=match.request(options), **given, **match.load_args)
    warn_all(found.warnings)
    emit(found.render(fmt), output, f"wrote the {fmt} report of {len(found)} goal(s)")
    sys.exit(exit_code((r.status, None) for r in found))
