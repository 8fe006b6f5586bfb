"""The one wrapper of the MaxSAT solver: PySAT's RC2 (core-guided, OLL with totalizers).

RC2 solves weighted partial MaxSAT with an incremental SAT solver (Glucose 4 here), after
one round of preprocessing of the hard clauses, and strengthens each unsatisfiable core it finds: *trimming* (the core of the core, up to
five times), *minimisation* (dropping literals under a small conflict budget) and
*exhaustion* (raising the bound of a new sum while it stays unsatisfiable).  Its cost
at any moment is the total weight of the cores processed so far, a lower bound on the
optimum.

RC2 itself finishes the iteration a time limit interrupts, and reads a core from the
interrupted call.  :class:`Oracle` does not: once it is told to stop, every call to
the SAT solver raises :class:`Stopped` instead, so the cost it reports afterwards
counts only cores that were proven.  A watcher thread interrupts the SAT solver at the
deadline, or when the caller's ``stop`` says so (a gap reached).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

from pysat.examples.rc2 import RC2, RC2Stratified
from pysat.formula import WCNF

#: the SAT solver under RC2: Glucose 4 (BENCHMARKS.md, "MaxSAT": faster than Glucose 3 on the
#: hard presets, and it stops at once when interrupted, where Glucose 3 ran on for seconds)
SAT_SOLVER = "g4"
#: rounds of PySAT's formula preprocessing before the search (the soft literals frozen):
#: hard-10k 11968 · units 30.2 s against 46.3 s without, hard-4k 4748 10.2 s against 12.1 s
PROCESS = 1
#: how often the watcher looks at the clock and the bound (seconds)
POLL_S = 0.02


class Stopped(Exception):
    """The search was told to stop (deadline or the caller's ``stop``)."""


class _Halting:
    """RC2's SAT calls, always interruptible, and never counting an interrupted call."""

    halt = False
    oracle: Any

    def _call_oracle(self, assumptions=(), expect_interrupt=False):  # noqa: ARG002 (RC2's signature)
        if self.halt:
            raise Stopped
        result = self.oracle.solve_limited(assumptions=list(assumptions), expect_interrupt=True)
        if self.halt:
            raise Stopped
        return result


class _RC2(_Halting, RC2):
    """RC2 for equal weights."""


class _RC2Stratified(_Halting, RC2Stratified):
    """RC2 stratified by weight (the weights differ), the levels found by clustering the
    weights: measured faster on ``success`` than the default (BENCHMARKS.md, "MaxSAT")."""

    def __init__(self, formula: WCNF, **options):
        super().__init__(formula, blo="cluster", **options)


class Oracle:
    """A weighted partial MaxSAT problem: hard clauses, soft unit clauses, one optimum.

    Literals are non-zero integers (DIMACS).  ``soft(lit, w)`` asks for ``lit`` at the
    price ``w`` when it is false.  :meth:`solve` returns the model of an optimum (a set
    of true variables) or None (the hard clauses are unsatisfiable).  Clauses added
    after a solve (``hard``) start a new solver at the next solve: stratification
    hardens soft clauses against the cost of the last model, which a new clause may
    raise.  The lower bound proven before still holds (a clause only removes solutions).
    """

    def __init__(self) -> None:
        self.formula = WCNF()
        self._solver: _RC2 | _RC2Stratified | None = None
        self._lower = 0

    def hard(self, clause: Sequence[int]) -> None:
        self.formula.append(list(clause))
        if self._solver is not None:
            self._lower = self.lower
            self._solver.delete()
            self._solver = None

    def soft(self, lit: int, weight: int) -> None:
        self.formula.append([lit], weight=weight)

    @property
    def lower(self) -> int:
        """The proven lower bound on the optimum's weight (the cores so far)."""
        return self._lower if self._solver is None else max(self._lower, self._solver.cost)

    def solve(
        self,
        deadline: float | None = None,
        stop: Callable[[int], bool] | None = None,
    ) -> set[int] | None:
        """An optimum's true variables, or None when the hard clauses have no model.

        Raises :class:`Stopped` at the ``deadline`` (``time.perf_counter()``) or once
        ``stop(lower)`` is true; :attr:`lower` then holds the bound proven so far."""
        if self._solver is None:
            kind = _RC2 if len(set(self.formula.wght)) <= 1 else _RC2Stratified
            self._solver = kind(
                self.formula, solver=SAT_SOLVER, adapt=True, exhaust=True, minz=True, trim=5, process=PROCESS
            )
        solver = self._solver
        done = threading.Event()

        def watch() -> None:
            while not done.wait(POLL_S):
                if (deadline is not None and time.perf_counter() >= deadline) or (
                    stop is not None and stop(solver.cost)
                ):
                    solver.halt = True
                    solver.oracle.interrupt()

        watcher = None
        if deadline is not None or stop is not None:
            if deadline is not None and time.perf_counter() >= deadline:
                raise Stopped
            watcher = threading.Thread(target=watch, daemon=True)
            watcher.start()
        try:
            model = solver.compute(expect_interrupt=True)
        finally:
            done.set()
            if watcher is not None:
                watcher.join()
            self._lower = max(self._lower, solver.cost)
        if solver.halt:
            raise Stopped
        if model is None:
            return None
        return {lit for lit in model if lit > 0}
