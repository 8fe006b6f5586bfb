"""``foon2asp schedule``: each goal's task tree on robot arms and people, with a proven-minimal makespan."""

from __future__ import annotations

import sys

import click

from foon2asp import api, report
from foon2asp.cli.main import guarded
from foon2asp.cli.options import (
    choice_option,
    goal_command,
    progress_option,
    strategy_options,
    time_limit_option,
    together_option,
)
from foon2asp.cli.output import echo_now, emit, goal_progress, progress_bar, solver_of
from foon2asp.cli.schedule_options import schedule_options
from foon2asp.report import draw
from foon2asp.schedule.result import seconds_text
from foon2asp.schedule.solve import DEFAULT_TIME_LIMIT

#: formats of the schedules themselves; the others are pictures of them (report kind ``schedule``)
OWN = ("text", "json")
#: statuses that answer a goal (exit status 0)
ANSWERED = ("optimal", "unschedulable", "unreachable")

EXIT = """\b
Exit codes: 0 every goal answered (makespan proven, or unschedulable or unreachable);
1 some makespan is not proven (time limit); 2 bad input or usage; 130 interrupted."""


def status_text(info: dict) -> str:
    """``schedule greek salad: makespan 65 s, lower bound 62.5 s`` (the makespan phase), or
    ``...: makespan 40 s (proven), human units 15, at least 11`` (the human units)."""
    head = f"schedule {info.get('goal', '')}: makespan {seconds_text(info['makespan'])} s"
    if info.get("phase") == "human":
        return f"{head} (proven), human units {info['human']}, at least {info['human_lower']}"
    return f"{head}, lower bound {seconds_text(info['lower'])} s"


@goal_command(
    None,
    objective="The tree's objective(s), comma-separated (units, success, inputs, depth, cost): the tree scheduled,"
    " or with --joint the tie-breaker after makespan and human units.",
    epilog=EXIT,
)
@time_limit_option(
    "Seconds per solve (tree, schedule; with --joint also the search over trees); a schedule cut short is"
    " 'feasible': the best found, with its lower bound. Without it the tree has no limit and each schedule"
    f" solve {DEFAULT_TIME_LIMIT:g} s."
)
@schedule_options
@click.option(
    "--joint",
    is_flag=True,
    help="Choose tree and schedule together: the makespan is minimal over every valid tree (the fixed tree's"
    " is reported beside it).",
)
@choice_option(
    "--format",
    "fmt",
    choices=[*OWN, *report.names("schedule")],
    default="text",
    help="text: a timeline per agent; json: a list, one object per goal; svg/png/pdf/dot: Gantt charts;"
    " html: a page of them.",
)
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), help="Write to FILE instead of stdout (png, pdf: binary)."
)
@choice_option(
    "--encoding",
    choices=api.SCHEDULE_ENCODINGS,
    default=api.DEFAULT_SCHEDULE_ENCODING,
    help="Time steps in plain ASP, or clingo-dl start times (needs clingo-dl).",
)
@together_option("A meal: one tree that makes every goal, and one schedule of it.")
@strategy_options
@progress_option
@guarded
def schedule(data, goal, goals, spec, joint, fmt, output, encoding, together, progress, options):
    """Schedule each goal's task tree (the best by --objective) on the agents: who does which unit
    when, with the makespan proven minimal, the list-scheduling baseline and the lower bounds.

    A unit starts when the units making its required inputs have finished; an agent does one
    unit at a time; capabilities and resources hold. Ties of makespan go to fewer units done by
    a 'human' agent, then to the tree objective. Text output is printed goal by goal.
    """
    kb, jobs = data.load_goals(goal, goals, together)
    solver = solver_of(kb, options)
    if fmt not in OWN and fmt != "dot":
        draw.require_dot()  # before solving, not after
    # a status line on stderr: the best makespan and its bound, then the human units
    status = goal_progress(progress, status_text)
    found = kb.schedule_iter(jobs, spec, solver, joint=joint, encoding=encoding, progress=status)
    done: list = []
    stream = fmt == "text" and output is None
    for s in progress_bar(found, len(jobs), progress, "schedule"):
        if status is not None:
            status.close()
        done.append(s)
        if stream:
            echo_now(("\n" if len(done) > 1 else "") + s.to_text())
    if fmt == "text":
        out: str | bytes = "\n".join(s.to_text() for s in done)
    elif fmt == "json":
        out = api.schedules_json(done)
    else:
        out = report.render_bytes("schedule", fmt, [s.to_dict() for s in done])
    if not stream:
        emit(out, output, f"wrote {len(done)} schedule(s) as {fmt}")
    sys.exit(0 if all(s.status in ANSWERED for s in done) else 1)
