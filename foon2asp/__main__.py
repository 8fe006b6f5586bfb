"""`python -m foon2asp`: the command line."""

from foon2asp.cli import main

main(prog_name="foon2asp")
