"""``foon2asp merge``: FOON subgraphs into one universal FOON."""

from __future__ import annotations

import click

from foon2asp import api
from foon2asp.cli.main import guarded, main
from foon2asp.cli.output import warn


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path())
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The merged FOON file.")
@click.option("--strict", is_flag=True, help="Treat skipped units (warnings) as errors.")
@click.option(
    "--format",
    "fmt",
    type=click.Choice(api.FOON_FORMATS),
    default="foon",
    show_default=True,
    help="foon: official dialect with ids; foon-plain: without ids; foon-json: foon_api's JSON.",
)
@guarded
def merge(files, output, strict, fmt):
    """Merge FOON subgraphs into one universal FOON (duplicate units merged)."""
    foon = api.read_foons(files, strict)
    for warning in foon.warnings:
        warn(warning)
    api.write_foon(foon, output, fmt, header=f"merged by foon2asp from {len(files)} file(s)")
    click.echo(
        f"merged {len(files)} file(s): {len(foon.units)} units, {len(foon.objects)} objects -> {output}", err=True
    )
