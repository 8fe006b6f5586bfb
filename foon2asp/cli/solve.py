"""``foon2asp solve``: the best task tree for each goal, or one tree for a meal."""

from __future__ import annotations

import sys

import click

from foon2asp import api, report
from foon2asp.cli.main import guarded
from foon2asp.cli.options import (
    gap_option,
    goal_command,
    is_search,
    methods_of,
    progress_option,
    solver_options,
    time_limit_option,
    together_option,
)
from foon2asp.cli.output import echo_now, exit_code, goal_progress, progress_bar, solver_of, warn
from foon2asp.errors import InputError
from foon2asp.report import draw
from foon2asp.report.trees import render, render_bytes

#: formats whose rendering of several trees is the renderings of each, joined by this: streamed
STREAMED = {"text": "\n", "foon": "", "jsonl": ""}


def safe_name(index: int, label: str) -> str:
    keep = "".join(c if c.isalnum() else "_" for c in label).strip("_")[:60] or "goal"
    return f"{index:03d}-{keep}"


def written(trees: list) -> str:
    """What a file written by ``solve -o DIR`` holds: ``optimal``, ``found, INVALID``, ..."""
    return "; ".join(t.status + (", INVALID" if t.has_tree and t.extra.get("valid") is False else "") for t in trees)


@goal_command("trees", methods="asp")
@click.option(
    "-o",
    "--output",
    type=click.Path(file_okay=False),
    help="A FOLDER: write one file per goal (and method) there, and print one line per file written.",
)
@time_limit_option("Seconds per goal; the best tree so far is reported as 'feasible'.")
@gap_option
@together_option("A meal: one tree that makes every goal, units shared between dishes counted once (ASP methods).")
@solver_options
@progress_option
@guarded
def solve(data, goal, goals, method_list, fmt, output, together, options, progress):
    """Find the best task tree for each goal (default: the goals file's goals; with --together:
    one tree for all goals).

    Text, FOON and JSON-lines output is printed goal by goal as each is solved.
    """
    names = methods_of(method_list)
    kb, jobs = data.load_goals(goal, goals, together)
    search = [m for m in names if is_search(m)]
    if together and search:
        raise InputError(f"--together needs an ASP method; {', '.join(search)} are search baselines")
    if search and options.solver_settings:
        raise InputError(f"solver settings apply to ASP methods only; {', '.join(search)} are search baselines")
    status_line = goal_progress(progress)
    if status_line is not None:
        options = api.Options.of(options, on_progress=status_line)
    solver = solver_of(kb, options)
    problem = kb.problem
    binary = report.get("trees", fmt).binary
    if fmt in draw.FORMATS and fmt != "dot":
        draw.require_dot()  # before solving, not after
    out_dir = api.writable_dir(output) if output else None
    ext = report.get("trees", fmt).extension
    sep = None if binary else STREAMED.get(fmt)
    held: list = []
    answers: list[tuple[str, object]] = []
    printed = 0
    for method in names:
        trees = kb.solve_iter(jobs, method, solver)
        for index, tree in enumerate(progress_bar(trees, len(jobs), progress, f"solve {method}"), 1):
            if is_search(method):
                tree.judge()  # "valid" for search baselines, as compare gives it
            ranked = tree.with_alternatives  # --models / --all-optimal: the further trees, best first
            found = [t.raw for t in ranked]
            answers += [(t.status, t.extra.get("valid")) for t in found]
            for t in ranked:
                if t.note is not None:
                    warn(f"{t.goal.label}: {t.note}")
            if out_dir:  # the files, and one line per file on stdout
                suffix = f"-{method}" if len(names) > 1 else ""
                label = "+".join(g.label for g in tree.goals)
                path = out_dir / f"{safe_name(index, label)}{suffix}.{ext}"
                api.write_file(path, render_bytes(problem, found, fmt))
                echo_now(f"wrote {path} ({written(found)})", status_line, nl=True)
            elif sep is None:
                held.extend(found)
            else:
                echo_now((sep if printed else "") + render(problem, found, fmt), status_line)
                printed += 1
    if status_line is not None:
        status_line.close()
    if binary and not out_dir:
        sys.stdout.buffer.write(render_bytes(problem, held, fmt))
    elif sep is None and not out_dir:
        click.echo(render(problem, held, fmt), nl=False)
    sys.exit(exit_code(answers))
