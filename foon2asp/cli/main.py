"""The ``foon2asp`` command line (one module; subcommands share the loaders)."""

from __future__ import annotations

import functools
import signal
import sys
import traceback
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import click

from foon2asp import api, methods, report
from foon2asp.analysis import compare as compare_mod
from foon2asp.analysis import queries
from foon2asp.asp.constraints import ConstraintSpec, read_file, unknown_names
from foon2asp.asp.facts import facts as facts_text
from foon2asp.asp.multishot.driver import alternatives
from foon2asp.asp.options import OBJECTIVES
from foon2asp.batch import grounding as grounding_mod
from foon2asp.batch import results as batch_results
from foon2asp.cli.options import EXIT_CODES, exit_code, progress_bar
from foon2asp.cli.params import SCHEDULER, SECONDS, int32
from foon2asp.errors import InputError, Terminated, escape
from foon2asp.foon import foonjson
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.parser import id_map, read_foons, write_foon
from foon2asp.foon.problem import UTENSIL_RULES, Problem
from foon2asp.report import draw
from foon2asp.report.trees import render, render_bytes

#: exit statuses: 2 bad input or usage, 3 an internal error, 130 SIGINT, 143 SIGTERM
EXIT_INPUT, EXIT_INTERNAL, EXIT_SIGINT, EXIT_SIGTERM = 2, 3, 130, 143


def fail(message: str, code: int = EXIT_INPUT) -> None:
    click.echo(f"foon2asp: error: {escape(message)}", err=True)
    sys.exit(code)


def _debug() -> bool:
    ctx = click.get_current_context(silent=True)
    return bool(ctx is not None and ctx.find_root().params.get("debug"))


def _terminate(signum, frame) -> None:
    raise Terminated()


def report_exception(exc: BaseException) -> None:
    """Turn any exception of a command into one line on stderr and a documented exit status."""
    if isinstance(exc, Terminated):
        click.echo("foon2asp: terminated", err=True)
        sys.exit(EXIT_SIGTERM)
    if isinstance(exc, KeyboardInterrupt):
        click.echo("foon2asp: interrupted", err=True)
        sys.exit(EXIT_SIGINT)
    if isinstance(exc, InputError):
        fail(str(exc))
    if isinstance(exc, BrokenPipeError):
        sys.exit(0)
    if isinstance(exc, OSError) and exc.filename is not None:
        fail(f"{exc.filename}: {exc.strerror or exc}")
    if isinstance(exc, RecursionError | MemoryError):
        fail(f"input too large or too deeply nested ({type(exc).__name__})")
    if _debug():
        traceback.print_exception(exc)
    fail(
        f"internal error: {type(exc).__name__}: {exc} -- please report it with the command line"
        f"{'' if _debug() else ' (--debug shows the traceback)'}",
        EXIT_INTERNAL,
    )


