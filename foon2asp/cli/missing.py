"""``foon2asp missing``: the fewest objects to add to the kitchen so a goal can be made."""

from __future__ import annotations

import sys

import click

from foon2asp import report
from foon2asp.cli.main import guarded
from foon2asp.cli.options import goal_command, progress_option, strategy_options, time_limit_option, together_option
from foon2asp.cli.output import exit_code, progress_bar, solver_of


@goal_command(
    "missing",
    objective="After the fewest added objects, the best tree by these objectives (units, success, inputs, cost with"
    " --motion-cost), comma-separated.",
)
@time_limit_option("Seconds per goal; the best answer so far is reported as 'feasible'.")
@together_option("A meal: the fewest objects so that one tree makes every goal.")
@strategy_options
@progress_option
@guarded
def missing(data, goal, goals, fmt, together, options, progress):
    """The fewest objects to add to the kitchen so a goal can be made (proven minimal), and the tree.

    Default goals: the goals file's.  With --together: the fewest objects for the whole meal.
    """
    kb, jobs = data.load_goals(goal, goals, together)
    solver_of(kb, options)  # the request checked, its warnings first
    results = []
    for g in progress_bar(jobs, len(jobs), progress, "missing"):
        results.append(kb.missing(g, options=options).raw)
        if fmt == "jsonl":
            click.echo(report.render("missing", fmt, kb.problem, results[-1:]), nl=False)
    if fmt != "jsonl":
        click.echo(report.render("missing", fmt, kb.problem, results), nl=False)
    sys.exit(exit_code((r.status, None) for r in results))
