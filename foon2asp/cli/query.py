"""``foon2asp query PROGRAM``: run your ASP program with the FOON facts."""

from __future__ import annotations

import sys

import click

from foon2asp import api, report
from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import (
    GOAL_HELP,
    data_options,
    format_option,
    models_option,
    request_options,
    time_limit_option,
)
from foon2asp.cli.output import warn_all

#: the statuses of a query that exit 0: a model, the proven optimum (unsatisfiable, feasible and unknown exit 1)
ANSWERED = frozenset({"satisfiable", "optimal"})


@main.command()
@click.argument("program", type=click.Path())
@data_options
@click.option(
    "--goals", "goals", metavar="FILE|all|all-objects", help="Goals for goal_node/2 facts (default: the goals file)."
)
@click.option("--goal", "goal", metavar="TEXT", help="Also add goal(O) for this goal. " + GOAL_HELP)
@click.option(
    "--encoding",
    "encoding_names",
    multiple=True,
    help="Also load a shipped encoding (tree, units, success, inputs, reachable, missing) and what it needs; repeatable.",
)
@request_options({"models": "models"}, models_option(0, "Models to print (0 = all); with an objective, the optimum."))
@format_option("query")
@time_limit_option("Seconds for the solve.")
@guarded
def query(program, data, goals, goal, encoding_names, fmt, options):
    """Run your ASP PROGRAM with the FOON facts; print its shown atoms with ids as readable objects.

    With a #show statement in PROGRAM only what it shows is printed. Atoms that
    no rule or fact defines (a misspelt predicate) are warned about.

    \b
    Exit codes: 0 a model (with an objective, the proven optimum); 1 no such
    answer: proven unsatisfiable, or the time limit stopped the search (no model
    yet, or the optimum not proven; the status printed says which); 2 bad input
    or usage; 130 interrupted.
    """
    text = api.read_program(program)
    kb = data.load(goals)
    nodes = kb.select_goals((), goals) if goals else None
    result = kb.query(
        text, goal=goal or None, encodings=encoding_names, name=program, goal_nodes=nodes, options=options
    )
    warn_all(result.warnings)
    click.echo(report.render("query", fmt, kb.problem, result), nl=False)
    sys.exit(0 if result.status in ANSWERED else 1)
