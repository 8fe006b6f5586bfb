"""Lower bounds on the makespan and the list-scheduling baseline of an instance
(:class:`foon2asp.schedule.model.Instance`; times in milliseconds).

* chain: the longest chain of minimum durations (each unit at its least duration over the
  kinds that can do it; a unit waits for the first maker of each object it needs);
* work: the total minimum work over the number of agents, rounded up;
* energy: energetic reasoning over time windows (:func:`energy_over`), at least both, also
  over the pools of units that share fewer servers (:func:`pools`).

The baseline is list scheduling, longest remaining chain first (:func:`list_schedule`).
"""

from __future__ import annotations

import itertools
import math
import random
from dataclasses import dataclass

import numpy as np

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


def energy_bound(inst: Instance, start: dict[int, int], tail: dict[int, int], floor: int, step: int) -> int:
    """Energetic reasoning over every unit of ``inst`` on its agents (:func:`energy_over`)."""
    d = {u: inst.min_duration(u) for u in inst.units}
    return energy_over([[u] for u in inst.units], d, start, tail, len(inst.agents), floor, step)


def energy_over(
    parts: list[list[int]],
    d: dict[int, int],
    start: dict[int, int],
    tail: dict[int, int],
    servers: int,
    floor: int,
    step: int,
    limit: int | None = None,
) -> int:
    """Energetic reasoning: in a schedule of makespan C, unit u (duration ``d[u]``, earliest
    start r, at least q from its start to the end) runs at least ``min(d, r + d - a, q - b)``
    within ``[a, C - b]``; a part (a list of units of which one runs; a unit alone, or the
    possible makers of an object) at least the least of its units.  Those parts fit on the
    ``servers`` only if that window is at least :func:`window_lengths` long; so no C strictly
    between a + b and a + b + that length is possible.  The bound is the least C >= ``floor``,
    a multiple of ``step`` (every makespan of a left-justified schedule is a sum of
    durations), outside all those gaps, for a over the heads and b over the tails of the
    units; windows with a + b at ``limit`` or later are not looked at (the bound is then at
    most what they would give, still a bound)."""
    return _clear([_gaps(parts, d, start, tail, servers, limit)], floor, step)


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


def window_lengths(c: np.ndarray, m: int) -> np.ndarray:
    """Per row of ``c`` (parts of length c_i), the least L > 0 with sum(min(c_i, L)) <= m L:
    the shortest window that holds the parts on m servers (0 when they need no window).  With
    the c_i sorted, L lies in [c_(j-1), c_j) for the first j where prefix_j / (m - (n - j))
    does (prefix_j: the sum of the j shortest)."""
    rows, n = c.shape
    c = np.sort(c, axis=1)
    prefix = np.concatenate([np.zeros((rows, 1)), np.cumsum(c, axis=1)], axis=1)
    j = np.arange(n + 1)
    slope = m - (n - j)
    low = np.concatenate([np.zeros((rows, 1)), c], axis=1)
    high = np.concatenate([c, np.full((rows, 1), np.inf)], axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        root = np.where(slope > 0, np.maximum(low, prefix / np.where(slope > 0, slope, 1)), np.inf)
    valid = (slope > 0) & ((root < high) | (j == n))
    first = np.argmax(valid, axis=1)
    return root[np.arange(rows), first]


def _gaps(
    parts: list[list[int]],
    d: dict[int, int],
    start: dict[int, int],
    tail: dict[int, int],
    servers: int,
    limit: int | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The makespans :func:`energy_over` rules out: open intervals (lows, highs)."""
    order = [u for g in parts for u in g]
    if not order:
        return np.zeros(0), np.zeros(0)
    dur = np.array([d[u] for u in order], dtype=np.int64)
    s = np.array([start[u] for u in order], dtype=np.int64)
    t = np.array([tail[u] for u in order], dtype=np.int64)
    cuts = np.cumsum([0] + [len(g) for g in parts[:-1]])
    after = np.unique(t - dur)
    lows: list[np.ndarray] = [np.zeros(0)]
    highs: list[np.ndarray] = [np.zeros(0)]
    for a in np.unique(s):
        b = after if limit is None else after[a + after < limit]
        if not len(b):
            continue
        part = np.maximum(np.minimum(np.minimum(dur, s + dur - a)[None, :], t[None, :] - b[:, None]), 0)
        length = window_lengths(np.minimum.reduceat(part, cuts, axis=1).astype(float), servers)
        keep = length > 0
        lows.append(a + b[keep])
        highs.append(a + b[keep] + length[keep])
    return np.concatenate(lows), np.concatenate(highs)


def _clear(gaps: list[tuple[np.ndarray, np.ndarray]], floor: int, step: int) -> int:
    """The least multiple of ``step`` at least ``floor`` in none of the open intervals ``gaps``."""
    low = np.concatenate([g[0] for g in gaps])
    high = np.concatenate([g[1] for g in gaps])
    best = -(-floor // step) * step
    while True:
        inside = (low < best) & (best < high)
        if not inside.any():
            return best
        best = math.ceil(float(high[inside].max()) / step) * step


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
    gaps = [_gaps([[u] for u in inst.units], d, start, tail, len(inst.agents))]
    floor = max(chain, work)
    for units, pd, servers in pools(inst):
        gaps.append(_gaps([[u] for u in units], pd, start, tail, servers))
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
