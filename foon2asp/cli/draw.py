"""``foon2asp draw TREE -o FILE``: the picture of any task tree file."""

from __future__ import annotations

import click

from foon2asp import api
from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import STRICT_HELP, DataArgs, MatchArgs, match_options
from foon2asp.cli.output import warn
from foon2asp.errors import InputError
from foon2asp.report import draw as draw_mod


@main.command()
@click.argument("tree", type=click.Path())
@click.option(
    "--data", "data_dir", type=click.Path(), help="Data directory: marks kitchen items, the goal and a blocking cycle."
)
@click.option("--goal", "goal", help="Goal label (default: the goal a JSON result names, else inferred from the tree).")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="FILE.svg, .png, .pdf or .dot")
@click.option(
    "--format", "fmt", type=click.Choice(draw_mod.FORMATS), help="Drawing format (default: from the extension)."
)
@click.option("--strict", is_flag=True, help=STRICT_HELP)
@match_options
@guarded
def draw(tree, data_dir, goal, output, fmt, strict, match):
    """Draw a task tree file: FOON text (either dialect), FOON JSON, foon2asp JSON or the unit-list
    JSON of generated trees.

    Objects are ellipses, functional units boxes; with --data the goal is gold,
    kitchen items green, and the cycle that blocks an invalid tree red.
    """
    fmt = fmt or draw_mod.format_of(output)
    if fmt != "dot":
        draw_mod.require_dot()
    kb = None
    if data_dir is not None:
        kb = DataArgs(data_dir, (), None, None, None, "starter", False, match).load()
    elif match != MatchArgs():
        raise InputError("--level, --normalize, --synonyms and --substitutes need --data DIR to compare with")
    warnings: list[str] = []
    count = api.draw_file(
        tree, output, fmt=fmt, kb=kb, goal=goal, strict=strict, warnings=warnings, options=match.request()
    )
    for warning in warnings:
        warn(warning)
    click.echo(f"drew {count} tree(s) from {tree} -> {output}", err=True)
