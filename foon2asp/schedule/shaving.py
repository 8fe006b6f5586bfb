"""Shaving: each unit's kinds and window narrowed at a makespan by ruling out one choice at a time.

A choice (a unit on one kind, starting at its earliest start, ending at its latest end) is
ruled out when, with it, precedence and the energetic test of the kinds
(:mod:`foon2asp.schedule.lower_bounds`) fail; what is left holds in every schedule of that
makespan (docs/proofs/schedules.md, "Shaving").
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace

from foon2asp.schedule.instances import Entry, Instance, divisor, earliest, human_units, tails
from foon2asp.schedule.lower_bounds import Window, human_capacity, slack_of_windows, window_tests

#: seconds a search runs before shaving narrows its problem beside it (schedule/encode.py)
AFTER = 2.0
#: the windows each choice is tested on: the tightest of the domains at the start of a round
WINDOWS = 25
#: rounds, each choosing the tightest windows anew
ROUNDS = 5
#: the least slack of a window that fits (the split is fractional)
EPSILON = 1e-6


@dataclass
class Domains:
    """What every schedule within a makespan keeps to: each unit's kinds (with their
    durations), earliest start and latest end (ms)."""

    durations: dict[int, dict[str, int]]
    release: dict[int, int]
    deadline: dict[int, int]

    def copy(self) -> Domains:
        return Domains({u: dict(d) for u, d in self.durations.items()}, dict(self.release), dict(self.deadline))

    def least(self, u: int) -> int:
        return min(self.durations[u].values())

    def starts(self) -> dict[int, tuple[int, int]]:
        """Each unit's start window: its earliest start and its latest at its least duration."""
        return {u: (r, self.deadline[u] - self.least(u)) for u, r in self.release.items()}

    def tails(self, inst: Instance, tail: dict[int, int]) -> dict[int, int]:
        """``tail`` (:func:`foon2asp.schedule.instances.tails`) with each unit's own least
        duration that of its kinds left (the chain after it unchanged)."""
        return {u: tail[u] - inst.min_duration(u) + self.least(u) for u in inst.units}


def _propagate(inst: Instance, dom: Domains) -> bool:
    """Tighten ``dom`` in place along precedence to a fixpoint, dropping the kinds too long for
    a unit's window; False when a unit has none left."""
    preds = inst.preds
    several = [(v, [m for m in ms if m != v]) for v in inst.units for _, ms in inst.needs[v] if len(ms) > 1]
    r, e = dom.release, dom.deadline
    changed = True
    while changed:
        changed = False
        for v in inst.units:
            for p in preds[v]:
                if r[p] + dom.least(p) > r[v]:
                    r[v], changed = r[p] + dom.least(p), True
                if e[v] - dom.least(v) < e[p]:
                    e[p], changed = e[v] - dom.least(v), True
        for v, makers in several:  # v waits for one of them
            first = min((r[m] + dom.least(m) for m in makers), default=r[v])
            if first > r[v]:
                r[v], changed = first, True
        for u in inst.units:
            too_long = [k for k, d in dom.durations[u].items() if d > e[u] - r[u]]
            for k in too_long:
                del dom.durations[u][k]
            if not dom.durations[u]:
                return False
            changed = changed or bool(too_long)
    return True


def _tightened(inst: Instance, dom: Domains, windows: list[Window]) -> Domains | None:
    """A copy of ``dom`` tightened by precedence, or None when it or the ``windows`` fail."""
    dom = dom.copy()
    if not _propagate(inst, dom):
        return None
    narrowed = replace(inst, durations=dom.durations)
    if slack_of_windows(narrowed, dom.release, dom.deadline, windows)[0] < -EPSILON:
        return None
    return dom


def _tightest(inst: Instance, dom: Domains, count: int) -> tuple[float, list[Window]]:
    """The least slack over every window of ``dom`` and the ``count`` tightest windows."""
    narrowed = replace(inst, durations=dom.durations)
    tests = window_tests(narrowed, dom.release, dom.deadline)
    return slack_of_windows(narrowed, dom.release, dom.deadline, tests, count)


