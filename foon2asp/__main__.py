"""`python -m foon2asp`: the command line."""

from foon2asp.cli.main import run

run()
