"""Solver settings: the defaults live in asp/options.py and every command solves with them."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

import foon2asp
from foon2asp.asp import control as control_mod
from foon2asp.asp import options as settings
from foon2asp.asp.options import AspOptions
from foon2asp.cli.main import main
from synth import preset


def test_default_settings():
    assert settings.DEFAULT_OPT_STRATEGY == "usc,oll,succinct,stratify"
    assert "--opt-strategy=usc,oll,succinct,stratify" in AspOptions().args()
    two = AspOptions(threads=2).args()
    assert "--parallel-mode=2" in two and not any(a.startswith("--opt-strategy") for a in two)
    config = next(a for a in two if a.startswith("--configuration="))
    with open(config.split("=", 1)[1], encoding="utf-8") as fh:
        assert fh.read() == settings.PORTFOLIO
    assert "[bbsign]: --opt-strategy=bb --opt-heuristic=sign,model" in settings.PORTFOLIO
    assert "[usc]: --opt-strategy=usc,oll,succinct,stratify" in settings.PORTFOLIO
    mine = AspOptions(opt_strategy="bb", threads=2).args()
    assert "--opt-strategy=bb" in mine and not any(a.startswith("--configuration") for a in mine)
    kb = foon2asp.load("demo")
    assert kb.options().args() == AspOptions().args()
    assert kb.options(threads=2, opt_strategy="usc,k").args()[-2:] == ["--opt-strategy=usc,k", "--parallel-mode=2"]


@pytest.fixture()
def recorded(monkeypatch):
    """The arguments of every optimising clingo control made meanwhile."""
    calls: list[list[str]] = []
    real = control_mod.Control.__init__

    def spy(self, args=(), *rest, **kw):
        if "--opt-mode=opt" in args:
            calls.append(list(args))
        real(self, args, *rest, **kw)

    monkeypatch.setattr(control_mod.Control, "__init__", spy)
    return calls


def _strategy(args: list[str]) -> list[str]:
    return [a for a in args if a.startswith(("--opt-strategy", "--configuration", "--parallel-mode"))]


@pytest.mark.parametrize(
    "command",
    [
        ["solve", "--goals", "all"],
        ["compare", "--goals", "all"],
        ["missing", "--goals", "all"],
        ["batch", "--goals", "all", "--output", "{tmp}/r.jsonl", "--no-shortcuts"],
        ["check", "{tmp}/tree.txt"],
    ],
)
def test_every_command_solves_with_the_default(command, tmp_path, recorded, monkeypatch):
    # the small preset: real choice, so the bounds do not answer every goal without the solver
    data = preset("small").write(tmp_path / "small")
    runner = CliRunner()
    if command[0] == "check":
        res = runner.invoke(main, ["solve", "--data", str(data), "--goals", "all", "--format", "foon"])
        (tmp_path / "tree.txt").write_text(res.output)
        recorded.clear()
    args = [a.replace("{tmp}", str(tmp_path)) for a in command] + ["--data", str(data)]
    res = runner.invoke(main, args)
    assert res.exit_code in (0, 1), res.output
    assert recorded, "no optimising solver call"
    for call in recorded:
        assert _strategy(call) == [f"--opt-strategy={settings.DEFAULT_OPT_STRATEGY}", "--configuration=trendy"], call
        assert "--opt-usc-shrink=bin" in call
    if command[0] != "check":  # check's optimum takes no solver options
        recorded.clear()
        again = [a.replace("r.jsonl", "r2.jsonl") for a in args]
        res = runner.invoke(main, [*again, "--threads", "2"])
        assert res.exit_code in (0, 1), res.output
        assert recorded
        for call in recorded:
            assert _strategy(call)[0] == "--parallel-mode=2" and _strategy(call)[1].startswith("--configuration=")


@pytest.mark.parametrize(
    ("arg", "why"),
    [
        ("--solve-limit=1", "it ends a search early"),
        ("--opt-stop=3", "it ends a search early"),
        ("--opt-mode=opt,3", "foon2asp sets it for each solve call"),
        ("-n3", "the number of trees: --models"),
        ("--project", "foon2asp sets it for each solve call"),
        ("-t2", "the number of threads is --threads"),
    ],
)
def test_clingo_options_that_change_what_a_solve_call_proves_are_refused(arg, why):
    """A conflict limit would let a search cut short pass for a proof; the solve mode, models and
    threads are foon2asp's own settings."""
    with pytest.raises(foon2asp.InputError) as refused:
        foon2asp.Options(clingo_args=[arg])
    assert str(refused.value).startswith(f"clingo option '{arg}' is not taken: ") and why in str(refused.value)
    result = CliRunner().invoke(main, ["solve", "--data", "demo", "--goal", "tomato salad", arg])
    assert result.exit_code == 2 and f"clingo option '{arg}' is not taken" in result.output
    assert settings.clingo_options(["--configuration=crafty", "--single-shot"]) == [
        "--configuration=crafty",
        "--single-shot",
    ]


def test_a_clingo_option_without_its_value_says_how_to_give_it():
    with pytest.raises(foon2asp.InputError, match=r"'configuration' requires a value! \(write --configuration=VALUE\)"):
        foon2asp.Options(clingo_args=["--configuration"])


def test_a_clingo_option_given_by_a_prefix_replaces_foon2asps_own():
    """clingo takes an unambiguous prefix of an option's name, and each option once."""
    args = settings.clingo_options(["--config=crafty", "--opt-usc-sh=inv", "--single-shot"])
    assert args == ["--configuration=crafty", "--opt-usc-shrink=inv", "--single-shot"]
    assert [a for a in AspOptions(clingo_args=args).args() if a.startswith(("--configuration", "--opt-usc"))] == [
        "--configuration=crafty",
        "--opt-usc-shrink=inv",
    ]
    tree = foon2asp.load("demo").solve("tomato salad", clingo_args=["--config=crafty"])
    assert (tree.status, tree.cost["units"]) == ("optimal", 4)
