"""``foon2asp batch``: many goals x methods into a resumable JSON-lines file, then a summary."""

from __future__ import annotations

import sys

import click

from foon2asp import api, report
from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import (
    choice_option,
    constraint_options,
    data_options,
    gap_option,
    goal_options,
    method_option,
    methods_of,
    objective_option,
    progress_option,
    request_options,
    strategy_options,
    time_limit_option,
)
from foon2asp.cli.output import EXIT_CODES, exit_code, solver_of
from foon2asp.cli.params import SCHEDULER, WORKERS
from foon2asp.cli.schedule_options import schedule_options

#: schedule statuses that answer their goal
SCHEDULED = ("optimal", "unschedulable")

#: --grounding and --shortcuts, into the request
_batch_settings = request_options(
    {"grounding": "grounding", "shortcuts": "shortcuts"},
    choice_option(
        "--grounding",
        choices=api.GROUNDINGS,
        default="auto",
        help="One grounding for all goals, or a small grounding of each goal's relevant part; auto: per-goal when"
        " the goals' median relevant part is under 10 % of the viable units or there are over 50,000 of them"
        " (the summary says which).",
    ),
    click.option(
        "--shortcuts/--no-shortcuts",
        default=True,
        show_default=True,
        help="Let preparation answer a goal it proves (one tree in the goal's part; the landmark bound met by"
        " the bounds tree); --no-shortcuts: clingo answers every goal that can be made.",
    ),
)


@main.command(epilog=EXIT_CODES)
@data_options
@goal_options
@method_option("asp")
@objective_option()
@click.option(
    "-o",
    "--output",
    default="results.jsonl",
    show_default=True,
    type=click.Path(dir_okay=False),
    help="A FILE of results, one JSON line per (goal, method).",
)
@click.option(
    "--resume",
    is_flag=True,
    help="Continue OUTPUT: skip the (goal, method) pairs it already holds for the same configuration.",
)
@click.option(
    "--workers",
    type=WORKERS,
    metavar="N|auto",
    default="auto",
    show_default=True,
    help="Worker processes; auto: this process, and once the batch has run 5 s the rest on every usable core.",
)
@click.option(
    "--scheduler", type=SCHEDULER, metavar="ADDRESS", help="Run on this Dask scheduler (needs the 'dask' extra)."
)
@time_limit_option("Seconds per goal; the best tree so far is reported as 'feasible'.")
@gap_option
@strategy_options
@_batch_settings
@choice_option(
    "--summary",
    "summary_fmt",
    choices=report.names("summary"),
    default="text",
    help="Format of the summary printed at the end.",
)
@progress_option
@click.option(
    "--fsync/--no-fsync",
    default=True,
    show_default=True,
    help="Sync result lines to disk (grouped: at most 0.25 s apart, and at the end).",
)
@constraint_options
@click.option(
    "--schedule",
    "with_schedules",
    is_flag=True,
    help="Also schedule each goal's tree (of the first method) on the agents of the schedule options, into"
    " OUTPUT with the suffix .schedules.json (a JSON list as 'schedule --format json' writes).",
)
@schedule_options
@guarded
def batch(
    data,
    goal,
    goals,
    method_list,
    output,
    resume,
    workers,
    scheduler,
    summary_fmt,
    progress,
    fsync,
    with_schedules,
    spec,
    options,
):
    """Solve many goals with several methods; resumable JSON-lines output and a summary.

    Every result line carries "valid" (the independent validator's verdict); the
    summary counts the valid trees per method. Default goals: the goals file's.
    """
    kb, goal_ids = data.load_goals(goal, goals)
    solver_of(kb, options)  # the request checked, its warnings before the run
    run = kb.batch(
        goal_ids,
        output,
        methods=methods_of(method_list),
        workers=workers,
        resume=resume,
        progress=progress,
        fsync=fsync,
        scheduler=scheduler,
        options=options,
    )
    answers = [(r.get("status", "?"), r.get("valid")) for r in run.records]
    if with_schedules:
        path = api.schedules_path(output)
        found = run.schedule(spec, output=path, options=options)
        click.echo(f"wrote {len(found)} schedule(s) to {path}", err=True)
        answers += [("optimal" if s.status in SCHEDULED else s.status, None) for s in found]
    click.echo(run.render(summary_fmt), nl=False)
    sys.exit(exit_code(answers))
