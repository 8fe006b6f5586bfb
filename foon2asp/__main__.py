from .cli import main

main(prog_name="foon2asp")