def guarded(func):
    """Run a command: bad input is one line on stderr and exit status 2, an internal error one line
    and 3 (the traceback with --debug), SIGINT 130, SIGTERM 143; never a traceback otherwise."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except (SystemExit, click.exceptions.Exit, click.ClickException):
            raise
        except BaseException as exc:
            report_exception(exc)

    return wrapper


def writable_dir(path: str | Path) -> Path:
    """``path`` as a directory, created with its parents (an error names the path)."""
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create the output directory: {exc.strerror or exc}", str(out)) from None
    if not out.is_dir():
        raise InputError("output path is not a directory", str(out))
    return out


def write_file(path: str | Path, text: str | bytes) -> None:
    """Write ``text`` to ``path``, creating its directory (an error names the path)."""
    out = Path(path)
    if out.parent != Path("."):
        writable_dir(out.parent)
    try:
        if isinstance(text, bytes):
            out.write_bytes(text)
        else:
            out.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot write the output file: {exc.strerror or exc}", str(out)) from None


class Main(click.Group):
    """The command group: usage errors are one line too, SIGTERM is an interrupt (exit 143)."""

    def main(self, *args: Any, standalone_mode: bool = True, **kwargs: Any) -> Any:
        run: Any = super().main
        if not standalone_mode:
            return run(*args, standalone_mode=False, **kwargs)
        try:
            previous = signal.signal(signal.SIGTERM, _terminate)
        except ValueError:  # not the main thread
            previous = None
        try:
            rv = run(*args, standalone_mode=False, **kwargs)
        except click.exceptions.Exit as exc:
            sys.exit(exc.exit_code)
        except click.ClickException as exc:
            message = " ".join(exc.format_message().split())
            ctx = getattr(exc, "ctx", None)
            name = ctx.command_path if ctx is not None else "foon2asp"
            usage = isinstance(exc, click.UsageError)
            hint = f" (see '{name} --help')" if usage else ""
            where = f"{ctx.info_name}: " if usage and ctx is not None and ctx.parent is not None else ""
            click.echo(f"foon2asp: error: {where}{escape(message)}{hint}", err=True)
            sys.exit(exc.exit_code)
        except click.Abort as exc:
            report_exception(exc.__context__ if isinstance(exc.__context__, KeyboardInterrupt) else KeyboardInterrupt())
        except (SystemExit, BrokenPipeError):
            raise
        except BaseException as exc:
            report_exception(exc)
        finally:
            if previous is not None:
                signal.signal(signal.SIGTERM, previous)
        sys.exit(rv if isinstance(rv, int) else 0)


def data_options(func, with_kitchen: bool = True):
    """--data DIR and the per-file overrides, plus --utensil-rule and --strict, passed on as one
    ``data`` value (:class:`DataArgs`); ``with_kitchen=False`` leaves out ``--kitchen FILE``."""
    opts = [
        click.option(
            "--data",
            "data_dir",
            type=click.Path(),
            help="Directory with FOON.txt, kitchen.json, goal_nodes.json, motion.txt, utensils.txt;"
            " 'demo' for the demo data set shipped with foon2asp.",
        ),
        click.option(
            "--foon",
            "foon",
            type=click.Path(),
            multiple=True,
            help="FOON file(s), several are merged; without --data the other files are read from beside the first.",
        ),
        click.option("--motion", type=click.Path(), help="motion.txt (motion TAB success rate)"),
        click.option("--utensils", type=click.Path(), help="utensils.txt"),
        click.option(
            "--utensil-rule",
            type=click.Choice(UTENSIL_RULES),
            default="starter",
            show_default=True,
            help="When a utensil holding one ingredient is not a required input.",
        ),
        click.option("--strict", is_flag=True, help="Treat skipped FOON units (warnings) as errors."),
    ]
    if with_kitchen:
        opts.insert(2, click.option("--kitchen", type=click.Path(), help="kitchen.json"))

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        values = {k: kwargs.pop(k) for k in DataArgs.__dataclass_fields__ if with_kitchen or k != "kitchen"}
        values.setdefault("kitchen", None)
        return func(*args, data=DataArgs(**values), **kwargs)

    for opt in reversed(opts):
        wrapper = opt(wrapper)
    return wrapper


@dataclass(frozen=True)
class DataArgs:
    """The data options of a command (--data, --foon, --kitchen, --motion, --utensils, --utensil-rule, --strict)."""

    data_dir: str | None
    foon: tuple[str, ...]
    kitchen: str | None
    motion: str | None
    utensils: str | None
    utensil_rule: str
    strict: bool

    def load(self, goals_file: str | None = None) -> api.KnowledgeBase:
        """The knowledge base these options name (``goals_file``: a ``--goals FILE`` to read)."""
        return load(
            self.data_dir,
            self.foon,
            self.kitchen,
            self.motion,
            self.utensils,
            self.utensil_rule,
            self.strict,
            goals_file,
        )


GOAL_HELP = (
    "Goal: a label, an object's text as foon2asp prints it ('tomato, diced, in [plate]') or #ID"
    " from 'foon2asp objects'; repeatable."
)
GOALS_HELP = (
    "FILE of goal objects (e.g. 'foon2asp objects --format json' output), 'all' (the goals file) or"
    " 'all-objects' (every made object). Default without --goal: the goals file."
)


def goal_options(func):
    func = click.option("--goals", "goals", metavar="FILE|all|all-objects", help=GOALS_HELP)(func)
    func = click.option("--goal", "goal", multiple=True, metavar="TEXT", help=GOAL_HELP)(func)
    return func


def method_option(default: str, many: bool = True):
    """``--method``/``--methods`` (the same option): registered names, comma-separated or repeated."""
    return click.option(
        "--methods",
        "--method",
        "method_list",
        multiple=True,
        metavar="NAME[,NAME]",
        help=f"Registered method(s) (see 'foon2asp methods'), comma-separated or repeated (default: {default}).",
    )


def progress_option(func):
    return click.option(
        "--progress/--no-progress", default=None, help="Progress bar on stderr (default: when it is a terminal)."
    )(func)


_CONSTRAINT_KEYS = (
    "constraint",
    "rule",
    "forbid_motion",
    "forbid_object",
    "require_motion",
    "require_object",
    "max_units",
)


def constraint_options(func):
    """--constraint FILE.lp, --rule TEXT and the convenience flags, passed on as ``constraints``
    (a :class:`foon2asp.constraints.ConstraintSpec`; see :func:`constraint_programs`)."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        values = [kwargs.pop(k) for k in _CONSTRAINT_KEYS]
        spec = ConstraintSpec(*(tuple(v) if isinstance(v, tuple) else v for v in values))  # type: ignore[arg-type]
        return func(*args, constraints=spec, **kwargs)

    opts = [
        click.option(
            "--constraint",
            type=click.Path(),
            multiple=True,
            help="ASP file with extra rules over the vocabulary (use/1, motion/2, label/2, ...); repeatable.",
        ),
        click.option(
            "--rule", multiple=True, help="An extra ASP rule, e.g. ':- use(U), motion(U,\"fry\").'; repeatable."
        ),
        click.option(
            "--forbid-motion", multiple=True, metavar="M", help="No unit of the tree has motion M; repeatable."
        ),
        click.option(
            "--forbid-object",
            multiple=True,
            metavar="LABEL",
            help="No unit of the tree has an input or output labelled LABEL; repeatable.",
        ),
        click.option(
            "--require-motion", multiple=True, metavar="M", help="Some unit of the tree has motion M; repeatable."
        ),
        click.option(
            "--require-object",
            multiple=True,
            metavar="LABEL",
            help="Some unit of the tree has an input or output labelled LABEL; repeatable.",
        ),
        click.option("--max-units", type=int32(min=0), help="The tree has at most N units."),
    ]
    for opt in reversed(opts):
        wrapper = opt(wrapper)
    return wrapper


