"""What every command shares: the error style, exit codes, progress bars and streamed output."""

from __future__ import annotations

import sys
from collections.abc import Iterable
from typing import Any

import click
from tqdm import tqdm

#: exit codes, the same for every command (README "Exit codes")
EXIT_CODES = """\b
Exit codes: 0 every goal answered as asked (a tree, or proven unreachable);
1 some answer is not proven (time limit) or a tree is invalid;
2 bad input or usage; 130 interrupted."""

#: statuses that answer a goal: a proven tree, a proven k-th best tree, a proof that there is none,
#: or a search method's tree (judged separately by "valid")
ANSWERED = frozenset({"optimal", "ranked", "unreachable", "found", "satisfiable", "unsatisfiable"})


#: statuses that come with a tree (whose "valid" counts)
WITH_TREE = frozenset({"optimal", "ranked", "feasible", "found"})


def exit_code(answers: Iterable[tuple[str, Any]]) -> int:
    """0 when every (status, valid) pair answers its goal, else 1 (``valid`` None: not judged)."""
    ok = all(status in ANSWERED and not (valid is False and status in WITH_TREE) for status, valid in answers)
    return 0 if ok else 1


def error(message: str) -> str:
    return f"foon2asp: error: {message}"


class Group(click.Group):
    """click's group with foon2asp's error style: usage errors are one line
    ``foon2asp: error: ...`` on stderr with exit code 2, like bad input."""

    def main(self, args=None, prog_name=None, complete_var=None, standalone_mode=True, **extra):
        try:
            rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except click.exceptions.NoArgsIsHelpError as exc:  # pragma: no cover - click >= 8.2
            click.echo(exc.ctx.get_help() if exc.ctx else str(exc))
            rv = 0
        except click.UsageError as exc:
            where = f"{exc.ctx.info_name}: " if exc.ctx is not None and exc.ctx.parent is not None else ""
            hint = f" (see '{exc.ctx.command_path} --help')" if exc.ctx is not None else ""
            click.echo(error(f"{where}{_one_line(exc.format_message())}{hint}"), err=True)
            rv = 2
        except click.ClickException as exc:
            click.echo(error(_one_line(exc.format_message())), err=True)
            rv = exc.exit_code
        except click.Abort:
            click.echo(error("interrupted"), err=True)
            rv = 130
        if not standalone_mode:
            return rv
        sys.exit(rv if isinstance(rv, int) else 0)


def _one_line(text: str) -> str:
    return " ".join(text.split())


def progress_bar(items: Iterable, total: int, enabled: bool | None, what: str) -> Any:
    """``items`` (``total`` goals) behind a progress bar on stderr: when it is a terminal
    and there is more than one goal (``enabled`` None), or as ``enabled`` says."""
    show = (sys.stderr.isatty() and total > 1) if enabled is None else enabled
    return tqdm(items, total=total, desc=what, unit="goal", file=sys.stderr, disable=not show, leave=False)
