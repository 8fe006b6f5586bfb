"""The one wrapper of the MaxSAT solver: PySAT's RC2 (core-guided, OLL with totalizers).

RC2 solves weighted partial MaxSAT with an incremental SAT solver (Glucose 4 here), after
one round of preprocessing of the hard clauses, and strengthens each unsatisfiable core it finds: *trimming* (the core of the core, up to
five times), *minimisation* (dropping literals under a small conflict budget; with equal
weights only for small cores, :data:`MINIMISE_UP_TO`) and
*exhaustion* (raising the bound of a new sum while it stays unsatisfiable).  Its cost
at any moment is the total weight of the cores processed so far, a lower bound on the
optimum.

RC2 itself finishes the iteration a time limit interrupts, and reads a core from the
interrupted call.  :class:`Oracle` does not: once it is told to stop, every call to
the SAT solver raises :class:`Stopped` instead, so the cost it reports afterwards
counts only cores that were proven.  The search runs on a thread of its own and the
caller watches it: it interrupts the SAT solver at the deadline, or when the caller's
``stop`` says so (a gap reached), and goes on without it if the solver has not answered
the interrupt a moment later.

*The smallest optimum.*  Once RC2 has an optimum, the models of its SAT solver under
its assumptions (every soft literal and every bound of a relaxed core) are exactly the
optima: the cost of a model is the bound plus the weights of the assumptions it
violates.  :meth:`Oracle.smallest` walks from the optimum found to the
lexicographically smallest one over an order of variables, on the same solver (its
cores and learnt clauses kept): each step asks for an optimum that agrees with the
current one up to a variable that it makes true and the current one has false; none
left is the proof.  The steps share a budget of SAT conflicts, so the optimum it ends
with depends only on the input.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from pysat.examples.rc2 import RC2, RC2Stratified
from pysat.formula import WCNF
from pysat.process import Processor

#: the SAT solver under RC2: Glucose 4 (BENCHMARKS.md, "MaxSAT": faster than Glucose 3 on the
#: hard presets, and it stops at once when interrupted, where Glucose 3 ran on for seconds)
SAT_SOLVER = "g4"
#: rounds of PySAT's formula preprocessing before the search (the soft literals frozen):
#: hard-10k 11968 · units 30.2 s against 46.3 s without, hard-4k 4748 10.2 s against 12.1 s
PROCESS = 1
#: with equal weights, RC2 minimises the cores of at most this many literals (larger ones as
#: found): every 20th object of hard-4k 33.9 s against 49.1 s, hard-4k 4748 11.0 s against 6.2 s
#: (BENCHMARKS.md, "Searches that would fail")
MINIMISE_UP_TO = 8
#: the budget of :meth:`Oracle.smallest`, in conflicts of the SAT solver
CONFLICTS = 5000
#: how often the watcher looks at the clock and the bound (seconds)
POLL_S = 0.02
#: how long after an interrupt the caller waits for the SAT call to end (seconds)
GIVE_UP_S = 0.25


class Stopped(Exception):
    """The search was told to stop (deadline or the caller's ``stop``)."""


class _Halting:
    """RC2's SAT calls, always interruptible, and never counting an interrupted call."""

    halt = False
    #: a call still runs on its thread (the caller gave up waiting): deleted by nobody
    abandoned = False
    oracle: Any
    process: int
    processor: Any

    def init(self, formula: WCNF, incr: bool = False) -> None:
        """RC2's set-up, the hard clauses preprocessed (:data:`PROCESS` rounds, the soft
        literals frozen) before RC2 sees them: RC2 then adds them as they are and
        restores each model through the preprocessor, as when it preprocesses itself."""
        rounds = self.process
        if not rounds:
            super().init(formula, incr)  # type: ignore[misc]
            return
        processor = Processor(bootstrap_with=formula.hard)
        frozen = [clause[0] for clause in formula.soft]  # soft clauses are unit clauses here
        # CaDiCaL's clauses as they come: Processor.process deep-copies them (4.7 of 41 s on every
        # 20th object of hard-4k, BENCHMARKS.md, "Less Python around the solver"); PySAT's defaults
        _, clauses = processor.cadical.process(rounds=rounds, freeze=frozen)
        processed = WCNF()
        processed.hard, processed.soft, processed.wght = clauses, formula.soft, formula.wght
        processed.nv, processed.topw = formula.nv, formula.topw
        self.process = 0
        try:
            super().init(processed, incr)  # type: ignore[misc]
        finally:
            self.process = rounds
        self.processor = processor

    def _call_oracle(self, assumptions=(), expect_interrupt=False):  # noqa: ARG002 (RC2's signature)
        if self.halt:
            raise Stopped
        result = self.oracle.solve_limited(assumptions=list(assumptions), expect_interrupt=True)
        if self.halt:
            raise Stopped
        return result


class _RC2(_Halting, RC2):
    """RC2 for equal weights, minimising only cores of at most :data:`MINIMISE_UP_TO` literals."""

    def minimize_core(self) -> None:
        if len(self.core) <= MINIMISE_UP_TO:
            super().minimize_core()


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
        # the formula as plain lists, handed to RC2 as a WCNF at the next solve (appending to a
        # WCNF clause by clause cost 2.3 of 41 s on every 20th object of hard-4k)
        self._hard: list[list[int]] = []
        self._soft: list[list[int]] = []
        self._weights: list[int] = []
        #: the highest variable so far
        self._top = 0
        self._solver: _RC2 | _RC2Stratified | None = None
        self._lower = 0
        #: the true variables of the last optimum
        self._model: set[int] = set()

    def hard(self, clause: Sequence[int]) -> None:
        self.hards([list(clause)])

    def hards(self, clauses: Iterable[list[int]], top: int | None = None) -> None:
        """Hard clauses, many at once (lists the oracle keeps); ``top``: their highest
        variable, when the caller knows it."""
        new = list(clauses)
        self._hard += new
        if top is None:
            top = max((abs(lit) for clause in new for lit in clause), default=0)
        self._top = max(self._top, top)
        if self._solver is not None:
            self._lower = self.lower
            if not self._solver.abandoned:
                self._solver.delete()
            self._solver = None

    def soft(self, lit: int, weight: int) -> None:
        self._soft.append([lit])
        self._weights.append(weight)
        self._top = max(self._top, abs(lit))

    @property
    def formula(self) -> WCNF:
        """The problem as PySAT's WCNF (its lists are the oracle's: RC2 only reads them here)."""
        formula = WCNF()
        formula.hard, formula.soft, formula.wght = self._hard, self._soft, self._weights
        formula.nv, formula.topw = self._top, sum(self._weights) + 1
        return formula

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
            kind = _RC2 if len(set(self._weights)) <= 1 else _RC2Stratified
            self._solver = kind(
                self.formula, solver=SAT_SOLVER, adapt=True, exhaust=True, minz=True, trim=5, process=PROCESS
            )
        solver = self._solver
        try:
            model = _watched(solver, deadline, stop, lambda: solver.compute(expect_interrupt=True))
        finally:
            self._lower = max(self._lower, solver.cost)
        if model is None:
            return None
        self._model = {lit for lit in model if lit > 0}
        return self._model

    def smallest(
        self, order: Sequence[int], deadline: float | None = None, conflicts: int = CONFLICTS
    ) -> tuple[set[int], str]:
        """After :meth:`solve` found an optimum: the true variables among ``order`` of the
        lexicographically smallest optimum (the first variable of ``order`` on which two
        optima differ is true in the smaller), and how the walk ended: ``"complete"``
        (proven smallest), ``"budget"`` (``conflicts`` spent: the smallest reached) or
        ``"time"`` (the ``deadline``).  Each variable of ``order`` must cost when true (its
        negation a soft literal: frozen by the preprocessing, and a model with one more of
        them true costs more)."""
        solver = self._solver
        assert solver is not None, "smallest() after solve()"
        sat = solver.oracle
        assumptions = list(solver.active_assumps())
        # a variable the assumptions make false is false in every optimum: the walk leaves it out
        # (the order among the others is the same), which spares about one clause per such
        # variable and step (most of the part's units, whose soft literals no core holds)
        assumed = set(assumptions)
        order = [v for v in order if -v not in assumed]
        current = {v for v in order if v in self._model}
        spent = sat.accum_stats()["conflicts"]
        while True:
            left = conflicts - (sat.accum_stats()["conflicts"] - spent)
            if left <= 0:
                return current, "budget"
            act = solver.pool.id()
            sat.append_formula([[-act, *clause] for clause in _smaller(order, current, solver.pool.id)])
            sat.conf_budget(left)
            try:
                step = [*assumptions, act]
                found = _watched(solver, deadline, None, lambda: sat.solve_limited(step, True))  # noqa: B023
            except Stopped:
                return current, "time"
            finally:
                if not solver.abandoned:  # (an abandoned call still runs on the solver)
                    sat.add_clause([-act])  # the step's clauses off for good
                    sat.conf_budget(-1)
            if found is None:
                return current, "budget"
            if not found:
                return current, "complete"
            model = sat.get_model()
            current = {v for v in order if model[v - 1] > 0}


def _smaller(order: Sequence[int], current: set[int], new: Callable[[], int]) -> list[list[int]]:
    """Clauses whose models are lexicographically smaller than ``current`` over ``order``.

    The variables of ``order`` true in ``current`` cut it into gaps (the false ones before
    the first, between two, ...).  A model is smaller when, for some gap, it has every true
    variable of ``current`` before the gap true, every variable of the earlier gaps false
    and some variable of the gap true (the first of those is where it first differs, and
    it makes it true).  A selector ``s`` per gap says so; ``z`` (per gap) says that the
    model agrees with ``current`` on everything before the gap, as a chain.  So the clauses
    number about one per variable of ``order`` and the new variables two per true one.
    Only gaps before the last variable true in ``current`` count: a model that agrees with
    ``current`` up to a later variable and makes it true has more true variables than
    ``current``, so it costs more (every soft literal here weighs something)."""
    clauses: list[list[int]] = []
    some: list[int] = []
    gap: list[int] = []
    agree = 0  # "the model agrees with current on everything before here" (0: nothing yet, true)
    for v in order:
        if v not in current:
            gap.append(v)
            continue
        if gap:  # the gap before v: some variable of it true, everything before it agreeing
            s = new()
            some.append(s)
            clauses.append([-s, *gap])
            if agree:
                clauses.append([-s, agree])
        z = new()  # agrees up to and including v: the gap false, v true, and before it
        clauses.extend([-z, -g] for g in gap)
        clauses.append([-z, v])
        if agree:
            clauses.append([-z, agree])
        agree, gap = z, []
    clauses.append(some)
    return clauses


def _watched(solver: Any, deadline: float | None, stop: Callable[[int], bool] | None, call: Callable[[], Any]) -> Any:
    """``call()`` on RC2 ``solver``, interrupted at the ``deadline`` (``time.perf_counter()``)
    or once ``stop(cost)`` is true, which raises :class:`Stopped`.

    The call runs on a thread of its own: Glucose answers an interrupt only at its next
    conflict check, seconds later at times (BENCHMARKS.md, "Time limits overrun"), so
    :data:`GIVE_UP_S` after the interrupt the caller stops waiting and goes on; the call
    ends by itself later (every SAT call after the interrupt raises :class:`Stopped`) and
    keeps the solver alive until then."""
    if deadline is None and stop is None:
        return call()
    if deadline is not None and time.perf_counter() >= deadline:
        raise Stopped
    box: dict[str, Any] = {}
    finished = threading.Event()

    def run(keep: Any) -> None:  # ``keep``: the solver stays alive while its call runs
        try:
            box["result"] = call()
        except BaseException as error:  # noqa: BLE001 (handed to the caller's thread)
            box["error"] = error
        finally:
            finished.set()

    threading.Thread(target=run, args=(solver,), daemon=True).start()
    halted = None
    try:
        while not finished.wait(POLL_S):
            now = time.perf_counter()
            if halted is None:
                if (deadline is not None and now >= deadline) or (stop is not None and stop(solver.cost)):
                    solver.halt = True
                    solver.oracle.interrupt()
                    halted = now
            elif now - halted >= GIVE_UP_S:
                raise Stopped
            else:
                solver.oracle.interrupt()
    except BaseException:  # given up, or an interrupt (Ctrl-C) or error here: the call is told to stop
        solver.halt = True
        solver.oracle.interrupt()
        if not finished.is_set():
            solver.abandoned = True  # never deleted by the caller: its call still runs
        raise
    if "error" in box:
        raise box["error"]
    if solver.halt:
        raise Stopped
    return box["result"]
