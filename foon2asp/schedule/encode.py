"""The two schedule encodings and their solving: time steps (plain ASP) and clingo-dl.

``steps``: ``schedule_steps.lp`` (``schedule_order.lp`` for a fixed tree without durations 0),
start steps chosen by clasp; ``dl``: ``schedule_dl.lp``, clingo-dl start times, the makespan
minimised by descending bounds.  Both read the facts of :func:`schedule_facts`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import clingo

from foon2asp.asp import encoding_files
from foon2asp.asp.control import Control, remaining
from foon2asp.asp.facts import q
from foon2asp.asp.interrupts import signal_pending
from foon2asp.errors import InputError
from foon2asp.schedule import shaving
from foon2asp.schedule.instances import Entry, Instance, assign_agents, compact, divisor, human_units, makespan
from foon2asp.schedule.lower_bounds import human_lower
from foon2asp.schedule.spec import HUMAN

ENCODINGS = ("steps", "dl")

#: seconds of the search for a schedule at the makespan shaving leaves, on its domains
DECIDE = 0.5


@dataclass
class Solution:
    """What an encoding ended with."""

    #: the best schedule found (None: none)
    entries: list[Entry] | None = None
    #: its makespan is proven minimal
    proven: bool = False
    #: no schedule exists (for joint scheduling: for no valid tree)
    unsatisfiable: bool = False
    #: the units scheduled (joint: the chosen tree)
    units: tuple[int, ...] = ()
    stats: dict = field(default_factory=dict)


@dataclass
class Job:
    """What both encodings solve: an instance, each unit's earliest start (``head``) and least
    time from its start to the end (``tail``), a known makespan (``horizon``) and a lower bound
    (``floor``), in ms; joint: ``tree_parts``, ``levels`` tree objectives and ``user`` programs."""

    inst: Instance
    head: dict[int, int]
    tail: dict[int, int]
    horizon: int
    floor: int = 0
    args: Sequence[str] = ()
    tree_parts: Sequence[tuple[str, str]] = ()
    levels: int = 0
    user: Sequence[str] = ()
    #: optimise the tie-breakers even when the known schedule stays the best
    ties: bool = True
    #: the schedule of makespan ``horizon`` known beforehand (fixed trees; None: none given)
    known: list[Entry] | None = None
    #: called with ``{"makespan", "lower", "human", "human_lower", "phase"}`` (ms) as schedules improve
    progress: Callable[[dict], None] | None = None

    @property
    def fixed(self) -> bool:
        return not self.tree_parts

    @property
    def breakers(self) -> bool:
        """Are there tie-breakers: the tree objective, or a human kind?"""
        return bool(self.levels) or HUMAN in self.inst.kinds

    def windows(self, horizon: int) -> dict[int, tuple[int, int]] | None:
        """Each unit's start window within ``horizon``; None when a given unit has none."""
        w = {
            u: (e, horizon - self.tail[u])
            for u, e in self.head.items()
            if u in self.tail and e <= horizon - self.tail[u]
        }
        return None if self.fixed and len(w) < len(self.inst.units) else w


def _zeros(inst: Instance) -> bool:
    """Does some unit take no time on some kind?"""
    return any(d == 0 for table in inst.durations.values() for d in table.values())


def schedule_facts(
    inst: Instance, scale: int, windows: dict[int, tuple[int, int]], fixed: bool, agents: bool, tail: dict | None = None
) -> str:
    """The facts both encodings read; times divided by ``scale``; ``fixed``: the units are
    given (``use/1`` facts), else tree.lp chooses them; ``agents``: ``agent(K,I)`` facts (dl)."""
    lines = ["% schedule"]
    if _zeros(inst):
        lines.append("zeros.")
    makers: set[tuple[int, int]] = set()
    for kind, n in inst.kinds.items():
        lines.append(f"kind({q(kind)},{n}).")
        if agents:
            lines += [f"agent({q(kind)},{i})." for i in range(1, n + 1)]
        if kind == HUMAN:
            lines.append(f"human_kind({q(kind)}).")
    for u in inst.units:
        if u not in windows:
            continue  # never ready, or nobody can do it: no tree uses it
        if fixed:
            lines.append(f"use({u}).")
        lines += [f"can({u},{q(kind)},{d // scale})." for kind, d in inst.durations[u].items()]
        e, last = windows[u]
        lines.append(f"window({u},{e // scale},{last // scale}).")
        if tail is not None:
            lines.append(f"tail({u},{tail[u] // scale}).")
        for o, ms in inst.needs[u]:
            lines.append(f"need({u},{o}).")
            makers.update((m, o) for m in ms if m in windows)
        lines += [f"uses({u},{q(r)})." for r in inst.uses[u]]
    lines += [f"maker({m},{o})." for m, o in sorted(makers)]
    lines += [f"capacity({q(r)},{c})." for r, c in inst.capacity.items()]
    return "\n".join(lines) + "\n"


