"""The commands on goals: solve, compare, missing, reachable, schedule and batch."""

from __future__ import annotations

import re
import sys

import click

from foon2asp import api, report
from foon2asp.cli import flags as opt
from foon2asp.cli.flags import Checked, command, goal_command
from foon2asp.cli.main import (
    EXIT_CODES,
    echo_now,
    emit,
    exit_code,
    goal_progress,
    progress_bar,
    solver_of,
    warn_all,
    warn_request,
)
from foon2asp.errors import InputError
from foon2asp.report import draw
from foon2asp.report.tree_formats import render, render_bytes


def methods_of(values: tuple[str, ...], default: list[str] | tuple[str, ...] = ("asp",)) -> list[str]:
    """The names of ``--method`` (each checked), else ``default``."""
    names = [n.strip() for v in values for n in v.split(",") if n.strip()]
    for name in names:
        api.method(name)
    return list(dict.fromkeys(names)) or list(default)


def is_search(name: str) -> bool:
    """Is ``name`` a search baseline (no solver, no constraints)?"""
    return api.method(name).kind != "asp"


# ---------------------------------------------------------------- solve

#: formats whose rendering of several trees is the renderings of each, joined by this: streamed
STREAMED = {"text": "\n", "foon": "", "jsonl": ""}


def safe_name(index: int, label: str) -> str:
    keep = "".join(c if c.isalnum() else "_" for c in label).strip("_")[:60] or "goal"
    return f"{index:03d}-{keep}"


def written(trees: list) -> str:
    """What a file written by ``solve -o DIR`` holds: ``optimal``, ``found, INVALID``, ..."""
    return "; ".join(t.status + (", INVALID" if t.has_tree and t.valid is False else "") for t in trees)


#: --max-depth, --human-steps, --models, --all-optimal and :data:`~foon2asp.cli.flags.STRATEGY`
SOLVER = [
    opt.option(
        "--max-depth",
        "Only trees of at most N sequential rounds (the goal's level); with --objective depth, the search stops there.",
        type=opt.int32(min=1),
    ),
    opt.option(
        "--human-steps",
        "At most M units may be done by a person (success 1.0); the solver picks them, the output marks them.",
        type=opt.int32(min=0),
    ),
    opt.option("--models", "The K best distinct trees per goal, best first.", type=opt.int32(min=1), default=1),
    opt.flag("--all-optimal", "Every optimal tree per goal (at most 100)."),
    *opt.STRATEGY,
]


#: answers by polynomial reasoning, or clingo's for every goal that can be made
SHORTCUTS = opt.option(
    "--shortcuts/--no-shortcuts",
    "Let preparation answer a goal it proves (one tree in the goal's part; a checkable lower bound met by"
    " the bounds tree); --no-shortcuts: clingo answers every goal that can be made.",
    default=True,
)


@goal_command(
    "trees",
    opt.output_option(
        "A FOLDER: write one file per goal (and method) there, and print one line per file written.", file=False
    ),
    opt.time_limit_option(),
    opt.GAP_OPTION,
    opt.flag(
        "--together", "A meal: one tree that makes every goal, units shared between dishes counted once (ASP methods)."
    ),
    SOLVER,
    SHORTCUTS,
    opt.PROGRESS,
    methods="asp",
)
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
            answers += [(t.status, t.valid) for t in found]
            warn_all(f"{t.goal.label}: {t.note}" for t in ranked if t.note is not None)
            if out_dir:
                suffix = f"-{method}" if len(names) > 1 else ""
                label = "+".join(g.label for g in tree.goals)
                path = out_dir / f"{safe_name(index, label)}{suffix}.{report.get('trees', fmt).extension}"
                api.write_file(path, render_bytes(problem, found, fmt))
                echo_now(f"wrote {path} ({written(found)})", status_line, nl=True)
            elif sep is None:
                held.extend(found)
            else:
                echo_now((sep if printed else "") + render(problem, found, fmt), status_line)
                printed += 1
    if status_line is not None:
        status_line.close()
    if sep is None and not out_dir:
        emit((render_bytes if binary else render)(problem, held, fmt), None, "")
    sys.exit(exit_code(answers))


