"""``foon2asp check``: is a tree (or a plan) valid, and how far is it from the optimum?"""

from __future__ import annotations

import sys

import click

from foon2asp import report
from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import data_options, format_option


@main.command()
@click.argument("tree", type=click.Path())
@data_options
@click.option(
    "--goal",
    "goal",
    multiple=True,
    metavar="TEXT",
    help="The goal (a label, an object's text or #ID; repeat for a meal); default: the goal the file names"
    " (a JSON result, or the '# task tree for ...' line of solve --format foon), else the tree's only sink.",
)
@click.option(
    "--goals",
    "goals",
    metavar="FILE|all",
    help="Several goals (a goals file, or 'all' for the goals file): each tree's goal is the one of them it makes.",
)
@format_option("check")
@click.option(
    "--optimum/--no-optimum", default=True, show_default=True, help="Also solve the ASP optimum to compare with."
)
@guarded
def check(tree, data, goal, goals, fmt, optimum):
    """Check the task tree(s) in TREE (FOON text with // between units, FOON JSON or foon2asp JSON),
    or a plan for a problem of 'export pddl' ('(action-name)' lines, as Fast Downward writes them).

    \b
    Exit codes: 0 every tree valid; 1 some tree invalid; 2 bad input or usage;
    130 interrupted.
    """
    kb = data.load(goals)
    among = kb.select_goals((), goals) if goals else None
    reports = kb.check_all(tree, list(goal) or None, optimum, among)
    click.echo(report.render("check", fmt, kb.problem, [r.raw for r in reports]), nl=False)
    sys.exit(0 if all(r.valid for r in reports) else 1)