def _shave_unit(inst: Instance, dom: Domains, u: int, windows: list[Window], step: int) -> Domains | None:
    """A copy of ``dom`` with the kinds and ends of ``u``'s window that fail ruled out; None
    when every choice fails."""
    dom = dom.copy()
    for k in list(dom.durations[u]):
        if len(dom.durations[u]) < 2:
            break
        trial = dom.copy()
        trial.durations[u] = {k: dom.durations[u][k]}
        if _tightened(inst, trial, windows) is None:
            del dom.durations[u][k]
            found = _tightened(inst, dom, windows)
            if found is None:
                return None
            dom = found
    for early in (True, False):
        while True:
            trial = dom.copy()
            longest = max(dom.durations[u].values())
            if early:  # u starts at its earliest start (ends by it plus its longest duration)
                trial.deadline[u] = min(dom.deadline[u], dom.release[u] + longest)
            else:  # u ends at its latest end
                trial.release[u] = max(dom.release[u], dom.deadline[u] - longest)
            if _tightened(inst, trial, windows) is not None:
                break
            dom = dom.copy()
            if early:
                dom.release[u] += step
            else:
                dom.deadline[u] -= step
            found = _tightened(inst, dom, windows)
            if found is None:
                return None
            dom = found
    return dom


def shave(
    inst: Instance,
    horizon: int,
    windows: int = WINDOWS,
    rounds: int = ROUNDS,
    left: Callable[[], float | None] | None = None,
) -> Domains | None:
    """The domains every schedule of ``inst`` with makespan at most ``horizon`` keeps to; None
    when shaving shows there is no such schedule.  ``left``: the time left (0: stop narrowing
    and return the domains so far)."""
    start, tail = earliest(inst), tails(inst)
    if len(start) < len(inst.units) or inst.incapable():
        return None
    step = divisor(inst)
    horizon -= horizon % step  # every start and end is on the step grid
    dom = Domains(
        {u: dict(inst.durations[u]) for u in inst.units},
        dict(start),
        {u: horizon - tail[u] + inst.min_duration(u) for u in inst.units},
    )
    found = _tightened(inst, dom, [])
    if found is None:
        return None
    dom = found
    for _ in range(rounds):
        least, tight = _tightest(inst, dom, windows)
        if least < -EPSILON:
            return None
        before = dom.copy()
        while True:
            last = dom.copy()
            for u in inst.units:
                if left is not None and left() == 0.0:
                    return dom
                shaved = _shave_unit(inst, dom, u, tight, step)
                if shaved is None:
                    return None
                dom = shaved
            if dom == last:
                break
        if dom == before:
            break
    return dom if _tightest(inst, dom, 0)[0] >= -EPSILON else None


def human_floor(inst: Instance, dom: Domains) -> int:
    """The fewest units a person does in every schedule that keeps to ``dom``."""
    span = {u: (dom.release[u], dom.deadline[u]) for u in inst.units}
    return human_capacity(replace(inst, durations=dom.durations), span)


def least_floor(inst: Instance, floor: int, below: int, left: Callable[[], float | None]) -> tuple[int, Domains | None]:
    """The least makespan from ``floor`` on, a step at a time and below ``below``, that shaving
    leaves possible, with its domains (None: none below ``below``, or no time is left)."""
    step = divisor(inst)
    while floor < below and left() != 0.0:
        dom = shave(inst, floor, left=left)
        if dom is not None:
            return floor, dom
        floor += step
    return floor, None


class HumanStop:
    """The stop of a search for the fewest human units at makespan ``horizon`` at ``low``
    (``fewest``: the count of the schedule known before; ``report``: told each schedule and
    the count): :meth:`shave`, asked while the search runs, raises ``low`` by
    :func:`human_floor` once the search has run :data:`AFTER`."""

    def __init__(
        self,
        inst: Instance,
        horizon: int,
        low: int,
        left: Callable[[], float | None],
        fewest: int | None,
        report: Callable[[list[Entry], int], None],
    ) -> None:
        self.inst, self.horizon, self.low, self.left, self.fewest, self.report = (
            inst,
            horizon,
            low,
            left,
            fewest,
            report,
        )
        self.since = time.perf_counter()
        self.shaved = False

    def __call__(self, entries: list[Entry]) -> bool:
        self.report(entries, self.low)
        found = human_units(entries)
        self.fewest = found if self.fewest is None else min(self.fewest, found)
        return found <= self.low

    def shave(self) -> bool:
        """Shave once the search has run long enough; is a schedule found at the raised count?"""
        if self.shaved or time.perf_counter() - self.since < AFTER:
            return False
        self.shaved = True
        dom = shave(self.inst, self.horizon, left=self.left)
        if dom is not None:
            self.low = max(self.low, human_floor(self.inst, dom))
        return self.fewest is not None and self.fewest <= self.low