def constraint_programs(spec: ConstraintSpec, problem: Problem | None = None) -> list[tuple[str, str]]:
    """The (name, text) programs for AspOptions.programs; names no motion/label matches are warned about."""
    if problem is not None:
        for warning in unknown_names(problem, spec):
            click.echo(f"foon2asp: warning: {warning}", err=True)
    return spec.programs()


def load(data_dir, foon, kitchen, motion, utensils, utensil_rule, strict, goals_file=None) -> api.KnowledgeBase:
    """Read the data through the library; warnings go to stderr.  Never the demo data unless asked."""
    if data_dir is None and not foon:
        raise InputError("no data given: use --data DIR, --foon FILE (with kitchen.json ... beside it) or --data demo")
    goals_path = goals_file if goals_file not in (None, "all", "all-objects") else None
    kb = api.load(
        data_dir,
        foon=list(foon) if foon else None,
        kitchen=kitchen,
        goals=goals_path,
        motion=motion,
        utensils=utensils,
        utensil_rule=utensil_rule,
        strict=strict,
    )
    _warn(kb)
    return kb


def _warn(kb: api.KnowledgeBase) -> None:
    for warning in kb.warnings:
        click.echo(f"foon2asp: warning: {escape(warning)}", err=True)
    kb.warnings.clear()


def _constraints(spec: ConstraintSpec) -> api.Constraints:
    return api.Constraints(
        spec.forbid_motion,
        spec.forbid_object,
        spec.require_motion,
        spec.require_object,
        spec.max_units,
        spec.rules,
        spec.files,
    )


def _objective(value: str) -> tuple[str, ...]:
    parts = tuple(p.strip() for p in value.split(",") if p.strip())
    for p in parts:
        if p not in OBJECTIVES:
            raise InputError(f"unknown objective {p!r} (have {', '.join(OBJECTIVES)})")
    return parts or ("units",)


_SOLVER_KEYS = ("max_depth", "human_steps", "models", "all_optimal", "opt_strategy", "threads")
SOLVER_DEFAULTS = {
    "max_depth": None,
    "human_steps": None,
    "models": 1,
    "all_optimal": False,
    "opt_strategy": None,
    "threads": 1,
}


def _opt_strategy(ctx, param, value):
    if value is not None and value.split(",")[0] not in ("bb", "usc"):
        raise click.BadParameter("expected bb or usc, optionally with clingo's refinements (e.g. usc,oll or bb,hier)")
    return value


