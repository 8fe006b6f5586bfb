"""``foon2asp objects``: list objects with their ids and texts, to pick goals from."""

from __future__ import annotations

import json
from dataclasses import replace
from functools import partial

import click

from foon2asp.cli.main import guarded, main
from foon2asp.cli.options import KITCHEN_HELP, choice_option, data_options, joined_lines
from foon2asp.errors import InputError


def _makers(kb, oid: int) -> tuple[int, int]:
    """How many units make object ``oid``, and how many output it but also take it as an input
    (which do not make it: the heated stove stays on)."""
    problem = kb.problem
    units = problem.producers.get(oid, ())
    needing = sum(1 for u in units if oid in problem.inputs[u])
    return len(units) - needing, needing


@main.command()
@click.argument("query", required=False, metavar="[LABEL]")
@partial(data_options, with_kitchen=False)  # --kitchen keeps kitchen items; the file is --kitchen-file
@click.option(
    "--produced", "only", flag_value="produced", help="Only objects some unit makes (without needing it as an input)."
)
@click.option("--kitchen", "only", flag_value="kitchen", help="Only kitchen items.")
@click.option("--derivable", "only", flag_value="derivable", help="Only objects that can be made from the kitchen.")
@click.option(
    "--kitchen-file",
    "kitchen_file",
    metavar="FILE|leaves",
    help=KITCHEN_HELP.replace("kitchen.json", "A kitchen.json", 1),
)
@choice_option("--format", "fmt", choices=("text", "json"), default="text")
@guarded
def objects(query, data, only, kitchen_file, fmt):
    """List the objects LABEL names (all objects without it), each with its #ID and text.

    LABEL is a label ('scrambled egg'), an object's text, #ID, or words of labels ('egg').
    Any #ID or text listed can be given as --goal; the JSON list is a goals file
    (--goals FILE).

    'made by N units' counts the units that make the object: a unit that outputs it but also
    needs it as an input does not make it ('output by N units that need it').
    """
    try:
        kb = replace(data, kitchen=kitchen_file).load()
    except InputError as exc:
        if (exc.hint or "").partition("=")[0] != "kitchen":
            raise
        looked_for = (exc.hint or "").partition("=")[2]
        raise InputError(
            f"no kitchen.json beside the FOON file (looked for {looked_for}); give --kitchen-file FILE,"
            " --kitchen-file leaves (every object no unit makes) or --data DIR"
        ) from None
    ids = kb.find_objects(query, only, options=data.match.request())
    makers = {i: _makers(kb, i) for i in ids}
    if only == "produced":  # some unit makes it, not only outputs it again
        ids = [i for i in ids if makers[i][0]]
    # "producers": the units that make it
    infos = [{**kb.object_info(i), "producers": makers[i][0]} for i in ids]
    if fmt == "json":
        click.echo("[\n" + ",\n".join(json.dumps(i, ensure_ascii=False) for i in infos) + "\n]" if infos else "[]")
        return
    width = len(f"#{max(ids)}") if ids else 2
    for info in infos:
        where = ["kitchen"] if info["in_kitchen"] else []
        if info["producers"]:
            where.append(f"made by {info['producers']} unit{'s' if info['producers'] != 1 else ''}")
        needing = makers[info["id"]][1]
        if needing:
            also = "also " if info["producers"] else "only "
            where.append(
                f"{also}output by {needing} unit{'s' if needing != 1 else ''} that need{'s' if needing == 1 else ''} it"
            )
        if "joined" in info:
            where.append("joins " + " | ".join(info["joined"]))
        click.echo(f"{'#' + str(info['id']):<{width}}  {info['text']}" + (f"   ({', '.join(where)})" if where else ""))
    what = {None: "", "produced": " made by some unit", "kitchen": " in the kitchen", "derivable": " derivable"}[only]
    click.echo(f"{len(infos)} object{'s' if len(infos) != 1 else ''}{what}", err=True)
    for line in joined_lines(kb.joined):
        click.echo(line, err=True)
