"""Lower bounds on the makespan and the list-scheduling baseline of an instance
(:class:`foon2asp.schedule.model.Instance`; times in milliseconds).

* chain: the longest chain of minimum durations (each unit at its least duration over the
  kinds that can do it; a unit waits for the first maker of each object it needs);
* work: the total minimum work over the number of agents, rounded up;
* energy: energetic reasoning over time windows (:func:`energy_bound`), at least both.

The baseline is list scheduling, longest remaining chain first (:func:`list_schedule`).
"""

from __future__ import annotations

import itertools
import math
import random
from collections.abc import Iterable
from dataclasses import dataclass

from foon2asp.schedule.model import Entry, Instance, divisor, earliest, makespan, tails
from foon2asp.schedule.spec import HUMAN


@dataclass(frozen=True)
class Bounds:
    """Lower bounds on the makespan (milliseconds)."""

    #: the longest chain of minimum durations
    chain: int
    #: total minimum work over the number of agents, rounded up
    work: int
    #: energetic reasoning over windows (:func:`energy_bound`); at least the other two
    energy: int = 0

    @property
    def lower(self) -> int:
        return max(self.chain, self.work, self.energy)


def _window_length(c: list[int], m: int) -> float:
    """The least L > 0 with sum(min(c_i, L)) <= m L: the shortest window that can hold parts
    of length c_i on m agents (0 when m >= len(c))."""
    c = sorted(x for x in c if x > 0)
    n = len(c)
    prefix = 0
    for j in range(n + 1):  # L in [c[j-1], c[j]): n - j parts longer than L
        slope = m - (n - j)
        low = c[j - 1] if j else 0
        high = c[j] if j < n else math.inf
        if slope > 0:
            root = max(low, prefix / slope)
            if root < high or j == n:
                return root
        if j < n:
            prefix += c[j]
    return math.inf  # pragma: no cover - slope is m > 0 at j == n


def energy_bound(inst: Instance, start: dict[int, int], tail: dict[int, int], floor: int, step: int) -> int:
    """Energetic reasoning: in a schedule of makespan C, unit u (minimum duration d, earliest
    start r, at least q from its start to the end) runs at least ``min(d, r + d - a, q - b)``
    within ``[a, C - b]``, and those parts fit on the m agents only if that window is at least
    :func:`_window_length` long; so no C strictly between a + b and a + b + that length is
    possible.  The bound is the least C >= ``floor``, a multiple of ``step`` (every makespan
    of a left-justified schedule is a sum of durations), outside all those gaps, for a over
    the heads and b over the tails of the units."""
    d = {u: inst.min_duration(u) for u in inst.units}
    return _clear(_gaps(inst.units, d, start, tail, len(inst.agents)), floor, step)


def pools(inst: Instance) -> list[tuple[list[int], dict[int, int], int]]:
    """Sets of units that share fewer servers than the agents: ``(units, durations, servers)``
    for each set of kinds but all (the units only those kinds can do, each at its least
    duration among them, on their agents) and for each resource (the units using it, on its
    capacity)."""
    kinds = sorted(inst.kinds)
    out = []
    for r in range(1, len(kinds)):
        for chosen in itertools.combinations(kinds, r):
            mine = set(chosen)
            units = [u for u in inst.units if inst.durations[u] and set(inst.durations[u]) <= mine]
            if units:
                d = {u: min(inst.durations[u][k] for k in inst.durations[u] if k in mine) for u in units}
                out.append((units, d, sum(inst.kinds[k] for k in chosen)))
    for label, capacity in sorted(inst.capacity.items()):
        units = [u for u in inst.units if label in inst.uses[u]]
        if units and capacity < len(inst.agents):
            out.append((units, {u: inst.min_duration(u) for u in units}, capacity))
    return out


def _gaps(
    units: Iterable[int], d: dict[int, int], start: dict[int, int], tail: dict[int, int], m: int
) -> list[tuple[int, float]]:
    """The makespans energetic reasoning rules out for ``units`` (durations ``d``) on ``m``
    servers: open intervals (a + b, a + b + window length), as in :func:`energy_bound`."""
    units = list(units)
    gaps = []
    for a in sorted({start[u] for u in units}):
        for b in sorted({tail[u] - d[u] for u in units}):
            length = _window_length([min(d[u], start[u] + d[u] - a, tail[u] - b) for u in units], m)
            if length > 0:
                gaps.append((a + b, a + b + length))
    return gaps