def solver_options(func):
    """--max-depth, --human-steps, --models, --all-optimal, --opt-strategy, --threads, passed on
    as ``solver_settings`` (keyword arguments of AspOptions)."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        settings = {k: kwargs.pop(k) for k in _SOLVER_KEYS}
        if settings["models"] > 1 and settings["all_optimal"]:
            raise click.UsageError("--models and --all-optimal exclude each other")
        return func(*args, solver_settings=settings, **kwargs)

    opts = [
        click.option(
            "--max-depth",
            type=int32(min=1),
            help="Only trees of at most N sequential rounds (the goal's level); with --objective depth, the search stops there.",
        ),
        click.option(
            "--human-steps",
            type=int32(min=0),
            help="At most M units may be done by a person (success 1.0); the solver picks them, the output marks them.",
        ),
        click.option(
            "--models",
            type=int32(min=1),
            default=1,
            show_default=True,
            help="The K best distinct trees per goal, best first.",
        ),
        click.option("--all-optimal", is_flag=True, help="Every optimal tree per goal (at most 100)."),
        click.option(
            "--opt-strategy",
            callback=_opt_strategy,
            help="clingo optimisation strategy: bb (branch and bound) or usc (core-guided), e.g. usc,oll;"
            " default usc,oll,succinct, or with --threads 2+ a portfolio of one bb and one usc solver.",
        ),
        click.option(
            "--threads",
            type=int32(min=1, max=64),
            default=1,
            show_default=True,
            help="clingo solver threads (parallel mode).",
        ),
    ]
    for opt in reversed(opts):
        wrapper = opt(wrapper)
    return wrapper


def strategy_options(func):
    """--opt-strategy and --threads (None and 1: the defaults of foon2asp.asp.settings)."""
    func = click.option(
        "--threads",
        type=int32(min=1, max=64),
        default=1,
        show_default=True,
        help="clingo solver threads; 2 or more without --opt-strategy: a bb and a usc solver side by side.",
    )(func)
    return click.option(
        "--opt-strategy",
        callback=_opt_strategy,
        help="clingo optimisation strategy: bb (branch and bound) or usc (core-guided), e.g. usc,oll; default usc,oll,succinct.",
    )(func)


def _solver_warnings(problem: Problem, trees: list) -> None:
    for tree in trees:
        if "note" in tree.extra:
            click.echo(f"foon2asp: warning: {problem.objects[tree.goal].label}: {tree.extra['note']}", err=True)


def safe_name(index: int, label: str) -> str:
    keep = "".join(c if c.isalnum() else "_" for c in label).strip("_")[:60] or "goal"
    return f"{index:03d}-{keep}"


@click.group(cls=Main, context_settings={"help_option_names": ["-h", "--help"]}, epilog=EXIT_CODES)
@click.version_option(package_name="foon2asp")
@click.option("--debug", is_flag=True, help="On an internal error (exit status 3), also print the traceback.")
def main(debug):
    """foon2asp: minimal, well-founded FOON task trees with answer-set programming.

    Exit status: 0 success, 1 a negative answer (check: invalid tree; query:
    unsatisfiable), 2 bad input or usage, 3 an internal error, 130 interrupted
    (SIGINT), 143 terminated (SIGTERM).
    """


#: formats whose rendering of several trees is the renderings of each, joined by this: streamed
STREAMED = {"text": "\n", "foon": "", "jsonl": ""}


@main.command(epilog=EXIT_CODES)
@data_options
@goal_options
@constraint_options
@method_option("asp")
@click.option(
    "--objective", default="units", show_default=True, help="ASP objective(s), comma-separated, most important first."
)
@click.option("--format", "fmt", type=click.Choice(report.names("trees")), default="text", show_default=True)
@click.option(
    "-o",
    "--output",
    type=click.Path(file_okay=False),
    help="A FOLDER: also write one file per goal (and method) there.",
)
@click.option("--time-limit", type=SECONDS, help="Seconds per goal; the best tree so far is reported as 'feasible'.")
@click.option(
    "--together",
    is_flag=True,
    help="A meal: one tree that makes every goal, units shared between dishes counted once (ASP methods).",
)
@solver_options
@progress_option
@guarded
def solve(
    data,
    goal,
    goals,
    method_list,
    objective,
    fmt,
    output,
    time_limit,
    together,
    constraints,
    solver_settings,
    progress,
):
    """Find the best task tree for each goal (default: the goals file's goals; with --together:
    one tree for all goals).

    Text, FOON and JSON-lines output is printed goal by goal as each is solved.
    """
    names = _method_list(method_list)
    kb = data.load(goals)
    goal_ids = goals_mod.resolve(kb.data, kb.problem, goal, goals)
    search = [m for m in names if methods.get(m).kind != "asp"]
    if together and search:
        raise InputError(f"--together needs an ASP method; {', '.join(search)} are search baselines")
    if search and solver_settings != SOLVER_DEFAULTS:
        raise InputError(f"solver settings apply to ASP methods only; {', '.join(search)} are search baselines")
    options = kb.options(objective, time_limit, _constraints(constraints), **solver_settings)
    _warn(kb)
    problem = kb.problem
    binary = report.get("trees", fmt).binary
    if fmt in draw.FORMATS and fmt != "dot":
        draw.require_dot()  # before solving, not after
    out_dir = writable_dir(output) if output else None
    ext = report.get("trees", fmt).extension
    sep = None if binary else STREAMED.get(fmt)
    held: list = []
    answers: list[tuple[str, object]] = []
    printed = 0
    jobs: list = [tuple(dict.fromkeys(goal_ids))] if together else goal_ids
    for method in names:
        trees = kb.solve_iter(jobs, method, options)
        for index, tree in enumerate(progress_bar(trees, len(jobs), progress, f"solve {method}"), 1):
            if methods.get(method).kind != "asp":
                compare_mod.judge(problem, tree.raw)  # "valid" for search baselines, as compare gives it
            found = alternatives(tree.raw)  # --models / --all-optimal: the further trees, best first
            answers += [(t.status, t.extra.get("valid")) for t in found]
            _solver_warnings(problem, found)
            if out_dir:
                suffix = f"-{method}" if len(names) > 1 else ""
                label = "+".join(g.label for g in tree.goals)
                write_file(out_dir / f"{safe_name(index, label)}{suffix}.{ext}", render_bytes(problem, found, fmt))
            if sep is None:
                held.extend(found)
                continue
            text = render(problem, found, fmt)
            click.echo((sep if printed else "") + text, nl=False)
            sys.stdout.flush()
            printed += 1
    if binary and out_dir:
        click.echo(f"wrote {len(jobs) * len(names)} {fmt} file(s) to {out_dir}", err=True)
    elif binary:
        sys.stdout.buffer.write(render_bytes(problem, held, fmt))
    elif sep is None:
        click.echo(render(problem, held, fmt), nl=False)
    sys.exit(exit_code(answers))


@main.command()
@data_options
@click.option(
    "--goals", "goals", metavar="FILE|all|all-objects", help="Goals for goal_node/2 facts (default: the goals file)."
)
@click.option("--goal", "goal", multiple=True, metavar="TEXT", help="Also fix goal(O) for this goal. " + GOAL_HELP)
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="A FILE to write the facts to (default: stdout).")
@guarded
def facts(data, goals, goal, output):
    """Write the FOON, kitchen and goals as ASP facts."""
    kb = data.load(goals)
    text = facts_text(kb.problem, goal_nodes=_goal_nodes(kb, goals))
    fixed = goals_mod.resolve(kb.data, kb.problem, goal, None) if goal else []
    text += "".join(f"goal({g}).\n" for g in fixed)
    if output:
        write_file(output, text)
        click.echo(f"wrote {len(text.splitlines())} lines to {output}", err=True)
    else:
        click.echo(text, nl=False)


def _goal_nodes(kb: api.KnowledgeBase, goals: str | None) -> list[int]:
    """goal_node/2 facts: ``--goals FILE|all|all-objects``, else the goals file's entries (if any)."""
    if goals:
        return goals_mod.resolve(kb.data, kb.problem, (), goals)
    path = kb.data.paths.get("goals")
    return [goals_mod.goal_id(kb.problem, obj, path, line) for obj, line in kb.data.goals]


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path())
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The merged FOON file.")
@click.option("--strict", is_flag=True, help="Treat skipped units (warnings) as errors.")
@click.option(
    "--format",
    "fmt",
    type=click.Choice(("foon", "foon-plain", "foon-json")),
    default="foon",
    show_default=True,
    help="foon: official dialect with ids; foon-plain: without ids; foon-json: foon_api's JSON.",
)
@guarded
def merge(files, output, strict, fmt):
    """Merge FOON subgraphs into one universal FOON (duplicate units merged)."""
    for f in files:
        if not Path(f).is_file():
            raise InputError("FOON file not found", f)
    foon = read_foons(files, strict)
    for warning in foon.warnings:
        click.echo(f"foon2asp: warning: {warning}", err=True)
    header = f"merged by foon2asp from {len(files)} file(s)"
    if Path(output).parent != Path("."):
        writable_dir(Path(output).parent)
    try:
        with open(output, "w", encoding="utf-8") as fh:
            if fmt == "foon-json":
                fh.write(foonjson.dumps(foon.units, id_map(foon), header))
            else:
                write_foon(foon, fh, header=header, dialect="plain" if fmt == "foon-plain" else "official")
    except OSError as exc:
        raise InputError(f"cannot write the output file: {exc.strerror or exc}", output) from None
    click.echo(
        f"merged {len(files)} file(s): {len(foon.units)} units, {len(foon.objects)} objects -> {output}", err=True
    )