# ---------------------------------------------------------------- compare, missing, reachable


@goal_command(
    "compare",
    opt.time_limit_option("Seconds per goal for ASP methods."),
    opt.GAP_OPTION,
    opt.flag("--together", "A meal: the one tree for all goals beside the sum of the single optima (ASP)."),
    opt.STRATEGY,
    opt.PROGRESS,
    methods=",".join(api.COMPARE_METHODS),
)
def compare(data, goal, goals, method_list, fmt, together, options, progress):
    """Compare methods goal by goal: units, validity, success product, depth (default: the goals file's goals).

    --format jsonl prints each goal's results as soon as it is done.  With --together: the
    meal's tree (one tree for every goal) beside the sum of the single optima.
    """
    names = methods_of(method_list, api.COMPARE_METHODS)
    kb, goal_ids = data.load_goals(goal, goals)
    search = [n for n in names if is_search(n)]
    if options.constraints and search:
        warn_request([f"constraints apply to ASP methods only; {', '.join(search)} ignore them"])
    solver = solver_of(kb, options)
    if together:
        asp = [n for n in names if not is_search(n)]
        meal = kb.compare_meal(goal_ids, (asp or ["asp"])[0], options=solver)
        click.echo(report.render("compare", fmt, kb.problem, meal), nl=False)
        sys.exit(exit_code([(meal.meal.status, meal.meal.valid)]))
    rows = []
    for part in progress_bar(kb.compare_iter(goal_ids, names, solver), len(goal_ids), progress, "compare"):
        rows.extend(part.raw)
        if fmt == "jsonl":
            echo_now(part.render(fmt))
    if fmt != "jsonl":
        click.echo(api.Comparison(kb, rows).render(fmt), nl=False)
    sys.exit(exit_code((t.status, t.valid) for r in rows for t in r.trees.values()))


@goal_command(
    "missing",
    opt.time_limit_option("Seconds per goal; the best answer so far is reported as 'feasible'."),
    opt.flag("--together", "A meal: the fewest objects so that one tree makes every goal."),
    opt.STRATEGY,
    opt.PROGRESS,
    objective_help="After the fewest added objects, the best tree by these objectives (units, success, inputs, cost"
    " with --motion-cost), comma-separated.",
)
def missing(data, goal, goals, fmt, together, options, progress):
    """The fewest objects to add to the kitchen so a goal can be made (proven minimal), and the tree.

    Default goals: the goals file's.  With --together: the fewest objects for the whole meal.
    """
    kb, jobs = data.load_goals(goal, goals, together)
    solver = solver_of(kb, options)  # the request checked, its warnings first
    results = []
    for g in progress_bar(jobs, len(jobs), progress, "missing"):
        results.append(kb.missing(g, options=solver).raw)
        if fmt == "jsonl":
            click.echo(report.render("missing", fmt, kb.problem, results[-1:]), nl=False)
    if fmt != "jsonl":
        click.echo(report.render("missing", fmt, kb.problem, results), nl=False)
    sys.exit(exit_code((r.status, None) for r in results))


@command(opt.DATA, opt.GOALS, opt.format_option("reachable"))
def reachable(data, goal, goals, fmt, options):
    """Which goals (or objects) can be made from the kitchen at all, in one solve (default: the goals file's goals)."""
    kb, goal_ids = data.load_goals(goal, goals)
    click.echo(kb.reachability(goal_ids, options=options).render(fmt), nl=False)


# ---------------------------------------------------------------- schedule

#: statuses of a schedule that answer its goal (exit status 0)
SCHEDULED = ("optimal", "unschedulable", "unreachable")


