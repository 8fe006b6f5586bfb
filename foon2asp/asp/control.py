"""The one wrapper around :class:`clingo.Control` that solving and queries share.

Named programs whose errors are one :class:`~foon2asp.errors.InputError`, solve modes,
guarded nogoods and time-limited solving; signals wait until a clingo call has returned
(docs/proofs/solving.md, "The watchdog and signals").
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cache, lru_cache
from typing import Any

import clingo
import clingo.ast

from foon2asp.asp.constraints import check_syntax, clingo_error
from foon2asp.asp.interrupts import POLL_S, WATCHDOG, deferred_signals, signal_pending
from foon2asp.asp.predicates import refuse_host_code
from foon2asp.errors import InputError

#: an atom no program has: a solve assuming it ends at once
_ABSORB = clingo.Function("foon2asp_no_atom")

#: between fact programs added in one call
_JOIN = "\n"

#: solve mode -> clingo's opt-mode, number of models (None: as many as asked for) and projection
MODES: dict[str, tuple[str, str | None, str]] = {
    "opt": ("opt", "0", "no"),
    "optN": ("optN", None, "project"),
    "first": ("ignore", "1", "no"),
}

#: a part to ground: its name and its arguments
Part = tuple[str, Sequence[int | clingo.Symbol]]


@cache
def option_names() -> tuple[str, ...]:
    """clingo's long options that set its solver's configuration (``--configuration``,
    ``--opt-strategy``, ...), each once, for suggestions."""
    names: set[str] = set()
    control = clingo.Control(logger=lambda code, message: None)  # kept while its configuration is read
    stack = [control.configuration]
    while stack:
        config = stack.pop()
        for key in config.keys or ():
            value = getattr(config, key)
            if isinstance(value, clingo.Configuration):
                stack.append(value[0] if value.is_array and len(value) else value)
            else:
                names.add("--" + key.replace("_", "-"))
    return tuple(sorted(names))


@lru_cache(maxsize=64)
def _parsed_file(path: str) -> tuple[tuple[str, clingo.ast.AST], ...]:
    """The statements of the encoding file at ``path`` and the files it includes, as clingo parses
    them, each with the file it is in."""
    found: list[tuple[str, clingo.ast.AST]] = []
    clingo.ast.parse_files([path], lambda stm: found.append((stm.location.begin.filename, stm)))
    return tuple(found)


def remaining(deadline: float | None) -> float | None:
    """The seconds left until ``deadline`` (a ``time.perf_counter()`` value; None: no limit)."""
    return None if deadline is None else max(0.0, deadline - time.perf_counter())


@dataclass
class SolveResult:
    """What a solve call ended with."""

    #: the search ran to its end (not stopped by the time limit or an interrupt)
    finished: bool
    satisfiable: bool | None
    unsatisfiable: bool | None
    exhausted: bool
    interrupted: bool
    time_s: float
    #: the best lower bound the solver proved, per priority level from the highest (maybe fewer); None: none
    lower: tuple[int, ...] | None = None
    #: the search was stopped because ``stop`` said so (e.g. the gap was small enough)
    stopped: bool = False


class Control:
    """A clingo control with named programs, one-line errors and time-limited solving; ``theory``:
    a clingo theory (clingo-dl's) that rewrites the programs and sees every model first."""

    def __init__(self, args: Sequence[str] = (), message_limit: int = 20, theory=None) -> None:
        self.messages: list[str] = []
        #: keep the choices, conflicts, models and solve time of each solve (:meth:`stats`)
        self.statistics = True
        self.user_programs: list[tuple[str, str]] = []
        #: the encoding files loaded so far (with the files they include)
        self._loaded: set[str] = set()
        self.theory = theory
        #: clingo runs one solve call, prepared for it (``--single-shot``): interrupting the
        #: control does not reach a search run in the calling thread, so a decision is not tried there
        self.single_shot = "--single-shot" in args
        #: the mode set by :meth:`solving` is "first"; :meth:`stop_soon` was asked; an interrupt may be pending
        self._decision = self._stopping = self._absorb = False
        try:
            self.ctl = clingo.Control(list(args), logger=self._log, message_limit=message_limit)
        except RuntimeError as exc:
            raise InputError(f"bad solver option: {' '.join(str(exc).split())}") from None
        if theory is not None:
            theory.register(self.ctl)

    def _log(self, code: clingo.MessageCode, message: str) -> None:
        self.messages.append(" ".join(message.split()))

    def add(self, name: str, text: str, user: bool = False, part: str = "base", params: Sequence[str] = ()) -> None:
        """Add program ``text`` (called ``name`` in errors) to ``part``, whose parameters are ``params``."""
        self.messages.clear()
        if user:
            refuse_host_code(name, text)
            self.user_programs.append((name, text))
        try:
            with deferred_signals():
                if self.theory is None:
                    self.ctl.add(part, list(params), text)
                else:  # a theory (clingo-dl) rewrites the program; it is added to the base part
                    with clingo.ast.ProgramBuilder(self.ctl) as builder:
                        clingo.ast.parse_string(text, lambda stm: self.theory.rewrite_ast(stm, builder.add))
        except RuntimeError:
            raise clingo_error(self.messages, name) from None

    def load(self, path: str) -> None:
        """Load the shipped encoding file at ``path``: clingo's parser reads it once per process,
        resolving its ``#include`` directives, and each control gets the statements parsed."""
        self.messages.clear()
        try:
            statements = _parsed_file(path)
            with deferred_signals(), clingo.ast.ProgramBuilder(self.ctl) as builder:
                add = builder.add if self.theory is None else (lambda stm: self.theory.rewrite_ast(stm, builder.add))
                for source, stm in statements:
                    if source not in self._loaded:  # a file loaded before, or included by one, once
                        add(stm)
            self._loaded.update(source for source, _ in statements)
        except RuntimeError:
            raise clingo_error(self.messages, path) from None

    def add_all(self, parts: Iterable[tuple[str, str]], user: Iterable[str] = ()) -> None:
        """Add ``parts``; consecutive parts not named in ``user`` go in one call (cheaper; they hold no error to name)."""
        users = set(user)
        shipped: list[str] = []
        for name, text in parts:
            if name in users:
                if shipped:
                    self.add("program", _JOIN.join(shipped))
                    shipped = []
                self.add(name, text, True)
            else:
                shipped.append(text)
        if shipped:
            self.add("program", _JOIN.join(shipped))

    def ground(self, parts: Sequence[Part] = (("base", ()),), what: str | None = None) -> None:
        """Ground ``parts`` (a part's name and its arguments, numbers or symbols); an error names the
        user program at fault, else it is clingo's first message about ``what``."""
        self.messages.clear()
        try:
            with deferred_signals():  # grounding cannot be interrupted: a signal waits for its end
                self.ctl.ground(
                    [(name, [clingo.Number(a) if isinstance(a, int) else a for a in args]) for name, args in parts]
                )
                if self.theory is not None:
                    self.theory.prepare(self.ctl)
        except RuntimeError:
            for name, text in self.user_programs:
                check_syntax(name, text)
            msg = self.messages[0] if self.messages else "error"
            raise InputError(msg.replace("<block>", "program"), what) from None

    def extend(self, name: str, text: str, parts: Sequence[Part] = (), what: str | None = None) -> None:
        """Add ``text`` as the part ``name`` and ground it with ``parts`` (multi-shot)."""
        with deferred_signals():  # one section: the part is never left added but not grounded
            self.add(name, text, part=name)
            self.ground([(name, ()), *parts], what)

    @contextmanager
    def solving(self, mode: str = "opt", count: int = 1, bound: Sequence[int] | None = None) -> Iterator[None]:
        """Solve in ``mode`` inside the body: "opt" (the best model), "optN" (up to ``count``
        distinct optimal models, projected) or "first" (the first model; with ``bound``, the
        first whose cost vector is at most ``bound``)."""
        opt_mode, models, project = MODES[mode]
        if bound is not None:
            opt_mode = ",".join(["enum", *map(str, bound)])
        self._decision = mode == "first"
        try:
            with self.configured(opt_mode=opt_mode, models=models or str(count), project=project):
                yield
        finally:
            self._decision = False

    @contextmanager
    def configured(self, **settings: str) -> Iterator[None]:
        """Inside the body clingo's solve configuration has ``settings`` (restored afterwards)."""
        conf: Any = self.ctl.configuration.solve
        saved = {key: getattr(conf, key) for key in settings}
        for key, value in settings.items():
            setattr(conf, key, value)
        try:
            yield
        finally:
            for key, value in saved.items():
                setattr(conf, key, value)

    def stop_soon(self) -> None:
        """End the running solve call, which then reports its search as finished."""
        self._stopping = True
        WATCHDOG.interrupt(self.ctl)

    def solve(
        self,
        on_model: Callable[[clingo.Model], bool | None] | None = None,
        time_limit: float | None = None,
        assumptions: Sequence[tuple[clingo.Symbol, bool]] = (),
        on_lower: Callable[[tuple[int, ...]], None] | None = None,
        stop: Callable[[], bool] | None = None,
    ) -> SolveResult:
        """Solve for at most ``time_limit`` seconds (None: no limit) or until ``stop()`` is true;
        ``on_lower`` sees each proven lower bound.  A signal cancels the search and is raised afterwards."""
        t0 = time.perf_counter()
        deadline = None if time_limit is None else t0 + max(0.0, time_limit)
        if self.theory is not None:
            theory, user = self.theory, on_model

            def on_model(model: clingo.Model) -> bool | None:  # the theory reads each model first
                theory.on_model(model)
                return user(model) if user is not None else None

        lower: list[tuple[int, ...]] = []

        def on_unsat(bound: Sequence[int]) -> None:
            lower[:] = [tuple(bound)]
            if on_lower is not None:
                on_lower(lower[0])

        stopped = False
        calls: dict[str, Any] = {"on_model": on_model, "on_unsat": on_unsat, "assumptions": list(assumptions)}
        with deferred_signals():
            if self._absorb:
                # an interrupt of the last call may have come after its end: this call takes it
                self._absorb = False
                self.ctl.solve(assumptions=[(_ABSORB, True)])
            self._stopping = False
            if self._decision and not self.single_shot:
                # a decision is first tried in this thread, for one slice
                with WATCHDOG.limit(self.ctl, self._slice(deadline)):
                    done = self.ctl.solve(**calls)
                if not done.interrupted or self._stopping:
                    self._stopped(done)
                    return self._result(done, True, False, t0, lower)
            with self.ctl.solve(**calls, async_=True) as handle:
                finished = False
                # wait in slices so that a deferred signal, the deadline or a stop is seen between them
                while not signal_pending():
                    if handle.wait(self._slice(deadline)):
                        finished = True
                        break
                    if deadline is not None and time.perf_counter() >= deadline:
                        break
                    if stop is not None and stop():
                        stopped = True
                        break
                if not finished:
                    handle.cancel()
                result = handle.get()
            self._stopped(result)
        return self._result(result, finished, stopped, t0, lower)

    @staticmethod
    def _slice(deadline: float | None) -> float:
        """How long to wait before looking again for a signal, the deadline or a stop."""
        left = remaining(deadline)
        return POLL_S if left is None else min(POLL_S, left)

    def _result(
        self, result: clingo.SolveResult, finished: bool, stopped: bool, t0: float, lower: list[tuple[int, ...]]
    ) -> SolveResult:
        """The :class:`SolveResult` of a call started at ``t0``."""
        return SolveResult(
            finished and (not result.interrupted or self._stopping),
            result.satisfiable,
            result.unsatisfiable,
            bool(result.exhausted),
            bool(result.interrupted),
            time.perf_counter() - t0,
            lower[0] if lower else None,
            stopped or self._stopping,
        )

    def _stopped(self, result: clingo.SolveResult) -> None:
        """After a solve call: an interrupt of :meth:`stop_soon` still to come is dropped or absorbed."""
        if self._stopping:
            WATCHDOG.forget(self.ctl)
            self._absorb = self._absorb or not result.interrupted

    @contextmanager
    def switched(self, atoms: Iterable[clingo.Symbol | int]) -> Iterator[None]:
        """The body runs with the external ``atoms`` true (false again afterwards)."""
        atoms = list(atoms)
        self.assign(dict.fromkeys(atoms, True))
        try:
            yield
        finally:
            self.assign(dict.fromkeys(atoms, False))

    def assign(self, externals: Mapping[Any, bool]) -> None:
        """Set external atoms (a signal meanwhile waits until all are set)."""
        with deferred_signals():
            for atom, value in externals.items():
                self.ctl.assign_external(atom, value)

    def has_atom(self, atom: clingo.Symbol) -> bool:
        """Did the grounder keep ``atom`` (it may be true in some model)?"""
        return self.ctl.symbolic_atoms[atom] is not None

    def guard(self, atoms: Iterable[clingo.Symbol]) -> int:
        """A nogood forbidding ``atoms`` together behind a fresh external guard (off): its literal."""
        body = []
        for atom in atoms:
            grounded = self.ctl.symbolic_atoms[atom]
            if grounded is None:
                raise ValueError(f"{atom} is not a grounded atom")
            body.append(grounded.literal)
        with deferred_signals(), self.ctl.backend() as backend:
            guard = backend.add_atom()
            backend.add_external(guard, clingo.TruthValue.False_)
            backend.add_rule([], [guard] + body)
        return guard

    def release(self, guards: Iterable[int]) -> None:
        """Remove the nogoods of ``guards`` (their externals become false for good)."""
        with deferred_signals():
            for guard in guards:
                self.ctl.release_external(guard)

    def facts_of(self, name: str, arity: int) -> set[clingo.Symbol]:
        """Atoms of ``name/arity`` the grounder derived as facts."""
        return {a.symbol for a in self.ctl.symbolic_atoms.by_signature(name, arity) if a.is_fact}

    def stats(self) -> dict:
        """Choices, conflicts, models and solve time of the last solve call (none without :attr:`statistics`)."""
        if not self.statistics:
            return {}
        try:
            return _summary(_statistics(self.ctl))
        except RuntimeError:
            return {}


def _statistics(ctl: clingo.Control) -> Any:
    """clingo's statistics of the last solve call, read lazily (``Control.statistics`` converts
    the whole tree into dicts, where only four numbers are needed)."""
    try:
        from clingo._internal import _c_call, _lib
        from clingo.statistics import StatisticsMap
    except ImportError:  # pragma: no cover - another clingo layout
        return ctl.statistics
    stats = _c_call("clingo_statistics_t*", _lib.clingo_control_statistics, ctl._rep)
    return StatisticsMap(stats, _c_call("uint64_t", _lib.clingo_statistics_root, stats))


def _summary(stats) -> dict:
    """Choices, conflicts, models and solve time from clingo's statistics (empty: none)."""
    try:
        solvers, summary = stats["solving"]["solvers"], stats["summary"]
        return {
            "choices": int(solvers["choices"]),
            "conflicts": int(solvers["conflicts"]),
            "models": int(summary["models"]["enumerated"]),
            "solve_s": round(summary["times"]["solve"], 6),
        }
    except (KeyError, RuntimeError):
        return {}
