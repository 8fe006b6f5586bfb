"""The scheduling problem of a set of units: the instance, precedence, compaction, agents dealt.

An :class:`Instance` holds the units of a tree (or every candidate unit of a goal) with their
durations per kind of agent, the objects they need and the resources they use; an
:class:`Entry` places one unit on one agent.  Times are in milliseconds.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace

from foon2asp.foon.problem import Problem
from foon2asp.schedule.spec import HUMAN, ScheduleSpec, kind_of


@dataclass(frozen=True)
class Entry:
    """Unit ``unit`` (a FOON unit id) done by ``agent`` over ``[start, end)`` (milliseconds)."""

    unit: int
    agent: str
    start: int
    end: int


@dataclass
class Instance:
    """Durations, needs and resources of a set of units, with the agents."""

    units: tuple[int, ...]
    #: unit -> kind -> milliseconds, for the kinds that can do it (none: nobody can)
    durations: dict[int, dict[str, int]]
    #: unit -> (object, its makers in the set) for each required input that is not a kitchen item
    needs: dict[int, tuple[tuple[int, tuple[int, ...]], ...]]
    #: unit -> the resource labels with a capacity its inputs use
    uses: dict[int, tuple[str, ...]]
    #: (name, kind) of every agent
    agents: list[tuple[str, str]]
    #: kind -> number of agents
    kinds: dict[str, int]
    #: resource label -> capacity
    capacity: dict[str, int] = field(default_factory=dict)

    @property
    def preds(self) -> dict[int, tuple[int, ...]]:
        """unit -> the units that must end before it starts: the sole maker of a needed object,
        or its only maker that does not itself wait for the unit (docs/proofs/schedules.md)."""
        preds = {u: {ms[0] for _, ms in self.needs[u] if len(ms) == 1} for u in self.units}
        several = [(u, ms) for u in self.units for _, ms in self.needs[u] if len(ms) > 1]
        changed = bool(several)
        while changed:
            changed = False
            succs = successors(preds)
            for v, ms in several:
                after = _reach(succs, v)
                left = [m for m in ms if m != v and m not in after]
                if len(left) == 1 and left[0] not in preds[v]:
                    preds[v].add(left[0])
                    changed = True
        return {u: tuple(sorted(ps)) for u, ps in preds.items()}

    def min_duration(self, u: int) -> int:
        return min(self.durations[u].values())

    def restrict(self, units: Iterable[int]) -> Instance:
        """The instance of ``units`` alone (a tree chosen among the candidates)."""
        keep = tuple(sorted(set(units)))
        mine = set(keep)
        needs = {u: tuple((o, tuple(m for m in ms if m in mine)) for o, ms in self.needs[u]) for u in keep}
        return replace(self, units=keep, durations={u: self.durations[u] for u in keep}, needs=needs)

    def incapable(self) -> list[int]:
        """The units no agent can do."""
        return [u for u in self.units if not self.durations[u]]


def designate(inst: Instance, first: Iterable[tuple[int, int]]) -> Instance:
    """``inst`` with each object of ``first`` ((object, maker) pairs) made, for every unit
    needing it, by that maker only (a unit waits for it whichever other maker ends first)."""
    chosen = dict(first)
    if not chosen:
        return inst
    needs = {u: tuple((o, (chosen[o],) if chosen.get(o) in ms else ms) for o, ms in inst.needs[u]) for u in inst.units}
    return replace(inst, needs=needs)


def successors(preds: Mapping[int, Iterable[int]]) -> dict[int, list[int]]:
    """unit -> the units that list it in ``preds``."""
    out: dict[int, list[int]] = {u: [] for u in preds}
    for v, ps in preds.items():
        for p in ps:
            out[p].append(v)
    return out


def _reach(succs: dict[int, list[int]], start: int) -> set[int]:
    """The units reachable from ``start`` along ``succs`` (not ``start`` itself unless on a cycle)."""
    out: set[int] = set()
    stack = list(succs.get(start, ()))
    while stack:
        x = stack.pop()
        if x not in out:
            out.add(x)
            stack.extend(succs.get(x, ()))
    return out


def instance(problem: Problem, units: Iterable[int], spec: ScheduleSpec) -> Instance:
    """The scheduling instance of ``units`` (FOON unit ids) with the agents of ``spec``."""
    ids = tuple(sorted(set(units)))
    kinds = dict(spec.agents)
    makers: dict[int, list[int]] = {}
    for u in ids:
        for o in problem.products[u]:
            makers.setdefault(o, []).append(u)
    durations, needs, uses = {}, {}, {}
    for u in ids:
        unit = problem.units[u]
        durations[u] = {k: spec.durations.of(k, unit.motion) for k in kinds if spec.can(k, unit.motion)}
        objs = [o for o in problem.required[u] if o not in problem.kitchen]
        needs[u] = tuple((o, tuple(m for m in makers.get(o, ()) if m != u)) for o in objs)
        uses[u] = tuple(sorted({o.label for o in unit.inputs if o.label in spec.resources}))
    used = {r for rs in uses.values() for r in rs}
    capacity = {r: c for r, c in spec.resources.items() if r in used}
    return Instance(ids, durations, needs, uses, spec.agent_list(), kinds, capacity)


def earliest(inst: Instance) -> dict[int, int]:
    """The earliest start of each unit at minimum durations, a unit waiting for the first maker
    of each object it needs (for joint scheduling, over every candidate); units no agent can
    do, or never ready, are left out."""
    users: dict[int, list[int]] = {}
    makes: dict[int, list[int]] = {}
    for u in inst.units:
        for o, ms in inst.needs[u]:
            users.setdefault(o, []).append(u)
            for m in ms:
                makes.setdefault(m, []).append(o)
    waiting = {u: len(inst.needs[u]) for u in inst.units}
    start: dict[int, int] = {}
    made: dict[int, int] = {}
    # (time, 0: unit ready | 1: object made, id), units in order
    queue: list[tuple[int, int, int]] = [(0, 0, u) for u in inst.units if waiting[u] == 0]
    while queue:
        t, what, x = heapq.heappop(queue)
        if what == 0:
            if x in start or not inst.durations[x]:
                continue
            start[x] = t
            for o in dict.fromkeys(makes.get(x, ())):
                if o not in made:
                    heapq.heappush(queue, (t + inst.min_duration(x), 1, o))
        elif x not in made:
            made[x] = t
            for v in users.get(x, ()):
                waiting[v] -= 1
                if waiting[v] == 0:
                    heapq.heappush(queue, (max(made[o] for o, _ in inst.needs[v]), 0, v))
    return start


def joint_tails(inst: Instance, goals: Iterable[int], products: Sequence[tuple[int, ...]]) -> dict[int, int]:
    """For joint scheduling (``inst`` holds every candidate unit): each unit's minimum
    duration plus the shortest chain after it to a unit making a goal, through units that
    need what it makes.  ``products``: unit -> the objects it makes; units that lead to no
    goal are left out."""
    wanted = set(goals)
    queue = [(inst.min_duration(u), u) for u in inst.units if inst.durations[u] and wanted & set(products[u])]
    heapq.heapify(queue)
    out: dict[int, int] = {}
    while queue:
        q, v = heapq.heappop(queue)
        if v in out:
            continue
        out[v] = q
        for m in {m for _, ms in inst.needs[v] for m in ms}:
            if m not in out and inst.durations[m]:
                heapq.heappush(queue, (q + inst.min_duration(m), m))
    return out


def tails(inst: Instance) -> dict[int, int]:
    """Each unit's minimum duration plus the longest chain of minimum durations of the units
    that must wait for it (:attr:`Instance.preds`): a lower bound on the time from its start
    to the end, and the priority of list scheduling."""
    preds = inst.preds
    succs = successors(preds)
    left = {u: len(succs[u]) for u in inst.units}
    stack = [u for u in inst.units if left[u] == 0]
    out: dict[int, int] = {}
    while stack:
        u = stack.pop()
        out[u] = inst.min_duration(u) + max((out[v] for v in succs[u]), default=0)
        for p in preds[u]:
            left[p] -= 1
            if left[p] == 0:
                stack.append(p)
    for u in inst.units:  # on a cycle (an invalid tree): its own duration
        out.setdefault(u, inst.min_duration(u))
    return out


def divisor(inst: Instance) -> int:
    """The greatest common divisor of every duration (1 when all are 0)."""
    return math.gcd(*(d for table in inst.durations.values() for d in table.values())) or 1


def makespan(entries: Iterable[Entry]) -> int:
    return max((e.end for e in entries), default=0)


def sequence(inst: Instance, entries: Iterable[Entry]) -> list[Entry]:
    """``entries`` in an order they can fire in: by start, and among units that start at once
    a maker before the unit that needs what it made (units of duration 0)."""
    pending = sorted(entries, key=lambda e: (e.start, e.end, e.unit))
    out: list[Entry] = []
    ended: dict[int, int] = {}
    while pending:
        pick = 0
        for k, e in enumerate(pending):
            if all(any(ended.get(m, e.start + 1) <= e.start for m in ms) for _, ms in inst.needs[e.unit]):
                pick = k
                break
        e = pending.pop(pick)
        out.append(e)
        ended[e.unit] = e.end
    return out


def partition(entries: list[Entry], slots: int) -> list[list[Entry]] | None:
    """``entries`` (by start) in ``slots`` lanes with no overlap in a lane, greedily (None: more
    than ``slots`` overlap somewhere).  Units of duration 0 go in the first lane, outside its order."""
    lanes: list[list[Entry]] = [[] for _ in range(slots)]
    instant = []
    for e in entries:
        if e.start == e.end:
            instant.append(e)
            continue
        lane = next((lane for lane in lanes if not lane or lane[-1].end <= e.start), None)
        if lane is None:
            return None
        lane.append(e)
    if slots:
        lanes[0] += instant
    return lanes


def assign_agents(inst: Instance, kind_of_unit: dict[int, str], start: dict[int, int]) -> list[Entry]:
    """Entries for units placed by kind (at most N running at once per kind of N agents):
    each kind's intervals dealt to its agents by :func:`partition`."""
    out = []
    for kind, n in inst.kinds.items():
        mine = [
            Entry(u, "", start[u], start[u] + inst.durations[u][kind]) for u, k in kind_of_unit.items() if k == kind
        ]
        lanes = partition(sorted(mine, key=lambda e: (e.start, e.end, e.unit)), n)
        if lanes is None:
            raise ValueError(f"more than {n} units of kind {kind!r} run at once")
        names = [name for name, k in inst.agents if k == kind]
        out += [Entry(e.unit, names[i], e.start, e.end) for i, lane in enumerate(lanes) for e in lane]
    return out


