"""``foon2asp export pddl``: the goal's relevant part of the FOON as PDDL for classical planners."""

from __future__ import annotations

from pathlib import Path

import click

from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import choice_option, constraint_options, data_options, motion_cost_option, request_options
from foon2asp.errors import InputError
from foon2asp.report import pddl


@main.group()
def export():
    """Write a FOON problem in another planning language."""


@export.command("pddl")
@data_options
@click.option("--goal", "goal", multiple=True, help="Goal label; repeat for a meal (every goal in :goal).")
@click.option("--goals", "goals", help="FILE of goal objects or 'all' (the goals file): all of them in one :goal.")
@choice_option(
    "--objective",
    choices=pddl.PDDL_OBJECTIVES,
    default="units",
    help="units: plan length; success: integer action costs round(-1000 ln p) (:action-costs); inputs: input nodes;"
    " cost: the motion costs of --motion-cost in hundredths.",
)
@request_options({"motion_cost": "motion_cost"}, motion_cost_option())
@click.option(
    "-o",
    "--output",
    required=True,
    type=click.Path(file_okay=False),
    help="Directory for domain.pddl and problem.pddl.",
)
@click.option("--name", default="foon", show_default=True, help="Domain name (problem: NAME-task).")
@constraint_options
@guarded
def export_pddl(data, goal, goals, objective, output, name, options):
    """The goal's relevant part as a delete-free STRIPS domain and problem (DIR/domain.pddl, DIR/problem.pddl).

    One action per functional unit, named u<id>-<motion> (a plan maps back to the units:
    'foon2asp check PLAN --goal ...'); preconditions are the required inputs, effects the
    products; kitchen items in :init, the goal(s) in :goal.  --forbid-motion and
    --forbid-object remove actions; general --rule/--constraint programs, --require-* and
    --max-units cannot be exported.
    """
    if goals == "all-objects":
        raise InputError("--goals all-objects cannot be one PDDL goal; name goals with --goal or a goals FILE")
    if options.substitutes is not None:
        raise InputError("export pddl cannot express --substitutes (a plan cannot count its substitutions)")
    kb, goal_ids = data.load_goals(goal, goals)
    problem = kb.solving_problem(kb.options(options))  # with the motion costs, for --objective cost
    if not all(c.isalnum() or c in "-_" for c in name) or not name[:1].isalpha():
        raise InputError(f"--name must be a PDDL name (a letter, then letters, digits, - or _), not {name!r}")
    task = pddl.export(problem, goal_ids, objective, options.constraints, name)
    out = Path(output)
    out.mkdir(parents=True, exist_ok=True)
    (out / "domain.pddl").write_text(task.domain, encoding="utf-8")
    (out / "problem.pddl").write_text(task.problem, encoding="utf-8")
    click.echo(
        f"wrote {out / 'domain.pddl'} ({len(task.actions)} actions, {len(task.objects)} objects) "
        f"and {out / 'problem.pddl'} ({len(task.goals)} goal(s))",
        err=True,
    )
