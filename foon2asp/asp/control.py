"""The one wrapper around :class:`clingo.Control` that solving and queries share.

It adds named programs and grounds them so that a syntax or grounding error
becomes one :class:`~foon2asp.errors.InputError` naming the program (a user
file, ``--rule #N``, ...), and it solves with an optional time limit on the
asynchronous solve handle, so a time-out or an interrupt stops clingo's
search through the handle (never by tearing the control down mid-call).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

import clingo

from foon2asp.asp.constraints import check, clingo_error
from foon2asp.errors import InputError


@dataclass
class Answer:
    """One model as foon2asp reads it: the tree's units (sorted), the cost vector,
    whether the optimum is proven, human steps, and the shown symbols."""

    units: tuple[int, ...] = ()
    cost: tuple[int, ...] = ()
    proven: bool = False
    human: tuple[int, ...] = ()
    symbols: list[clingo.Symbol] = field(default_factory=list)


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


class Control:
    """A clingo control with named programs, one-line errors and time-limited solving."""

    def __init__(self, args: Sequence[str] = (), message_limit: int = 20) -> None:
        self.messages: list[str] = []
        self.user_programs: list[tuple[str, str]] = []
        try:
            self.ctl = clingo.Control(list(args), logger=self._log, message_limit=message_limit)
        except RuntimeError as exc:
            raise InputError(f"bad solver option: {' '.join(str(exc).split())}") from None

    def _log(self, code: clingo.MessageCode, message: str) -> None:
        self.messages.append(" ".join(message.split()))

    def add(self, name: str, text: str, user: bool = False) -> None:
        """Add program ``text`` (called ``name`` in errors) to the base part."""
        self.messages.clear()
        if user:
            self.user_programs.append((name, text))
        try:
            self.ctl.add("base", [], text)
        except RuntimeError:
            raise clingo_error(self.messages, name) from None

    def add_all(self, parts: Iterable[tuple[str, str]], user: Iterable[str] = ()) -> None:
        users = set(user)
        for name, text in parts:
            self.add(name, text, name in users)

    def ground(self, parts: Sequence[tuple[str, Sequence[clingo.Symbol]]] = (("base", ()),)) -> None:
        """Ground ``parts``; on an error the user programs are checked one by one to name the culprit."""
        self.messages.clear()
        try:
            self.ctl.ground([(name, list(args)) for name, args in parts])
        except RuntimeError:
            for name, text in self.user_programs:
                check(name, text)
            msg = self.messages[0] if self.messages else "error"
            raise InputError(msg.replace("<block>", "program")) from None

    def solve(
        self,
        on_model: Callable[[clingo.Model], bool | None] | None = None,
        time_limit: float | None = None,
        assumptions: Sequence[tuple[clingo.Symbol, bool]] = (),
    ) -> SolveResult:
        """Solve, stopping after ``time_limit`` seconds (None: no limit) through the solve handle.

        A KeyboardInterrupt while waiting cancels the search cleanly before it is re-raised.
        """
        t0 = time.perf_counter()
        with self.ctl.solve(on_model=on_model, async_=True, assumptions=list(assumptions)) as handle:
            try:
                if time_limit is None:
                    # wait in slices so that signals are seen between them
                    while not handle.wait(0.5):
                        pass
                    finished = True
                else:
                    finished = bool(handle.wait(max(0.0, time_limit)))
            except BaseException:
                handle.cancel()
                handle.get()
                raise
            if not finished:
                handle.cancel()
            result = handle.get()
        return SolveResult(
            finished and not result.interrupted,
            result.satisfiable,
            result.unsatisfiable,
            bool(result.exhausted),
            bool(result.interrupted),
            time.perf_counter() - t0,
        )

    def facts_of(self, name: str, arity: int) -> set[clingo.Symbol]:
        """Atoms of ``name/arity`` the grounder derived as facts."""
        return {a.symbol for a in self.ctl.symbolic_atoms.by_signature(name, arity) if a.is_fact}

    def stats(self) -> dict:
        """Choices, conflicts, models and solve time of the last solve call."""
        try:
            s = self.ctl.statistics
            solving = s["solving"]["solvers"]
            summary = s["summary"]
            return {
                "choices": int(solving["choices"]),
                "conflicts": int(solving["conflicts"]),
                "models": int(summary["models"]["enumerated"]),
                "solve_s": round(summary["times"]["solve"], 6),
            }
        except (KeyError, RuntimeError):
            return {}
