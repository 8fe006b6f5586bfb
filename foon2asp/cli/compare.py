"""``foon2asp compare``: every method on every goal, each tree judged, beside the optimum."""

from __future__ import annotations

import sys

import click

from foon2asp import api, report
from foon2asp.cli.main import guarded
from foon2asp.cli.options import (
    gap_option,
    goal_command,
    is_search,
    methods_of,
    progress_option,
    strategy_options,
    time_limit_option,
    together_option,
)
from foon2asp.cli.output import echo_now, exit_code, progress_bar, solver_of, warn


@goal_command("compare", methods=",".join(api.COMPARE_METHODS))
@time_limit_option("Seconds per goal for ASP methods.")
@gap_option
@together_option("A meal: the one tree for all goals beside the sum of the single optima (ASP).")
@strategy_options
@progress_option
@guarded
def compare(data, goal, goals, method_list, fmt, together, options, progress):
    """Compare methods goal by goal: units, validity, success product, depth (default: the goals file's goals).

    --format jsonl prints each goal's results as soon as it is done.  With --together: the
    meal's tree (one tree for every goal) beside the sum of the single optima.
    """
    names = methods_of(method_list, api.COMPARE_METHODS)
    kb, goal_ids = data.load_goals(goal, goals)
    search = [n for n in names if is_search(n)]
    if options.constraints and search:
        warn(f"constraints apply to ASP methods only; {', '.join(search)} ignore them")
    solver = solver_of(kb, options)
    if together:
        asp = [n for n in names if not is_search(n)]
        meal = kb.compare_meal(goal_ids, (asp or ["asp"])[0], options=options)
        click.echo(report.render("compare", fmt, kb.problem, meal), nl=False)
        sys.exit(exit_code([(meal.meal.status, meal.meal.extra.get("valid"))]))
    rows = []
    parts = kb.compare_iter(goal_ids, names, solver)
    for part in progress_bar(parts, len(goal_ids), progress, "compare"):
        rows.extend(part.raw)
        if fmt == "jsonl":
            echo_now(part.render(fmt))
    if fmt != "jsonl":
        click.echo(api.Comparison(kb, rows).render(fmt), nl=False)
    sys.exit(exit_code((t.status, t.extra.get("valid")) for r in rows for t in r.trees.values()))