@main.command("methods")
def list_methods():
    """List the registered methods."""
    for name in methods.names():
        m = methods.get(name)
        click.echo(f"{name:16} {m.kind:7} {m.description}")


@main.command()
@click.argument("tree", type=click.Path())
@data_options
@click.option(
    "--goal",
    "goal",
    multiple=True,
    metavar="TEXT",
    help="The goal (a label, an object's text or #ID; repeat for a meal); default: the goal the file names"
    " (a JSON result, or the '# task tree for ...' line of solve --format foon), else the tree's only sink.",
)
@click.option(
    "--goals",
    "goals",
    metavar="FILE|all",
    help="Several goals (a goals file, or 'all' for the goals file): each tree's goal is the one of them it makes.",
)
@click.option("--format", "fmt", type=click.Choice(report.names("check")), default="text", show_default=True)
@click.option(
    "--optimum/--no-optimum", default=True, show_default=True, help="Also solve the ASP optimum to compare with."
)
@guarded
def check(tree, data, goal, goals, fmt, optimum):
    """Check the task tree(s) in TREE (FOON text with // between units, FOON JSON or foon2asp JSON),
    or a plan for a problem of 'export pddl' ('(action-name)' lines, as Fast Downward writes them).

    \b
    Exit codes: 0 every tree valid; 1 some tree invalid; 2 bad input or usage;
    130 interrupted.
    """
    kb = data.load(goals)
    among = None
    if goals:
        among = [kb.problem.objects[g] for g in goals_mod.resolve(kb.data, kb.problem, (), goals)]
    reports = kb.check_all(tree, list(goal) or None, optimum, among)
    click.echo(report.render("check", fmt, kb.problem, [r.raw for r in reports]), nl=False)
    sys.exit(0 if all(r.valid for r in reports) else 1)


