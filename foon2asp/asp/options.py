"""How to solve: objectives, extra programs, bounds and solver settings (:class:`AspOptions`).

The default solver settings (BENCHMARKS.md) live here too (:func:`solver_args`).
"""

from __future__ import annotations

import hashlib
import os
import re
import tempfile
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from functools import lru_cache

import clingo

from foon2asp.errors import InputError
from foon2asp.foon.substitutes import Substitute

#: objective name -> encoding that defines it (all use objective(Name,Priority)); ``cost`` is
#: the summed motion cost of a motion-cost table (AspOptions.motion_costs)
OBJECTIVES: dict[str, str] = {name: name for name in ("units", "success", "inputs", "depth", "cost")}

#: greedy retrieval inside the solver (AspOptions.heuristic -> encodings/greedy_NAME.lp)
HEURISTICS = ("h1", "h2")


#: the optimisation strategy when the user sets none (one thread)
DEFAULT_OPT_STRATEGY = "usc,oll,succinct,stratify"
#: clasp options that go with it: shrink each core by binary search, clasp's "trendy" configuration
DEFAULT_TUNING = ("--opt-usc-shrink=bin", "--configuration=trendy")

#: the portfolio for --threads >= 2 without --opt-strategy: one solver per line, ``[name]: <clasp options>``
#: (more threads repeat its lines)
PORTFOLIO = f"[bbsign]: --opt-strategy=bb --opt-heuristic=sign,model\n[usc]: --opt-strategy={DEFAULT_OPT_STRATEGY} {DEFAULT_TUNING[0]}\n"


