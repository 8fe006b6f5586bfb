"""``foon2asp reachable``: which goals can be made from the kitchen at all."""

from __future__ import annotations

import click

from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import data_options, format_option, goal_options


@main.command()
@data_options
@goal_options
@format_option("reachable")
@guarded
def reachable(data, goal, goals, fmt):
    """Which goals (or objects) can be made from the kitchen at all, in one solve (default: the goals file's goals)."""
    kb, goal_ids = data.load_goals(goal, goals)
    click.echo(kb.reachability(goal_ids, options=data.match.request()).render(fmt), nl=False)