def _priorities(levels: int, only: str | None = None) -> str:
    """The makespan above the human units above ``levels`` tree objectives (priorities 1..levels);
    ``only``: that one objective alone (``makespan`` or ``human``)."""
    both = {"makespan": f"priority(makespan,{levels + 2}).\n", "human": f"priority(human,{levels + 1}).\n"}
    return both[only] if only else "".join(both.values())


def _grounded(control: Control, job: Job, entry: str, parts: Sequence[tuple[str, str]]) -> Control:
    """``control`` with the schedule's facts ``parts``, the schedule entry ``entry`` and, for joint
    scheduling, the tree's encoding (``joint_tree.lp``) and facts, grounded."""
    control.add_all(parts)
    control.load(encoding_files.entry(entry))
    if not job.fixed:
        control.load(encoding_files.entry("joint_tree"))
    control.add_all(job.tree_parts, user=job.user)
    control.ground()
    return control


def _entries_of_steps(inst: Instance, atoms: Sequence[clingo.Symbol], scale: int) -> list[Entry]:
    """The schedule of a model: kinds and start steps, the agents dealt per kind."""
    kind: dict[int, str] = {}
    start: dict[int, int] = {}
    for s in atoms:
        if s.name == "on" and len(s.arguments) == 2:
            kind[s.arguments[0].number] = s.arguments[1].string
        elif s.name == "start" and len(s.arguments) == 2:
            start[s.arguments[0].number] = s.arguments[1].number * scale
    return assign_agents(inst, kind, start)


def _steps_once(
    job: Job,
    windows: dict,
    horizon: int,
    floor: int,
    time_limit: float | None,
    only: str | None = None,
    enough: Callable[[list[Entry]], bool] | None = None,
    stop: Callable[[], bool] | None = None,
) -> Solution:
    """One grounding and optimisation of the time-step encoding with makespan at most
    ``horizon`` (``only``: that objective alone; ``enough``: stop at a schedule it accepts;
    ``stop``: asked now and then while the search runs, stops it when true); ``proven``: the
    search ended, or ``enough`` accepted a schedule (returned compacted)."""
    inst = job.inst
    scale = divisor(inst)
    name = "schedule_order" if job.fixed and not _zeros(inst) else "schedule_steps"
    parts = [
        ("schedule facts", schedule_facts(inst, scale, windows, job.fixed, False, job.tail if job.fixed else None)),
        ("horizon", f"horizon({horizon // scale}).\nfloor({-(-floor // scale)}).\n" + _priorities(job.levels, only)),
    ]
    control = _grounded(Control(["--opt-mode=opt", *job.args]), job, name, parts)
    best: dict[str, Any] = {}

    def on_model(model: clingo.Model) -> bool:
        best["atoms"] = model.symbols(shown=True)
        best["met"] = enough is not None and enough(_entries_of_steps(inst, best["atoms"], scale))
        return not best["met"]

    result = control.solve(on_model, time_limit, stop=stop)
    stats = control.stats()
    if "atoms" not in best:
        return Solution(None, result.finished, result.finished and bool(result.unsatisfiable), (), stats)
    units = used(best["atoms"]) if not job.fixed else inst.units
    entries = _entries_of_steps(inst, best["atoms"], scale)
    if best["met"]:
        return Solution(compact(inst, entries), True, False, units, stats)
    return Solution(entries, result.finished, False, units, stats)


