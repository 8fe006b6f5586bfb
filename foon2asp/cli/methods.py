"""``foon2asp methods``: the registered methods."""

from __future__ import annotations

import click

from foon2asp import api
from foon2asp.cli.main import main


@main.command("methods")
def list_methods():
    """List the registered methods."""
    for m in api.methods():
        click.echo(f"{m.name:16} {m.kind:7} {m.description}")
