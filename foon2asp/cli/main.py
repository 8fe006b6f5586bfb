"""The ``foon2asp`` command group and what every command shares: errors, exit codes, warnings, progress bars."""

from __future__ import annotations

import signal
import sys
import threading
import time
import traceback
from collections.abc import Callable, Iterable
from typing import Any, NoReturn

import click
from tqdm import tqdm

from foon2asp import api
from foon2asp.errors import (
    InputError,
    Terminated,
    forget_unhandled_interrupt,
    interrupt_behind,
    one_line,
    strict_error,
)

# tqdm's bars share a lock, by default one of multiprocessing's too, whose import reads the
# kernel's randomness in the way that waits until the kernel has gathered enough (a minute on a
# freshly started machine); the command line writes its bars from its main thread only
tqdm.set_lock(threading.RLock())

#: exit codes, the same for every command (README "Exit codes")
EXIT_CODES = """\b
Exit codes: 0 every goal answered as asked (a tree, or proven unreachable);
1 some answer is not proven (time limit) or a tree is invalid;
2 bad input or usage; 130 interrupted."""

#: statuses that answer a goal: a proven tree, a proven k-th best tree, a proof that there is none,
#: or a search method's tree (judged separately by "valid")
ANSWERED = frozenset({"optimal", "ranked", "unreachable", "infeasible", "found", "satisfiable", "unsatisfiable"})


def exit_code(answers: Iterable[tuple[str, Any]]) -> int:
    """0 when every (status, valid) pair answers its goal, else 1 (``valid`` None: not judged)."""
    ok = all(status in ANSWERED and not (valid is False and status in api.WITH_TREE) for status, valid in answers)
    return 0 if ok else 1


def warn_all(warnings: Iterable[str]) -> None:
    """Warnings about the input or the request, one line each on stderr."""
    for warning in warnings:
        click.echo(f"foon2asp: warning: {one_line(warning)}", err=True)


#: where a command's context keeps its --strict (:func:`warn_request`)
STRICT = "foon2asp.strict"


def warn_request(warnings: Iterable[str]) -> None:
    """Warnings about the request (misspelt predicates in rules, kinds no file names, options that
    are ignored), one line each on stderr; with --strict the first is an error (exit status 2)."""
    warnings = list(warnings)
    ctx = click.get_current_context(silent=True)
    if warnings and ctx is not None and ctx.meta.get(STRICT):
        raise strict_error(warnings, "--strict")
    warn_all(warnings)


def solver_of(kb: api.KnowledgeBase, options: api.Options) -> Any:
    """The solver options of the request ``options``, its warnings on stderr (:func:`warn_request`)."""
    solver, warnings = kb.options_and_warnings(options)
    warn_request(warnings)
    return solver


def emit(text: str | bytes, output: str | None, wrote: str) -> None:
    """``text`` into the file ``output`` (stderr then says ``wrote``, then `` to OUTPUT``), else on stdout."""
    if output:
        api.write_file(output, text)
        click.echo(f"{wrote} to {output}", err=True)
    elif isinstance(text, bytes):
        sys.stdout.buffer.write(text)
    else:
        click.echo(text, nl=False)


def progress_bar(items: Iterable, total: int, enabled: bool | None, what: str) -> Any:
    """``items`` (``total`` goals) behind a progress bar on stderr: when it is a terminal
    and there is more than one goal (``enabled`` None), or as ``enabled`` says."""
    show = (sys.stderr.isatty() and total > 1) if enabled is None else enabled
    if not show:
        return items
    return tqdm(items, total=total, desc=what, unit="goal", file=sys.stderr, leave=False)


def solving_text(info: dict) -> str:
    """``solving: best 12, lower bound 10, gap 16.7%`` (the solver's weights per level)."""
    best = "/".join(map(str, info.get("cost") or ())) or "-"
    lower = "/".join(map(str, info.get("lower") or ())) or "-"
    gap = info.get("gap")
    return f"solving: best {best}, lower bound {lower}" + (f", gap {100 * gap:.1f}%" if gap is not None else "")


class GoalProgress:
    """A status line on stderr while one goal is solved, ``text(info)`` at most five times a second
    (the library's ``on_progress`` callback)."""

    def __init__(self, text: Callable[[dict], str]) -> None:
        self._text = text
        self._bar: Any = None
        self._last = 0.0
        self._lock = threading.Lock()

    def __call__(self, info: dict) -> None:
        now = time.monotonic()
        with self._lock:
            if now - self._last < 0.2:
                return
            self._last = now
            if self._bar is None:
                self._bar = tqdm(total=0, bar_format="{desc}", file=sys.stderr, leave=False)
            self._bar.set_description_str(self._text(info))

    def close(self) -> None:
        with self._lock:
            if self._bar is not None:
                self._bar.close()
                self._bar = None


def goal_progress(enabled: bool | None, text: Callable[[dict], str] = solving_text) -> GoalProgress | None:
    """A :class:`GoalProgress` showing ``text`` when stderr is a terminal (``enabled`` None) or as ``enabled`` says."""
    show = sys.stderr.isatty() if enabled is None else enabled
    return GoalProgress(text) if show else None


def echo_now(text: str, status: GoalProgress | None = None, nl: bool = False) -> None:
    """``text`` on stdout at once, after the status line ``status`` is cleared."""
    if status is not None:
        status.close()
    click.echo(text, nl=nl)
    sys.stdout.flush()


#: exit statuses: 2 bad input or usage, 3 an internal error, 130 SIGINT, 143 SIGTERM
EXIT_INPUT, EXIT_INTERNAL, EXIT_SIGINT, EXIT_SIGTERM = 2, 3, 130, 143

