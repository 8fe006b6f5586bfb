"""``foon2asp check``: is a tree (or a plan) valid, and how far is it from the optimum?"""

from __future__ import annotations

import sys
from collections.abc import Callable
from functools import partial

import click

from foon2asp import api, report
from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import MatchArgs, data_options, format_option
from foon2asp.cli.output import warn_all
from foon2asp.cli.schedule_options import schedule_options
from foon2asp.errors import InputError


@main.command()
@click.argument("trees", nargs=-1, required=True, type=click.Path(), metavar="TREE [TREE...]")
@data_options
@click.option(
    "--goal",
    "goal",
    multiple=True,
    metavar="TEXT",
    help="The goal (a label, an object's text or #ID; repeat for a meal); default: the goal the file names"
    " (a JSON result, or the '# task tree for ...' line of solve --format foon), else the tree's only sink"
    " (judged on its own: the products of its last unit).",
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
@schedule_options
@guarded
def check(trees, data, goal, goals, fmt, optimum, spec):
    """Check the task tree(s) in each TREE (FOON text with // between units, FOON JSON, foon2asp JSON,
    or the unit-list JSON of generated trees), or a plan for a problem of 'export pddl'
    ('(action-name)' lines, as Fast Downward writes them); one report per tree.

    Without --data and --foon each tree is judged on its own: the kitchen is its leaves (every
    object no unit of it makes; or --kitchen FILE), the goal the products of its last unit
    (or --goal), and it is valid when every unit fires in the order written; the report names
    the first unit that cannot and the object it waits for, or the cycle.

    \b
    A schedule file ('schedule --format json') is judged with the FOON (--data or --foon) on the
    agents, durations, capabilities and resources of the schedule options: the first violation of
    the tree's validity, durations, capabilities, precedence, one unit per agent at a time or resources.

    \b
    An answer that gives no units for its goal (solve's answer for an unreachable goal) is
    'unreachable: no tree to check' when the FOON confirms that the goal is not derivable from
    the kitchen, counted apart from the valid and invalid trees; else it is invalid.

    \b
    Exit codes: 0 every tree (schedule) valid or confirmed unreachable; 1 some tree (schedule)
    invalid; 2 bad input or usage; 130 interrupted.
    """
    schedules = [p for p in trees if api.is_schedule_file(p)]
    verdicts: list = []
    if schedules:
        if fmt not in ("text", "json"):
            raise InputError(f"schedules are checked in --format text or json, not {fmt}")
        kb = data.load()
        verdicts = [v for p in schedules for v in kb.check_schedules(p, spec, data.match.request())]
        out = api.verdicts_json(verdicts) if fmt == "json" else "".join(v.to_text() for v in verdicts)
        click.echo(out, nl=False)
        if len(schedules) == len(trees):
            sys.exit(0 if all(v.valid for v in verdicts) else 1)
        trees = [p for p in trees if p not in schedules]
    reports: list = []
    if data.data_dir is None and not data.foon:
        if data.match != MatchArgs():
            raise InputError(
                "--level, --normalize, --synonyms and --substitutes need a FOON (--data or --foon) to compare with"
            )
        if goals:
            raise InputError("--goals needs a FOON (--data or --foon); to judge a tree on its own, use --goal")
        files = {"kitchen": data.kitchen, "utensils": data.utensils, "utensil_rule": data.utensil_rule}
        judge: Callable[[str], list] = partial(api.check_tree, goal=list(goal) or None, strict=data.strict, **files)
        problem = None
    else:
        kb = data.load(goals)
        among = kb.select_goals((), goals) if goals else None
        options = data.match.request()
        judge = partial(
            kb.check_all, goal=list(goal) or None, optimum=optimum, goals=among, strict=data.strict, options=options
        )
        problem = kb.problem
    for path in trees:
        found = judge(path)
        warn_all(dict.fromkeys(w for v in found for w in v.warnings))
        reports += [v.raw for v in found]
    click.echo(report.render("check", fmt, problem, reports), nl=False)
    answered = all(report.check.answered(r) for r in reports)
    sys.exit(0 if answered and all(v.valid for v in verdicts) else 1)