def compact(inst: Instance, entries: list[Entry]) -> list[Entry]:
    """The same assignment and sequences with every unit started as early as they allow (each
    agent's and resource lane's order and each needed object's maker kept); the makespan does
    not grow."""
    seq = sequence(inst, entries)
    before: dict[int, set[int]] = {e.unit: set() for e in seq}
    placed: dict[int, Entry] = {}
    for e in seq:
        for _, ms in inst.needs[e.unit]:
            done = [placed[m] for m in ms if m in placed and placed[m].end <= e.start]
            if done:
                before[e.unit].add(min(done, key=lambda d: (d.end, d.unit)).unit)
        placed[e.unit] = e
    timed = [e for e in seq if e.start < e.end]  # units of duration 0 occupy nobody
    chains = [[e for e in timed if e.agent == name] for name, _ in inst.agents]
    for r, cap in inst.capacity.items():
        chains += partition([e for e in timed if r in inst.uses[e.unit]], cap) or []
    for chain in chains:
        for a, b in zip(chain, chain[1:]):
            before[b.unit].add(a.unit)
    end: dict[int, int] = {}
    out = []
    for e in seq:  # every edge goes forward in this order
        s = max((end[p] for p in before[e.unit] if p in end), default=0)
        end[e.unit] = s + (e.end - e.start)
        out.append(Entry(e.unit, e.agent, s, end[e.unit]))
    return out


def human_units(entries: Iterable[Entry]) -> int:
    return sum(1 for e in entries if kind_of(e.agent) == HUMAN)