#: the library's error hints (:attr:`foon2asp.errors.InputError.hint`, ``KEY`` or ``KEY=VALUE``)
#: worded with this command line's flags ({}: the hint's VALUE; ``KEY=`` is the wording when a VALUE is given)
FLAG_WORDING = {
    "no-goal": "no goal given: use --goal TEXT or --goals FILE|all|all-objects",
    "goals-all": "--goals all needs a goals file (goal_nodes.json in --data DIR, or --goals FILE)",
    "goals-all=": "--goals all needs a goals file, and there is no {} (give --goals FILE)",
    "no-goals-file": "no goal given and no goals file: use --goal TEXT, --goals FILE or --goals all-objects"
    " (goal_nodes.json beside the FOON is read when present)",
    "no-goals-file=": "no goal given and no goals file (there is no {}): use --goal TEXT, --goals FILE"
    " or --goals all-objects",
    "kitchen": "no kitchen.json beside the FOON file (looked for {});"
    " give --kitchen FILE, --kitchen leaves (every object no unit makes, e.g. for merged generated trees)"
    " or --data DIR (--data demo for the demo data)",
    "kitchen-data": "kitchen file not found in the data folder; give --kitchen FILE, or --kitchen leaves"
    " (every object no unit makes, e.g. for merged generated trees)",
    "motion-cost": "--objective cost needs --motion-cost FILE (a JSON object motion -> cost, or motion<TAB>cost lines)",
    "human-steps": "human steps only change the tree when 'success' is an objective (a person's step succeeds"
    " for sure); use --objective success or {}",
}


def fail(message: str, code: int = EXIT_INPUT) -> NoReturn:
    click.echo(f"foon2asp: error: {one_line(message)}", err=True)
    sys.exit(code)


def _terminate(signum, frame) -> None:
    raise Terminated()


def report_exception(exc: BaseException, debug: bool = False) -> NoReturn:
    """Turn any exception of a command into one line on stderr and a documented exit status
    (``debug``: with the traceback of an internal error)."""
    exc = interrupt_behind(exc)
    if isinstance(exc, KeyboardInterrupt):
        terminated = isinstance(exc, Terminated)
        click.echo(f"foon2asp: {'terminated' if terminated else 'interrupted'}", err=True)
        forget_unhandled_interrupt()  # the exit status is this one, not death by SIGINT
        sys.exit(EXIT_SIGTERM if terminated else EXIT_SIGINT)
    if isinstance(exc, InputError):
        key, _, value = (exc.hint or "").partition("=")
        if value and f"{key}=" in FLAG_WORDING:
            key += "="
        if key in FLAG_WORDING:
            exc = InputError(FLAG_WORDING[key].format(value), exc.path, exc.line, exc.column)
        fail(str(exc))
    if isinstance(exc, BrokenPipeError):
        sys.exit(0)
    if isinstance(exc, OSError) and exc.filename is not None:
        fail(f"{exc.filename}: {exc.strerror or exc}")
    if isinstance(exc, RecursionError | MemoryError):
        fail(f"input too large or too deeply nested ({type(exc).__name__})")
    if debug:
        traceback.print_exception(exc)
    fail(
        f"internal error: {type(exc).__name__}: {exc} -- please report it with the command line"
        f"{'' if debug else ' (--debug shows the traceback)'}",
        EXIT_INTERNAL,
    )


class Main(click.Group):
    """The command group: every error is one line on stderr with a documented exit status, never a traceback."""

    def make_context(self, *args: Any, **kwargs: Any) -> click.Context:
        try:
            return super().make_context(*args, **kwargs)
        except KeyboardInterrupt as exc:  # reported here: click would first print an empty line
            report_exception(exc)

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except (SystemExit, click.exceptions.Exit, click.ClickException):
            raise
        except BaseException as exc:
            report_exception(exc, bool(ctx.params.get("debug")))

    def main(self, *args: Any, standalone_mode: bool = True, **kwargs: Any) -> Any:
        run: Any = super().main
        if not standalone_mode:
            return run(*args, standalone_mode=False, **kwargs)
        try:
            previous = signal.signal(signal.SIGTERM, _terminate)
        except ValueError:  # not the main thread
            previous = None
        try:
            with api.kept_interrupts():  # an interrupt that a finaliser drops is raised again
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
            click.echo(f"foon2asp: error: {where}{one_line(message)}{hint}", err=True)
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


@click.group(cls=Main, context_settings={"help_option_names": ["-h", "--help"], "show_default": True})
@click.version_option(package_name="foon2asp")
@click.option("--debug", is_flag=True, help="On an internal error (exit status 3), also print the traceback.")
def main(debug):
    """foon2asp: minimal, well-founded FOON task trees with answer-set programming.

    Exit status: 0 every goal answered as asked (a tree, or proven unreachable); 1 a negative
    answer (not proven within the time limit; check: invalid tree; query: unsatisfiable); 2 bad
    input or usage; 3 an internal error; 130 interrupted (SIGINT); 143 terminated (SIGTERM).
    """


def ignore_signals() -> None:
    """SIGINT and SIGTERM are ignored from now on (the command is over, or its interrupt reported)."""
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def run(prog_name: str = "foon2asp") -> None:
    """The command group as the process's entry point (:func:`foon2asp.__main__.run`); SIGINT and
    SIGTERM are ignored once it is over, and one that comes as it ends is reported as any other."""
    try:
        try:
            api.keep_interrupts_until_exit()
            main(prog_name=prog_name)
        finally:
            ignore_signals()
    except KeyboardInterrupt as exc:  # came after the command's own handling, before it ignored signals
        ignore_signals()
        report_exception(exc)
