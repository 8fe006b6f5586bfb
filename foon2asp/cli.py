"""The ``foon2asp`` command line (one module; subcommands share the loaders)."""

from __future__ import annotations

import functools
import sys
import time
from pathlib import Path

import click

from . import goals as goals_mod
from . import methods
from .errors import InputError
from .facts import facts as facts_text
from .loaders import Dataset
from .parser import read_foons, write_foon
from .problem import UTENSIL_RULES, Problem
from .programs import demo_dir
from .solver import OBJECTIVES, AspOptions
from .writers import FORMATS, render


def fail(message: str, code: int = 2) -> None:
    click.echo(f"foon2asp: error: {message}", err=True)
    sys.exit(code)


def guarded(func):
    """Run a command; bad input becomes one line on stderr and exit code 2."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except InputError as exc:
            fail(str(exc))
        except KeyboardInterrupt:
            fail("interrupted", 130)
        except BrokenPipeError:
            sys.exit(0)

    return wrapper


def data_options(func):
    """--data DIR and the per-file overrides, plus --utensil-rule and --strict."""
    opts = [
        click.option("--data", "data_dir", type=click.Path(), help="Directory with FOON.txt, kitchen.json, goal_nodes.json, motion.txt, utensils.txt (default: the demo data)."),
        click.option("--foon", "foon", type=click.Path(), multiple=True, help="FOON file(s); several are merged."),
        click.option("--kitchen", type=click.Path(), help="kitchen.json"),
        click.option("--motion", type=click.Path(), help="motion.txt (motion TAB success rate)"),
        click.option("--utensils", type=click.Path(), help="utensils.txt"),
        click.option("--utensil-rule", type=click.Choice(UTENSIL_RULES), default="starter", show_default=True, help="When a utensil holding one ingredient is not a required input."),
        click.option("--strict", is_flag=True, help="Treat skipped FOON units (warnings) as errors."),
    ]
    for opt in reversed(opts):
        func = opt(func)
    return func


def goal_options(func):
    func = click.option("--goals", "goals", help="FILE of goal objects, 'all' (the goals file) or 'all-objects'.")(func)
    func = click.option("--goal", "goal", multiple=True, help="Goal label (goals-file entry, else a unique FOON object).")(func)
    return func


def load(data_dir, foon, kitchen, motion, utensils, utensil_rule, strict, goals_file=None):
    """Read the data and build the problem; warnings go to stderr."""
    if data_dir is None and not (foon and kitchen):
        data_dir = str(demo_dir())
    goals_path = goals_file if goals_file not in (None, "all", "all-objects") else None
    data = Dataset.load(
        data_dir,
        foon=list(foon) if foon else None,
        kitchen=kitchen,
        goals=goals_path,
        motion=motion,
        utensils=utensils,
        strict=strict,
    )
    for warning in data.foon.warnings:
        click.echo(f"foon2asp: warning: {warning}", err=True)
    problem = Problem.from_dataset(data, utensil_rule)
    if data.motion:
        unknown = problem.unknown_motions()
        if unknown:
            click.echo(
                f"foon2asp: warning: {len(unknown)} motion(s) not in {data.paths.get('motion')} "
                f"get success rate 0.5: {', '.join(unknown[:5])}",
                err=True,
            )
    return data, problem


def _objective(value: str) -> tuple[str, ...]:
    parts = tuple(p.strip() for p in value.split(",") if p.strip())
    for p in parts:
        if p not in OBJECTIVES:
            raise InputError(f"unknown objective {p!r} (have {', '.join(OBJECTIVES)})")
    return parts or ("units",)


def safe_name(index: int, label: str) -> str:
    keep = "".join(c if c.isalnum() else "_" for c in label).strip("_")[:60] or "goal"
    return f"{index:03d}-{keep}"


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="foon2asp")
def main():
    """foon2asp: minimal, well-founded FOON task trees with answer-set programming."""


@main.command()
@data_options
@goal_options
@click.option("--method", default="asp", show_default=True, help="A registered method (see 'foon2asp methods').")
@click.option("--objective", default="units", show_default=True, help="ASP objective(s), comma-separated, most important first.")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default="text", show_default=True)
@click.option("--output", type=click.Path(file_okay=False), help="Also write one file per goal into this directory.")
@click.option("--time-limit", type=float, help="Seconds per goal; the best tree so far is reported as 'feasible'.")
@guarded
def solve(data_dir, foon, kitchen, motion, utensils, utensil_rule, strict, goal, goals, method, objective, fmt, output, time_limit):
    """Find the best task tree for each goal."""
    data, problem = load(data_dir, foon, kitchen, motion, utensils, utensil_rule, strict, goals)
    goal_ids = goals_mod.resolve(data, problem, goal, goals)
    options = AspOptions(objective=_objective(objective), time_limit=time_limit)
    run = methods.runner(method, problem, options)
    trees = []
    out_dir = Path(output) if output else None
    if out_dir:
        out_dir.mkdir(parents=True, exist_ok=True)
    for index, g in enumerate(goal_ids, 1):
        tree = run(g)
        trees.append(tree)
        if out_dir:
            ext = {"text": "txt", "json": "json", "foon": "txt"}[fmt]
            name = safe_name(index, problem.objects[g].label) + ("" if fmt != "foon" else ".foon") + f".{ext}"
            (out_dir / name).write_text(render(problem, [tree], fmt), encoding="utf-8")
    click.echo(render(problem, trees, fmt), nl=False)


@main.command()
@data_options
@click.option("--goals", "goals_file", help="Goals FILE (default: goal_nodes.json of --data).")
@click.option("--goal", "goal", multiple=True, help="Also fix goal(O) for this label.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the facts here (default: stdout).")
@guarded
def facts(data_dir, foon, kitchen, motion, utensils, utensil_rule, strict, goals_file, goal, output):
    """Write the FOON, kitchen and goals as ASP facts."""
    data, problem = load(data_dir, foon, kitchen, motion, utensils, utensil_rule, strict, goals_file)
    goal_nodes = [goals_mod.goal_id(problem, obj, data.paths.get("goals"), line) for obj, line in data.goals]
    fixed = goals_mod.resolve(data, problem, goal, None) if goal else []
    text = facts_text(problem, goal_nodes=goal_nodes)
    text += "".join(f"goal({g}).\n" for g in fixed)
    if output:
        Path(output).write_text(text, encoding="utf-8")
        click.echo(f"wrote {len(text.splitlines())} lines to {output}", err=True)
    else:
        click.echo(text, nl=False)


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path())
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The merged FOON file.")
@click.option("--strict", is_flag=True, help="Treat skipped units (warnings) as errors.")
@guarded
def merge(files, output, strict):
    """Merge FOON subgraphs into one universal FOON (duplicate units merged)."""
    for f in files:
        if not Path(f).is_file():
            raise InputError("FOON file not found", f)
    foon = read_foons(files, strict)
    for warning in foon.warnings:
        click.echo(f"foon2asp: warning: {warning}", err=True)
    with open(output, "w", encoding="utf-8") as fh:
        write_foon(foon, fh, header=f"merged by foon2asp from {len(files)} file(s)")
    click.echo(f"merged {len(files)} file(s): {len(foon.units)} units, {len(foon.objects)} objects -> {output}", err=True)


@main.command("methods")
def list_methods():
    """List the registered methods."""
    for name in methods.names():
        m = methods.get(name)
        click.echo(f"{name:16} {m.kind:7} {m.description}")


if __name__ == "__main__":  # pragma: no cover
    main()