@main.command(epilog=EXIT_CODES)
@data_options
@goal_options
@constraint_options
@method_option("ids,gbfs-h1,gbfs-h2,asp")
@click.option(
    "--objective", default="units", show_default=True, help="ASP objective(s), comma-separated, most important first."
)
@click.option("--format", "fmt", type=click.Choice(report.names("compare")), default="text", show_default=True)
@click.option("--time-limit", type=SECONDS, help="Seconds per goal for ASP methods.")
@click.option(
    "--together", is_flag=True, help="A meal: the one tree for all goals beside the sum of the single optima (ASP)."
)
@strategy_options
@progress_option
@guarded
def compare(
    data,
    goal,
    goals,
    method_list,
    objective,
    fmt,
    time_limit,
    together,
    opt_strategy,
    threads,
    constraints,
    progress,
):
    """Compare methods goal by goal: units, validity, success product, depth (default: the goals file's goals).

    --format jsonl prints each goal's results as soon as it is done.  With --together: the
    meal's tree (one tree for every goal) beside the sum of the single optima.
    """
    names = _method_list(method_list, list(compare_mod.DEFAULT_METHODS))
    kb = data.load(goals)
    goal_ids = goals_mod.resolve(kb.data, kb.problem, goal, goals)
    search = [n for n in names if methods.get(n).kind != "asp"]
    if constraints and search:
        click.echo(
            f"foon2asp: warning: constraints apply to ASP methods only; {', '.join(search)} ignore them", err=True
        )
    if together:
        asp = [n for n in names if methods.get(n).kind == "asp"]
        meal = kb.compare_meal(
            goal_ids,
            (asp or ["asp"])[0],
            objective=objective,
            time_limit=time_limit,
            constraints=_constraints(constraints),
            opt_strategy=opt_strategy,
            threads=threads,
        )
        _warn(kb)
        click.echo(report.render("compare", fmt, kb.problem, meal), nl=False)
        sys.exit(exit_code([(meal.meal.status, meal.meal.extra.get("valid"))]))
    options = kb.options(objective, time_limit, _constraints(constraints), opt_strategy=opt_strategy, threads=threads)
    _warn(kb)
    rows = []
    parts = kb.compare_iter(goal_ids, names, options)
    for part in progress_bar(parts, len(goal_ids), progress, "compare"):
        rows.extend(part.raw)
        if fmt == "jsonl":
            click.echo(part.render(fmt), nl=False)
            sys.stdout.flush()
    if fmt != "jsonl":
        click.echo(api.Comparison(kb, rows).render(fmt), nl=False)
    sys.exit(exit_code((t.status, t.extra.get("valid")) for r in rows for t in r.trees.values()))