def status_text(info: dict) -> str:
    """``schedule greek salad: makespan 65 s, lower bound 62.5 s`` (the makespan phase), or
    ``...: makespan 40 s (proven), human units 15, at least 11`` (the human units)."""
    head = f"schedule {info.get('goal', '')}: makespan {api.seconds_text(info['makespan'])} s"
    if info.get("phase") == "human":
        return f"{head} (proven), human units {info['human']}, at least {info['human_lower']}"
    return f"{head}, lower bound {api.seconds_text(info['lower'])} s"


@goal_command(
    None,
    opt.time_limit_option(
        "Seconds per solve (tree, schedule; with --joint also the search over trees); a schedule cut short is"
        " 'feasible': the best found, with its lower bound. Without it the tree has no limit and each schedule"
        f" solve {api.SCHEDULE_TIME_LIMIT:g} s."
    ),
    opt.SCHEDULE,
    opt.flag(
        "--joint",
        "Choose tree and schedule together: the makespan is minimal over every valid tree (the fixed tree's"
        " is reported beside it).",
    ),
    opt.choice(
        "--format fmt",
        "text: a timeline per agent; json: a list, one object per goal; svg/png/pdf/dot: Gantt charts;"
        " html: a page of them.",
        ["text", "json", *report.names("schedule")],
    ),
    opt.output_option("Write to FILE instead of stdout (png, pdf: binary)."),
    opt.choice(
        "--encoding",
        "Time steps in plain ASP, or clingo-dl start times (needs clingo-dl).",
        api.SCHEDULE_ENCODINGS,
        default=api.DEFAULT_SCHEDULE_ENCODING,
    ),
    opt.flag("--together", "A meal: one tree that makes every goal, and one schedule of it."),
    opt.STRATEGY,
    opt.PROGRESS,
    objective_help="The tree's objective(s), comma-separated (units, success, inputs, depth, cost): the tree"
    " scheduled, or with --joint the tie-breaker after makespan and human units.",
    epilog="""\b
Exit codes: 0 every goal answered (makespan proven, or unschedulable or unreachable);
1 some makespan is not proven (time limit); 2 bad input or usage; 130 interrupted.""",
)
def schedule(data, goal, goals, spec, joint, fmt, output, encoding, together, progress, options):
    """Schedule each goal's task tree (the best by --objective) on the agents: who does which unit
    when, with the makespan proven minimal, the list-scheduling baseline and the lower bounds.

    A unit starts when the units making its required inputs have finished; an agent does one
    unit at a time; capabilities and resources hold. Ties of makespan go to fewer units done by
    a 'human' agent, then to the tree objective. Text output is printed goal by goal.
    """
    kb, jobs = data.load_goals(goal, goals, together)
    solver = solver_of(kb, options)
    if fmt not in ("text", "json", "dot"):
        draw.require_dot()  # before solving, not after
    status = goal_progress(progress, status_text)
    found = kb.schedule_iter(jobs, spec, solver, joint=joint, encoding=encoding, progress=status)
    done: list = []
    stream = fmt == "text" and output is None
    for s in progress_bar(found, len(jobs), progress, "schedule"):
        if status is not None:
            status.close()
        done.append(s)
        if stream:
            echo_now(("\n" if len(done) > 1 else "") + s.to_text())
    if fmt == "text":
        out: str | bytes = "\n".join(s.to_text() for s in done)
    elif fmt == "json":
        out = api.schedules_json(done)
    else:
        out = report.render_bytes("schedule", fmt, [s.to_dict() for s in done])
    if not stream:
        emit(out, output, f"wrote {len(done)} schedule(s) as {fmt}")
    sys.exit(0 if all(s.status in SCHEDULED for s in done) else 1)


# ---------------------------------------------------------------- batch


def _workers(text: str) -> int | str:
    if text.lower() == "auto":
        return "auto"
    try:
        number = int(text)
    except ValueError:
        raise ValueError(f"{text!r} is not a number of workers or 'auto'") from None
    if not 1 <= number <= 1024:
        raise ValueError(f"{number} is not in 1..1024 (or 'auto')")
    return number


