"""The one wrapper of the mixed-integer solver: HiGHS (highspy) on a MaxSAT formula.

A clause ``l1 or ... or lk`` over 0/1 columns is the row ``sum x(positive l) - sum
x(negative l) >= 1 - (number of negative l)``; a variable costing ``w`` when true is
the objective term ``w * x``.  HiGHS solves it by branch and cut on its LP relaxation
(presolve, cutting planes, one thread): a search unlike RC2's cores, and on some goals
with spread weights it proves what the cores cannot reach in time (BENCHMARKS.md,
"HiGHS beside RC2").  Its dual bound is a lower bound at every moment.

:class:`Program` is the only place that talks to HiGHS; it prints nothing (HiGHS's
banner on the first instance of a process is kept off the standard output).
"""

from __future__ import annotations

import math
import os
import sys
import threading
import time
from collections.abc import Callable, Iterable, Sequence
from typing import Any

#: HiGHS prints a banner on the standard output when the first instance of a process is made
_FIRST = threading.Lock()
_made = False


def _highs() -> Any:
    """A silent HiGHS instance (the banner of the first one sent to /dev/null)."""
    global _made
    import highspy

    with _FIRST:
        if _made:
            h = highspy.Highs()
        else:
            sys.stdout.flush()
            saved = os.dup(1)
            null = os.open(os.devnull, os.O_WRONLY)
            try:
                os.dup2(null, 1)
                h = highspy.Highs()
            finally:
                os.dup2(saved, 1)
                os.close(saved)
                os.close(null)
            _made = True
    h.setOptionValue("output_flag", False)
    return h


def available() -> bool:
    """Is highspy installed?"""
    try:
        import highspy  # noqa: F401
    except ImportError:
        return False
    return True


class Program:
    """A 0/1 program: ``nvars`` variables (DIMACS numbering), clauses as rows, a cost per
    variable (``costs``: variable -> weight when true), some variables fixed true.

    :meth:`solve` returns ``("optimal", model)``, ``("infeasible", None)`` or
    ``("stopped", incumbent)`` (the best model found, or None) with :attr:`lower` the
    proven lower bound (an integer: the costs are integers)."""

    def __init__(self, nvars: int, costs: dict[int, int], true: Iterable[int] = ()):
        import highspy
        import numpy as np

        self._hp, self._np = highspy, np
        self.n = nvars
        self.costs = dict(costs)
        self.lower = 0
        h = self.h = _highs()
        h.setOptionValue("threads", 1)
        h.setOptionValue("mip_rel_gap", 0.0)
        h.setOptionValue("mip_abs_gap", 0.5)  # integer costs: a gap below 1 is none
        lo, hi = np.zeros(nvars), np.ones(nvars)
        for v in true:
            lo[v - 1] = 1.0
        h.addVars(nvars, lo, hi)
        cols = np.arange(nvars, dtype=np.int32)
        cost = np.zeros(nvars)
        for v, w in costs.items():
            cost[v - 1] = float(w)
        h.changeColsCost(nvars, cols, cost)
        h.changeColsIntegrality(nvars, cols, np.full(nvars, highspy.HighsVarType.kInteger))
        self._halt: Callable[[], bool] = lambda: False
        #: called with the new bound whenever HiGHS raises it during a solve (the caller's to set)
        self.on_lower: Callable[[int], None] = lambda bound: None
        self._deadline: float | None = None
        h.cbMipInterrupt += self._on_mip
        h.cbSimplexInterrupt += self._on_simplex

    def add(self, clauses: Iterable[Sequence[int]]) -> None:
        """Clauses as rows (one call to HiGHS for all of them)."""
        np = self._np
        starts: list[int] = []
        index: list[int] = []
        value: list[float] = []
        lows: list[float] = []
        for clause in clauses:
            starts.append(len(index))
            negative = 0
            for lit in clause:
                index.append(abs(lit) - 1)
                value.append(1.0 if lit > 0 else -1.0)
                negative += lit < 0
            lows.append(1.0 - negative)
        if not starts:
            return
        m = len(starts)
        self.h.addRows(
            m,
            np.array(lows),
            np.full(m, self._hp.kHighsInf),
            len(index),
            np.array(starts, dtype=np.int32),
            np.array(index, dtype=np.int32),
            np.array(value),
        )

    def _stopping(self) -> bool:
        return self._halt() or (self._deadline is not None and time.perf_counter() >= self._deadline)

    def _on_mip(self, event: Any) -> None:
        bound = event.data_out.mip_dual_bound
        if math.isfinite(bound) and _ceil(bound) > self.lower:
            self.lower = _ceil(bound)
            self.on_lower(self.lower)
        if self._stopping():
            event.interrupt()

    def _on_simplex(self, event: Any) -> None:
        if self._stopping():
            event.interrupt()

    def solve(
        self, deadline: float | None = None, halt: Callable[[], bool] | None = None
    ) -> tuple[str, set[int] | None]:
        """The optimum's true variables (see the class); ``deadline`` (``time.perf_counter()``)
        and ``halt()`` end it early."""
        hp, h = self._hp, self.h
        self._halt = halt or (lambda: False)
        self._deadline = deadline
        if deadline is not None:
            left = deadline - time.perf_counter()
            if left <= 0:
                return "stopped", None
            h.setOptionValue("time_limit", left)
        h.run()
        status = h.getModelStatus()
        if status == hp.HighsModelStatus.kInfeasible:
            return "infeasible", None
        model = None
        if h.getInfo().primal_solution_status == 2:  # feasible
            values = h.getSolution().col_value
            model = {v + 1 for v in range(self.n) if values[v] > 0.5}
        if status == hp.HighsModelStatus.kOptimal and model is not None:
            self.lower = max(self.lower, sum(self.costs.get(v, 0) for v in model))
            return "optimal", model
        bound = h.getInfo().mip_dual_bound
        if math.isfinite(bound):
            self.lower = max(self.lower, _ceil(bound))
        return "stopped", model


def _ceil(bound: float) -> int:
    """The least integer at or above ``bound``, less HiGHS's relative tolerance (a bound
    must never exceed the optimum)."""
    return max(0, math.ceil(bound - 1e-6 * max(1.0, abs(bound))))