@main.command()
@data_options
@goal_options
@click.option("--format", "fmt", type=click.Choice(report.names("reachable")), default="text", show_default=True)
@guarded
def reachable(data, goal, goals, fmt):
    """Which goals (or objects) can be made from the kitchen at all, in one solve (default: the goals file's goals)."""
    kb = data.load(goals)
    goal_ids = goals_mod.resolve(kb.data, kb.problem, goal, goals)
    answers = queries.reachable(kb.problem, goal_ids)
    click.echo(report.render("reachable", fmt, kb.problem, answers), nl=False)


@main.command(epilog=EXIT_CODES)
@data_options
@goal_options
@constraint_options
@click.option(
    "--objective",
    default="units",
    show_default=True,
    help="After the fewest added objects, the best tree by these objectives (units, success, inputs), comma-separated.",
)
@click.option("--format", "fmt", type=click.Choice(report.names("missing")), default="text", show_default=True)
@click.option("--time-limit", type=SECONDS, help="Seconds per goal; the best answer so far is reported as 'feasible'.")
@click.option("--together", is_flag=True, help="A meal: the fewest objects so that one tree makes every goal.")
@strategy_options
@progress_option
@guarded
def missing(
    data,
    goal,
    goals,
    objective,
    fmt,
    time_limit,
    together,
    opt_strategy,
    threads,
    constraints,
    progress,
):
    """The fewest objects to add to the kitchen so a goal can be made (proven minimal), and the tree.

    Default goals: the goals file's.  With --together: the fewest objects for the whole meal.
    """
    kb = data.load(goals)
    goal_ids = goals_mod.resolve(kb.data, kb.problem, goal, goals)
    spec = _constraints(constraints)
    kb.options(objective, time_limit, spec)  # checks the names, warns about unknown ones
    _warn(kb)
    results = []
    jobs: list = [goal_ids] if together else goal_ids
    for g in progress_bar(jobs, len(jobs), progress, "missing"):
        answer = kb.missing(
            g, time_limit=time_limit, constraints=spec, objective=objective, opt_strategy=opt_strategy, threads=threads
        )
        results.append(answer.raw)
        if fmt == "jsonl":
            click.echo(report.render("missing", fmt, kb.problem, results[-1:]), nl=False)
    if fmt != "jsonl":
        click.echo(report.render("missing", fmt, kb.problem, results), nl=False)
    sys.exit(exit_code((r.status, None) for r in results))


@main.command()
@click.argument("program", type=click.Path())
@data_options
@click.option(
    "--goals", "goals", metavar="FILE|all|all-objects", help="Goals for goal_node/2 facts (default: the goals file)."
)
@click.option("--goal", "goal", metavar="TEXT", help="Also add goal(O) for this goal. " + GOAL_HELP)
@click.option(
    "--encoding",
    "encoding_names",
    multiple=True,
    help="Also load a shipped encoding (tree, units, success, inputs, reachable, missing) and what it needs; repeatable.",
)
@click.option(
    "--models",
    type=int32(min=0),
    default=1,
    show_default=True,
    help="Models to print (0 = all); with an objective, the optimum.",
)
@click.option("--format", "fmt", type=click.Choice(report.names("query")), default="text", show_default=True)
@click.option("--time-limit", type=SECONDS, help="Seconds for the solve.")
@guarded
def query(
    program,
    data,
    goals,
    goal,
    encoding_names,
    models,
    fmt,
    time_limit,
):
    """Run your ASP PROGRAM with the FOON facts; print its shown atoms with ids as readable objects.

    With a #show statement in PROGRAM only what it shows is printed. Atoms that
    no rule or fact defines (a misspelt predicate) are warned about.

    \b
    Exit codes: 0 a model, or proven unsatisfiable; 1 the time limit stopped the
    search (no model, or the optimum not proven); 2 bad input or usage; 130 interrupted.
    """

    text = read_file(program)
    kb = data.load(goals)
    result = kb.query(
        text,
        goal=goal or None,
        encodings=encoding_names,
        models=models,
        time_limit=time_limit,
        name=program,
        goal_nodes=goals or None,
    )
    for warning in result.warnings:
        click.echo(f"foon2asp: warning: {warning}", err=True)
    click.echo(report.render("query", fmt, kb.problem, result), nl=False)
    sys.exit(exit_code([(result.status, None)]))