def portfolio_file(text: str = PORTFOLIO) -> str:
    """A configuration file holding ``text`` for clingo's ``--configuration`` (written once,
    named by its content, in the temporary directory; worker processes share it)."""
    digest = hashlib.sha256(text.encode()).hexdigest()[:16]
    path = os.path.join(tempfile.gettempdir(), f"foon2asp-portfolio-{digest}.cfg")
    try:
        with open(path, encoding="utf-8") as fh:
            if fh.read() == text:
                return path
    except OSError:
        pass
    fd, tmp = tempfile.mkstemp(prefix="foon2asp-portfolio-", suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as fh:
        fh.write(text)
    os.replace(tmp, path)  # atomic: a reader sees the old file or the whole new one
    return path


def solver_args(opt_strategy: str | None = None, threads: int = 1, portfolio: str | None = None) -> list[str]:
    """clingo arguments for an optimisation strategy (None: the default), a number of threads
    and (threads > 1, no strategy) a portfolio in clasp's file format (None: :data:`PORTFOLIO`)."""
    parallel = [f"--parallel-mode={threads}"] if threads and threads > 1 else []
    if opt_strategy:
        return [f"--opt-strategy={opt_strategy}", *parallel]
    if parallel:
        return [*parallel, f"--configuration={portfolio_file(portfolio or PORTFOLIO)}"]
    return [f"--opt-strategy={DEFAULT_OPT_STRATEGY}", *DEFAULT_TUNING]


def check_objectives(names: Iterable[str]) -> None:
    """Raise InputError naming the first of ``names`` that is no objective."""
    for name in names:
        if name not in OBJECTIVES:
            raise InputError(f"unknown objective {name!r} (have {', '.join(OBJECTIVES)})")


#: clingo's solve settings no option of the user's may change, and why
KEPT_SETTINGS = {
    "solve_limit": "it ends a search early, so an answer would count as proven without being so",
    "opt_stop": "it ends a search early, so an answer would count as proven without being so",
    "opt_mode": "foon2asp sets it for each solve call",
    "models": "foon2asp sets it for each solve call (the number of trees: --models)",
    "enum_mode": "foon2asp sets it for each solve call",
    "project": "foon2asp sets it for each solve call",
    "parallel_mode": "the number of threads is --threads (threads=)",
}


def _solve_settings(args: list[str]) -> dict[str, str]:
    """clingo's solve settings (:data:`KEPT_SETTINGS`) under ``args``; RuntimeError when clingo refuses them."""
    control = clingo.Control(args, logger=lambda code, message: None)  # kept while its configuration is read
    solve = control.configuration.solve
    return {key: str(getattr(solve, key)) for key in KEPT_SETTINGS}


def clingo_options(args: Iterable[str]) -> list[str]:
    """``args`` checked as clingo's own command-line options (each ``--name=value`` or a flag).

    Raises InputError naming the first clingo refuses or that changes a setting of
    :data:`KEPT_SETTINGS`; for an option clingo does not know, its hint is ``unknown-option=ARG``.
    """
    args = [str(a) for a in args]
    for arg in args:
        if not arg.startswith("-"):
            raise InputError(f"clingo option {arg!r}: clingo's options start with '-' (e.g. --configuration=crafty)")
        try:
            settings = _solve_settings([arg])
        except RuntimeError as exc:
            text = " ".join(str(exc).split())
            hint = f"unknown-option={arg}" if "unknown option" in text else None
            if "requires a value" in text and arg.startswith("--") and "=" not in arg:
                text += f" (write {arg}=VALUE)"
            raise InputError(f"clingo option {arg!r}: {text}", hint=hint) from None
        default = _default_settings()
        for key, why in KEPT_SETTINGS.items():
            if settings[key] != default[key]:
                raise InputError(f"clingo option {arg!r} is not taken: {why}")
    return [_full_name(arg) for arg in args]


def _full_name(arg: str) -> str:
    """``arg`` with the full name of its option when it gives a prefix (``--config=crafty``:
    ``--configuration=crafty``), so that it replaces the same option of foon2asp's."""
    name, eq, value = arg.partition("=")
    if not name.startswith("--"):
        return arg
    try:
        clingo.Control([arg, arg], logger=lambda code, message: None)
    except RuntimeError as exc:  # clingo names the option it takes twice
        found = re.search(r"multiple occurrences: '([^']+)'", str(exc))
        if found and found.group(1).startswith(name[2:]):
            return f"--{found.group(1)}{eq}{value}"
    return arg


@lru_cache(maxsize=1)
def _default_settings() -> dict[str, str]:
    return _solve_settings([])


def with_clingo_args(args: Iterable[str], extra: Iterable[str]) -> list[str]:
    """``args`` and then ``extra``, whose options replace the same options in ``args`` (clingo
    takes an option once)."""
    extra = list(extra)

    def name(arg: str) -> str:
        return arg.lstrip("-").split("=", 1)[0]

    given = {name(a) for a in extra}
    return [a for a in args if name(a) not in given] + extra


@dataclass
class AspOptions:
    """How to solve: objectives (lexicographic, first = most important) and solver settings."""

    objective: tuple[str, ...] = ("units",)
    #: extra ASP programs as (name, text): user constraints and the like
    programs: list[tuple[str, str]] = field(default_factory=list)
    time_limit: float | None = None
    #: clingo's --opt-strategy; None: the default of :func:`solver_args` (usc; a portfolio with threads > 1)
    opt_strategy: str | None = None
    threads: int = 1
    #: threads > 1 without opt_strategy: the portfolio (clasp's configuration-file text); None: the default
    portfolio: str | None = None
    #: more of clingo's own options, each replacing the same option of foon2asp's (:func:`with_clingo_args`)
    clingo_args: list[str] = field(default_factory=list)
    #: ground only these units (e.g. the goals' relevant units); None: all units
    units: tuple[int, ...] | None = None
    #: only trees of at most this many sequential rounds (see foon2asp.asp.multishot.depth)
    max_depth: int | None = None
    #: at most this many units may be done by a person (success 1.0 for those)
    human_steps: int | None = None
    #: the K best distinct trees per goal, best first
    models: int = 1
    #: every optimal tree, at most all_optimal_cap of them
    all_optimal: bool = False
    all_optimal_cap: int = 100
    #: "h1" | "h2": greedy retrieval in the solver (first model under #heuristic)
    heuristic: str | None = None
    #: among several optimal trees, return the lexicographically smallest (foon2asp.asp.canonical)
    canonical: bool = True
    #: the objective "cost": motion -> cost in hundredths (a motion not listed: 100); None: no table
    motion_costs: dict[str, int] | None = None
    #: labels that may stand in for others; the cheapest substitutions rank above the objectives
    substitutes: tuple[Substitute, ...] = ()
    #: at most this many substitutions per tree
    max_substitutions: int | None = None
    #: stop a goal once its gap (foon2asp.tree.gap) is at most this (0.05: 5 %); None: prove
    gap: float | None = None
    #: goals polynomial reasoning proves are answered without clingo (``only-tree``, ``bounds``);
    #: False: clingo answers every goal it can make
    shortcuts: bool = True
    #: called with ``{"cost": [...], "lower": [...], "gap": g}`` at each model and proven lower bound
    progress: Callable[[dict], None] | None = field(default=None, compare=False, repr=False)

    @property
    def method(self) -> str:
        if self.heuristic:
            return f"asp-greedy-{self.heuristic}"
        return "asp-" + ",".join(self.objective)

    @property
    def plain(self) -> bool:
        """Is every tree of the grounded units an answer (no programs, substitutes, depth
        bound, human steps, alternatives or greedy retrieval)?"""
        return not (
            self.programs
            or self.substitutes
            or self.heuristic
            or self.max_depth is not None
            or self.human_steps is not None
            or self.models > 1
            or self.all_optimal
        )

    @property
    def driven(self) -> bool:
        """Does solving need the multi-shot driver (more than one plain optimisation)?"""
        return bool(
            self.heuristic
            or self.max_depth is not None
            or self.human_steps is not None
            or self.models > 1
            or self.all_optimal
            or "depth" in self.objective
        )

    def args(self, more: Iterable[str] = ()) -> list[str]:
        """clingo's arguments: foon2asp's, then ``more``, then :attr:`clingo_args` (each replacing
        the same option before it)."""
        args = ["--opt-mode=opt"]
        if self.heuristic:
            args.append("--heuristic=Domain")
        args += solver_args(self.opt_strategy, self.threads, self.portfolio)
        return with_clingo_args([*args, *more], self.clingo_args)