def solve_steps(job: Job, time_limit: float | None = None) -> Solution:
    """Solve with the time-step encoding within the known makespan ``job.horizon``: one
    lexicographic optimisation, or for a fixed tree with a person :func:`_steps_in_phases`."""
    stats: dict[str, Any] = {"encoding": "steps"}
    windows = job.windows(job.horizon)
    if windows is None:  # a unit cannot start and still end in time: no schedule within the horizon
        return Solution(None, True, True, (), stats)
    if job.fixed and job.breakers:
        return _steps_in_phases(job, windows, stats, time_limit)
    sol = _steps_once(job, windows, job.horizon, job.floor, time_limit, enough=_short(job) if job.fixed else None)
    stats.update(sol.stats)
    if sol.entries is not None and not sol.proven:
        stats["tie_breakers"] = "time"
    proven = sol.proven or (sol.entries is not None and makespan(sol.entries) <= job.floor)
    return replace(sol, proven=proven, stats=stats)


def _report(job: Job, entries: list[Entry], lower: int, human_low: int | None, phase: str) -> None:
    if job.progress is not None:
        made = {"makespan": makespan(entries), "lower": lower, "human": human_units(entries)}
        job.progress({**made, "human_lower": human_low, "phase": phase})


def _short(job: Job) -> Callable[[list[Entry]], bool]:
    """A stop at a schedule that compacts to ``job.floor`` (each one reported)."""

    def short(entries: list[Entry]) -> bool:
        entries = compact(job.inst, entries)
        _report(job, entries, job.floor, None, "makespan")
        return makespan(entries) <= job.floor

    return short


def _human_stop(job: Job, opt: int, least: int = 0) -> tuple[int, Callable[[list[Entry]], bool]]:
    """The fewest human units at makespan ``opt`` (at least ``least``) and a stop at a schedule
    with no more."""
    low = max(least, human_lower(job.inst, opt))

    def few(entries: list[Entry]) -> bool:
        _report(job, entries, opt, low, "human")
        return human_units(entries) <= low

    return low, few


def clock(time_limit: float | None) -> Callable[[], float | None]:
    """The time left of ``time_limit`` from now (None: no limit; 0 once a signal waits)."""
    deadline = None if time_limit is None else time.perf_counter() + time_limit
    return lambda: 0.0 if signal_pending() else remaining(deadline)


def _narrowed(job: Job, dom: shaving.Domains) -> tuple[Job, dict[int, tuple[int, int]]]:
    """``job`` with the kinds ``dom`` leaves each unit, and the units' start windows within it."""
    inst = replace(job.inst, durations=dom.durations)
    return replace(job, inst=inst, tail=dom.tails(job.inst, job.tail)), dom.starts()


class _FloorStop:
    """The stop of the makespan's search at the floor; after :data:`shaving.AFTER` :meth:`shave`
    raises the floor while shaving rules it out, and searches the domains left there for
    :data:`DECIDE`, then twice as long each time (the search runs on); ``best``: the schedule known before."""

    def __init__(self, job: Job, left: Callable[[], float | None], best: list[Entry] | None) -> None:
        self.job, self.left, self.best = job, left, best
        self.floor = job.floor
        #: when :meth:`shave` acts next (inf: never), and the time of its next search
        self.next, self.decide = time.perf_counter() + shaving.AFTER, DECIDE
        #: the floor and the domains shaving left there
        self.shaved: tuple[int, shaving.Domains] | None = None

    def __call__(self, entries: list[Entry]) -> bool:
        entries = compact(self.job.inst, entries)
        _report(self.job, entries, self.floor, None, "makespan")
        if self.best is None or makespan(entries) < makespan(self.best):
            self.best = entries
        return makespan(entries) <= self.floor

    def shave(self) -> bool:
        """Shave once the search has run long enough; is the best schedule at the floor?"""
        began = time.perf_counter()
        if began < self.next or self.left() == 0.0:
            return False
        self.next = float("inf")
        inst = self.job.inst
        if self.shaved is None:
            below = self.job.horizon if self.best is None else makespan(self.best)
            self.floor, dom = shaving.least_floor(inst, self.floor, below, self.left)
            if self.best is not None and makespan(self.best) <= self.floor:
                return True
            if dom is None or self.left() == 0.0:
                return False
            self.shaved = self.floor, dom
        job = replace(self.job, floor=self.floor)
        narrow, starts = _narrowed(job, self.shaved[1])
        left = self.left()
        decide = self.decide if left is None else min(self.decide, left)
        sol = _steps_once(narrow, starts, self.floor, self.floor, decide, "makespan", _short(job))
        if sol.entries is not None:
            self.best = compact(inst, sol.entries)
            return True
        if sol.proven:  # no schedule meets the floor
            self.floor, self.shaved = self.floor + divisor(inst), None
        else:  # the search runs on alone as long as this call took
            self.next, self.decide = 2 * time.perf_counter() - began, 2 * self.decide
        return False


