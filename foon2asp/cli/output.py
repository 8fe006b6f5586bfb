"""What every command shares when it reports: exit codes, warnings, progress bars."""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable, Iterable
from typing import Any

import click
from tqdm import tqdm

from foon2asp import api
from foon2asp.errors import escape

#: exit codes, the same for every command (README "Exit codes")
EXIT_CODES = """\b
Exit codes: 0 every goal answered as asked (a tree, or proven unreachable);
1 some answer is not proven (time limit) or a tree is invalid;
2 bad input or usage; 130 interrupted."""

#: statuses that answer a goal: a proven tree, a proven k-th best tree, a proof that there is none,
#: or a search method's tree (judged separately by "valid")
ANSWERED = frozenset({"optimal", "ranked", "unreachable", "infeasible", "found", "satisfiable", "unsatisfiable"})

#: statuses that come with a tree (whose "valid" counts)
WITH_TREE = frozenset({"optimal", "ranked", "feasible", "found"})


def exit_code(answers: Iterable[tuple[str, Any]]) -> int:
    """0 when every (status, valid) pair answers its goal, else 1 (``valid`` None: not judged)."""
    ok = all(status in ANSWERED and not (valid is False and status in WITH_TREE) for status, valid in answers)
    return 0 if ok else 1


def warn_all(warnings: Iterable[str]) -> None:
    """Warnings about the input or the request, one line each on stderr."""
    for warning in warnings:
        click.echo(f"foon2asp: warning: {escape(warning)}", err=True)


def solver_of(kb: api.KnowledgeBase, options: api.Options) -> Any:
    """The solver options of the request ``options``, its warnings on stderr."""
    solver, warnings = kb.options_and_warnings(options)
    warn_all(warnings)
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
    return tqdm(items, total=total, desc=what, unit="goal", file=sys.stderr, disable=not show, leave=False)


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
