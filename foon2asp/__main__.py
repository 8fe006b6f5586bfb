from foon2asp.cli.main import main

main(prog_name="foon2asp")