def _steps_in_phases(job: Job, windows: dict, stats: dict[str, Any], time_limit: float | None) -> Solution:
    """A fixed tree with a person, in two solves each stopping at its bound: the makespan alone
    from the known schedule down to ``job.floor``, then the human units within it
    (``stats["tie_breakers"]``: ``proven`` or ``time``).  With several kinds of agents, once a
    phase has run :data:`shaving.AFTER`, shaving (:mod:`foon2asp.schedule.shaving`) may raise
    its bound while it runs on (:class:`_FloorStop`, :class:`shaving.HumanStop`)."""
    inst, floor = job.inst, job.floor
    several = len(inst.kinds) > 1
    left = clock(time_limit)
    best = job.known
    horizon = job.horizon if best is None else min(job.horizon, makespan(best))
    proven = horizon <= floor
    shaved: tuple[int, shaving.Domains] | None = None  # a makespan and its domains
    if not proven:
        if best is not None:
            _report(job, best, floor, None, "makespan")
        short = _FloorStop(job, left, best)
        sol = _steps_once(job, windows, horizon, floor, left(), "makespan", short, short.shave if several else None)
        stats.update(sol.stats)
        best, floor, shaved = short.best, short.floor, short.shaved
        if best is None:
            return replace(sol, stats=stats)
        horizon = makespan(best)
        proven = sol.proven or horizon <= floor
        if not proven:
            stats["tie_breakers"] = "time"
            return Solution(best, False, False, inst.units, stats)
    human = job
    within = job.windows(horizon)
    if shaved is not None and shaved[0] == horizon:
        human, within = _narrowed(job, shaved[1])
        low, few = _human_stop(job, horizon, shaving.human_floor(inst, shaved[1]))
    else:
        low, few = _human_stop(job, horizon)
    if best is not None and human_units(best) <= low:
        stats["tie_breakers"] = "proven"
        return Solution(best, True, False, inst.units, stats)
    if within is None or left() == 0.0:
        stats["tie_breakers"] = "time"
        return Solution(best, True, False, inst.units, stats)
    later = None
    if several and shaved is None:  # shaving may raise the count while the search runs
        fewest = None if best is None else human_units(best)
        later = shaving.HumanStop(inst, horizon, low, left, fewest, lambda e, n: _report(job, e, horizon, n, "human"))
    stop = None if later is None else later.shave
    sol = _steps_once(human, within, horizon, horizon, left(), "human", later or few, stop)
    low = low if later is None else later.low
    if sol.entries is not None and (best is None or human_units(sol.entries) < human_units(best)):
        best = sol.entries
    if best is None:  # nothing within the horizon: it was the floor, and the floor no schedule meets
        return Solution(None, sol.proven, sol.proven, (), stats)
    stats["tie_breakers"] = "proven" if sol.proven or human_units(best) <= low else "time"
    return Solution(best, True, False, inst.units, stats)


def solve(job: Job, encoding: str, time_limit: float | None = None) -> Solution:
    """Solve ``job`` with ``encoding`` (``steps`` or ``dl``)."""
    solvers = {"steps": solve_steps, "dl": solve_dl}
    if encoding not in solvers:
        raise InputError(f"unknown schedule encoding {encoding!r} (have {', '.join(ENCODINGS)})")
    return solvers[encoding](job, time_limit)