def _clear(gaps: list[tuple[int, float]], floor: int, step: int) -> int:
    """The least multiple of ``step`` at least ``floor`` in none of the open intervals ``gaps``."""
    best = -(-floor // step) * step
    moved = True
    while moved:
        moved = False
        for low, high in gaps:
            if low < best < high:
                best = math.ceil(high / step) * step
                moved = True
    return best


def bounds(inst: Instance) -> Bounds:
    """The chain, work and energy bounds (each unit at its minimum duration over the kinds that
    can do it); the energy bound also counts each pool of units sharing fewer servers
    (:func:`pools`: the units only some kinds can do, the units using a resource)."""
    start = earliest(inst)
    if len(start) < len(inst.units):
        raise ValueError("some unit never becomes ready")
    chain = max((start[u] + inst.min_duration(u) for u in inst.units), default=0)
    work = -(-sum(inst.min_duration(u) for u in inst.units) // len(inst.agents))
    tail = tails(inst)
    d = {u: inst.min_duration(u) for u in inst.units}
    gaps = _gaps(inst.units, d, start, tail, len(inst.agents))
    floor = max(chain, work)
    for units, pd, servers in pools(inst):
        gaps += _gaps(units, pd, start, tail, servers)
        floor = max(floor, -(-sum(pd.values()) // servers))
    return Bounds(chain, work, _clear(gaps, floor, divisor(inst)))


#: randomised list-scheduling runs tried before the solver (BENCHMARKS.md, "Schedules")
TRIES = 48


def perturbed_schedule(inst: Instance, target: int, tries: int = TRIES, seed: int = 0) -> list[Entry]:
    """The shortest of :func:`list_schedule` under ``tries`` seeded random perturbations (up to
    30 %) of its longest-remaining-chain priorities, stopping at one that reaches ``target``
    (a lower bound); the first run is the unperturbed baseline.  The same answer every time."""
    base = tails(inst)
    rng = random.Random(seed)
    best = list_schedule(inst)
    for _ in range(tries):
        if makespan(best) <= target:
            break
        noisy = {u: base[u] * (1 + rng.uniform(-0.3, 0.3)) for u in inst.units}
        run = list_schedule(inst, noisy)
        if makespan(run) < makespan(best):
            best = run
    return best


def list_schedule(inst: Instance, prio: dict[int, float] | None = None) -> list[Entry]:
    """List scheduling, longest remaining chain first (:func:`tails`; or by ``prio``, highest
    first): whenever an agent is free, the ready unit with the longest chain starts on the
    free agent that can do it soonest (shortest duration, then not a person, then the first
    agent), if its resources allow; nobody waits while a unit it could do is ready (a
    non-delay schedule)."""
    order: dict[int, float] = dict(tails(inst)) if prio is None else prio
    waiting = {u: {o for o, _ in inst.needs[u]} for u in inst.units}
    users: dict[int, list[tuple[int, int]]] = {}
    for v in inst.units:
        for o, ms in inst.needs[v]:
            for m in ms:
                users.setdefault(m, []).append((v, o))
    ready = {u for u in inst.units if not waiting[u]}
    free = {name: True for name, _ in inst.agents}
    in_use = dict.fromkeys(inst.capacity, 0)
    running: list[Entry] = []
    out: list[Entry] = []
    t = 0
    while len(out) < len(inst.units) or running:
        for e in [e for e in running if e.end <= t]:
            running.remove(e)
            free[e.agent] = True
            for r in inst.uses[e.unit]:
                in_use[r] -= 1
            for v, o in users.get(e.unit, ()):
                if o in waiting[v]:
                    waiting[v].discard(o)
                    if not waiting[v]:
                        ready.add(v)
        for u in sorted(ready, key=lambda u: (-order[u], u)):
            if any(in_use[r] >= inst.capacity[r] for r in inst.uses[u]):
                continue
            choice = [
                (d, kind == HUMAN, k, name)
                for k, (name, kind) in enumerate(inst.agents)
                if free[name] and (d := inst.durations[u].get(kind)) is not None
            ]
            if not choice:
                continue
            d, _, _, name = min(choice)
            free[name] = False
            for r in inst.uses[u]:
                in_use[r] += 1
            ready.discard(u)
            entry = Entry(u, name, t, t + d)
            running.append(entry)
            out.append(entry)
        if any(e.end <= t for e in running):
            continue  # units of duration 0 end at once
        if not running:
            if len(out) < len(inst.units):
                raise ValueError("list scheduling is stuck: a unit no agent can do, or one never ready")
            break
        t = min(e.end for e in running)
    return out