_ADDRESS = re.compile(r"^(?:(tcp|tls|inproc|ucx|ws|wss)://)?(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.\-]+)(?::(\d{1,5}))?/?$")


def _address(text: str) -> str:
    m = _ADDRESS.match(text)
    expected = "(expected [tcp://]HOST:PORT, e.g. tcp://127.0.0.1:8786)"
    if m is None:
        raise ValueError(f"{text!r} is not a scheduler address {expected}")
    if m.group(3) is None and m.group(1) != "inproc":
        raise ValueError(f"{text!r} has no port {expected}")
    if m.group(3) is not None and not 0 < int(m.group(3)) < 65536:
        raise ValueError(f"port {m.group(3)} of {text!r} is not in 1..65535")
    return text


#: a number of worker processes (1..1024) or "auto", the ``[PROTOCOL://]HOST[:PORT]`` of a Dask scheduler
WORKERS, SCHEDULER = Checked("N|auto", _workers), Checked("address", _address)


@command(
    opt.DATA,
    opt.GOALS,
    opt.method_option("asp"),
    opt.objective_options(),
    opt.output_option("A FILE of results, one JSON line per (goal, method).", default="results.jsonl"),
    opt.flag("--resume", "Continue OUTPUT: skip the (goal, method) pairs it already holds for the same configuration."),
    opt.option(
        "--workers",
        "Worker processes; auto: this process, and once the batch has run 5 s the rest on every usable core.",
        type=WORKERS,
        metavar="N|auto",
        default="auto",
    ),
    opt.option(
        "--scheduler", "Run on this Dask scheduler (needs the 'dask' extra).", type=SCHEDULER, metavar="ADDRESS"
    ),
    opt.time_limit_option(),
    opt.GAP_OPTION,
    opt.STRATEGY,
    opt.choice(
        "--grounding",
        "One grounding for all goals, or a small grounding of each goal's relevant part; auto: per-goal when"
        " the goals' median relevant part is under 10 % of the viable units or there are over 50,000 of them"
        " (the summary says which).",
        api.GROUNDINGS,
        default="auto",
    ),
    SHORTCUTS,
    opt.choice("--summary summary_fmt", "Format of the summary printed at the end.", report.names("summary")),
    opt.PROGRESS,
    opt.option(
        "--fsync/--no-fsync", "Sync result lines to disk (grouped: at most 0.25 s apart, and at the end).", default=True
    ),
    opt.CONSTRAINTS,
    opt.flag(
        "--schedule with_schedules",
        "Also schedule each goal's tree (of the first method) on the agents of the schedule options, into"
        " OUTPUT with the suffix .schedules.json (a JSON list as 'schedule --format json' writes).",
    ),
    opt.SCHEDULE,
    epilog=EXIT_CODES,
)
def batch(data, goal, goals, method_list, output, summary_fmt, with_schedules, spec, options, **run_options):
    """Solve many goals with several methods; resumable JSON-lines output and a summary.

    Every result line carries "valid" (the independent validator's verdict); the
    summary counts the valid trees per method. Default goals: the goals file's.
    """
    names = methods_of(method_list)
    if options.solver_settings and all(is_search(m) for m in names):
        raise InputError(f"solver settings apply to ASP methods only; {', '.join(names)} are search baselines")
    kb, goal_ids = data.load_goals(goal, goals)
    solver = solver_of(kb, options)  # the request checked, its warnings before the run
    # run_options: --workers, --resume, --progress, --fsync and --scheduler, as kb.batch names them
    run = kb.batch(goal_ids, output, methods=names, options=options, **run_options)
    answers = [(r.get("status", "?"), r.get("valid")) for r in run.records]
    if with_schedules:
        path = api.schedules_path(output)
        found = run.schedule(spec, output=path, options=solver)
        click.echo(f"wrote {len(found)} schedule(s) to {path}", err=True)
        answers += [("optimal" if s.status in SCHEDULED else s.status, None) for s in found]
    click.echo(run.render(summary_fmt), nl=False)
    sys.exit(exit_code(answers))