def used(atoms: Sequence[clingo.Symbol]) -> tuple[int, ...]:
    """The units of a model's ``use/1`` atoms, sorted."""
    return tuple(sorted(s.arguments[0].number for s in atoms if s.name == "use" and len(s.arguments) == 1))


def solve_dl(job: Job, time_limit: float | None = None) -> Solution:
    """Solve with clingo-dl: descending makespan bounds from ``job.horizon`` to ``job.floor``,
    then the tie-breakers under the optimum (when there are any).  The solution's entries are
    None when the known schedule is the best (proven or not)."""
    try:
        from clingodl import ClingoDLTheory
    except ImportError:
        raise InputError("the dl schedule encoding needs clingo-dl: pip install clingo-dl") from None
    inst, floor = job.inst, job.floor
    theory: Any = ClingoDLTheory()
    windows = {u: (e, e) for u, e in job.head.items() if u in job.tail}
    parts = [
        ("schedule facts", schedule_facts(inst, 1, windows, job.fixed, agents=True, tail=job.tail)),
        ("priorities", _priorities(job.levels)),
    ]
    control = Control(["--opt-mode=ignore", *job.args], theory=theory)
    left = clock(time_limit)
    _grounded(control, job, "schedule_dl", parts)
    stats: dict[str, Any] = {"encoding": "dl"}
    conf: Any = control.ctl.configuration.solve
    conf.models = "1"
    names = {(kind, int(name.rsplit("-", 1)[1])): name for name, kind in inst.agents}
    best: dict[str, Any] = {}
    enough: list[Callable[[list[Entry]], bool]] = []  # the tie-breakers' stop, once set

    def on_model(model: clingo.Model) -> bool:
        values = {str(sym): int(val) for sym, val in theory.assignment(model.thread_id)}
        zero = values.get("0", 0)
        best["atoms"] = model.symbols(shown=True)
        best["entries"] = entries = []
        for a in best["atoms"]:
            if a.name == "on" and len(a.arguments) == 3:
                u, kind, i = a.arguments[0].number, a.arguments[1].string, a.arguments[2].number
                s = values.get(f"s({u})", zero) - zero
                entries.append(Entry(u, names[(kind, i)], s, s + inst.durations[u][kind]))
        return not (enough and enough[0](entries))

    grounded: list[int] = []

    def switch(b: int) -> None:
        """Ground bound(b) once; switch it on, every other bound off."""
        if b not in grounded:
            control.ground([("bound", [clingo.Number(b)])])
            grounded.append(b)
        control.assign({clingo.Function("bounded", [clingo.Number(a)]): a == b for a in grounded})

    opt, step, proven = job.horizon, divisor(inst), True
    while opt - step >= floor:
        switch(opt - step)
        before = best.get("entries")
        if not control.solve(on_model, left()).finished:
            proven = False
            break
        if best.get("entries") is before:  # no schedule under this bound
            break
        if job.fixed:  # compacted, a schedule may be shorter still: the next bound is below that
            best["entries"] = compact(inst, best["entries"])
        opt = makespan(best["entries"])
        _report(job, best["entries"], floor, None, "makespan")
    if proven and job.breakers and (job.ties or "entries" in best):
        # a fixed tree stops at the fewest human units a person must do
        low = None
        if job.fixed:
            low, few = _human_stop(job, opt)
            enough.append(few)

        def met() -> bool:
            return low is not None and "entries" in best and human_units(best["entries"]) <= low

        if met():
            stats["tie_breakers"] = "proven"
        else:
            switch(opt)
            conf.opt_mode, conf.models = "opt", "0"
            finished = control.solve(on_model, left()).finished
            stats["tie_breakers"] = "proven" if finished or met() else "time"
    stats.update(control.stats())
    if "entries" not in best:  # unsatisfiable, or the known schedule (of makespan horizon) is optimal, or no time
        return Solution(None, proven, False, (), stats)
    units = used(best["atoms"]) if not job.fixed else inst.units
    return Solution(best["entries"], proven, False, units, stats)