def _method_list(values: tuple[str, ...], default: list[str] | None = None) -> list[str]:
    names = [n.strip() for v in values for n in v.split(",") if n.strip()]
    for name in names:
        methods.get(name)
    return list(dict.fromkeys(names)) or list(default or ["asp"])


@main.command(epilog=EXIT_CODES)
@data_options
@goal_options
@method_option("asp")
@click.option(
    "--objective", default="units", show_default=True, help="ASP objective(s), comma-separated, most important first."
)
@click.option(
    "-o",
    "--output",
    default="results.jsonl",
    show_default=True,
    type=click.Path(dir_okay=False),
    help="A FILE of results, one JSON line per (goal, method).",
)
@click.option(
    "--resume",
    is_flag=True,
    help="Continue OUTPUT: skip the (goal, method) pairs it already holds for the same configuration.",
)
@click.option("--workers", type=int32(min=1, max=1024), default=1, show_default=True, help="Worker processes.")
@click.option(
    "--scheduler", type=SCHEDULER, metavar="ADDRESS", help="Run on this Dask scheduler (needs the 'dask' extra)."
)
@click.option("--time-limit", type=SECONDS, help="Seconds per goal; the best tree so far is reported as 'feasible'.")
@click.option(
    "--opt-strategy",
    callback=_opt_strategy,
    help="clingo optimisation strategy: bb (branch and bound) or usc (core-guided), e.g. usc,oll;"
    " default usc,oll,succinct (see foon2asp.asp.settings).",
)
@click.option(
    "--threads",
    type=int32(min=1, max=64),
    default=1,
    show_default=True,
    help="clingo solver threads per worker; 2 or more without --opt-strategy: a bb and a usc solver side by side.",
)
@click.option(
    "--grounding",
    type=click.Choice(grounding_mod.GROUNDING_CHOICES),
    default="auto",
    show_default=True,
    help="One grounding for all goals, or a small grounding of each goal's relevant part; auto: per-goal when"
    " the goals' median relevant part is under 10 % of the viable units or there are over 50,000 of them"
    " (the summary says which).",
)
@click.option(
    "--shortcuts/--no-shortcuts",
    default=True,
    show_default=True,
    help="Answer without the solver when the answer is forced (underivable goal; no choice in the goal's part).",
)
@click.option(
    "--summary",
    "summary_fmt",
    type=click.Choice(report.names("summary")),
    default="text",
    show_default=True,
    help="Format of the summary printed at the end.",
)
@click.option("--progress/--no-progress", default=None, help="Progress bar (default: when stderr is a terminal).")
@click.option(
    "--fsync/--no-fsync",
    default=True,
    show_default=True,
    help="Sync result lines to disk (grouped: at most 0.25 s apart, and at the end).",
)
@constraint_options
@guarded
def batch(
    data,
    goal,
    goals,
    method_list,
    objective,
    output,
    resume,
    workers,
    scheduler,
    time_limit,
    opt_strategy,
    threads,
    grounding,
    shortcuts,
    summary_fmt,
    progress,
    fsync,
    constraints,
):
    """Solve many goals with several methods; resumable JSON-lines output and a summary.

    Every result line carries "valid" (the independent validator's verdict); the
    summary counts the valid trees per method. Default goals: the goals file's.
    """
    kb = data.load(goals)
    goal_ids = goals_mod.resolve(kb.data, kb.problem, goal, goals)
    outcome = kb.batch(
        goal_ids,
        output,
        methods=_method_list(method_list),
        workers=workers,
        resume=resume,
        objective=objective,
        time_limit=time_limit,
        constraints=_constraints(constraints),
        opt_strategy=opt_strategy,
        threads=threads,
        grounding=grounding,
        shortcuts=shortcuts,
        progress=progress,
        fsync=fsync,
        scheduler=scheduler,
    )
    click.echo(report.render("summary", summary_fmt, batch_results.summarize(outcome.records), outcome), nl=False)
    sys.exit(exit_code((r.get("status", "?"), r.get("valid")) for r in outcome.records))


if __name__ == "__main__":  # pragma: no cover
    main()
