"""``foon2asp facts``: the FOON, kitchen and goals as ASP facts."""

from __future__ import annotations

import click

from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import GOAL_HELP, data_options
from foon2asp.cli.output import emit


@main.command()
@data_options
@click.option(
    "--goals", "goals", metavar="FILE|all|all-objects", help="Goals for goal_node/2 facts (default: the goals file)."
)
@click.option("--goal", "goal", multiple=True, metavar="TEXT", help="Also fix goal(O) for this goal. " + GOAL_HELP)
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="A FILE to write the facts to (default: stdout).")
@guarded
def facts(data, goals, goal, output):
    """Write the FOON, kitchen and goals as ASP facts."""
    kb = data.load(goals)
    nodes = kb.select_goals((), goals) if goals else None
    text = kb.facts(nodes, kb.select_goals(goal, None) if goal else [], options=data.match.request())
    emit(text, output, f"wrote {len(text.splitlines())} lines")
