"""``foon2asp merge``: FOON subgraphs into one universal FOON."""

from __future__ import annotations

import click

from foon2asp import api
from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import choice_option, joined_lines, match_options
from foon2asp.cli.output import warn_all
from foon2asp.errors import InputError


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path())
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The merged FOON file.")
@click.option("--strict", is_flag=True, help="Treat skipped units (warnings) as errors.")
@choice_option(
    "--format",
    "fmt",
    choices=api.FOON_FORMATS,
    default="foon",
    help="foon: official dialect with ids; foon-plain: without ids; foon-json: foon_api's JSON;"
    " units-json: the unit-list JSON of generated trees.",
)
@match_options
@guarded
def merge(files, output, strict, fmt, match):
    """Merge FOON subgraphs into one universal FOON (duplicate units merged).

    FILES may be FOON text, FOON JSON or the unit-list JSON of generated trees
    ({input_nodes, motion_node, output_nodes} per unit).  With --level 1 or 2, --normalize or
    --synonyms the units are written as that comparison sees them (units equal there merged,
    the first spelling of each text kept); the spellings joined are listed on stderr.
    """
    if match.substitutes is not None:
        raise InputError("merge writes a FOON: --substitutes applies where trees are found (solve, check, ...)")
    foon = api.read_foons(files, strict)
    warn_all(foon.warnings)
    foon, joined = api.match_foon(foon, **match.load_args)
    for line in joined_lines(joined):
        click.echo(line, err=True)
    api.write_foon(foon, output, fmt, header=f"merged by foon2asp from {len(files)} file(s)")
    click.echo(
        f"merged {len(files)} file(s): {len(foon.units)} units, {len(foon.objects)} objects -> {output}", err=True
    )
