"""The list-scheduling baseline and the schedule a solver starts from (times in milliseconds).

The baseline is list scheduling, longest remaining chain first; a solver starts from the best
of it and of perturbed and earliest-finish list schedules (:func:`known_schedule`).
"""

from __future__ import annotations

import random
from functools import cache

from foon2asp.schedule.instances import Entry, Instance, human_units, makespan, tails
from foon2asp.schedule.lower_bounds import human_lower
from foon2asp.schedule.spec import HUMAN

#: randomised list-scheduling runs tried before the solver (BENCHMARKS.md, "Schedules")
TRIES = 48


def _waiting(inst: Instance) -> tuple[dict[int, set[int]], dict[int, list[tuple[int, int]]], set[int]]:
    """``(waiting, users, ready)``: the objects each unit waits for, the (unit, object) pairs
    each maker supplies, and the units that wait for nothing."""
    waiting = {u: {o for o, _ in inst.needs[u]} for u in inst.units}
    users: dict[int, list[tuple[int, int]]] = {}
    for v in inst.units:
        for o, ms in inst.needs[v]:
            for m in ms:
                users.setdefault(m, []).append((v, o))
    return waiting, users, {u for u in inst.units if not waiting[u]}


def _release(u: int, waiting: dict[int, set[int]], users: dict[int, list[tuple[int, int]]], ready: set[int]) -> None:
    """Unit ``u`` made its objects: the units waiting for nothing more are ready."""
    for v, o in users.get(u, ()):
        if o in waiting[v]:
            waiting[v].discard(o)
            if not waiting[v]:
                ready.add(v)


def list_schedule(inst: Instance, prio: dict[int, float] | None = None) -> list[Entry]:
    """List scheduling, longest remaining chain first (or by ``prio``, highest first): whenever
    an agent is free, the ready unit with the longest chain starts on the free agent that can
    do it soonest, if its resources allow (a non-delay schedule)."""
    order: dict[int, float] = dict(tails(inst)) if prio is None else prio
    waiting, users, ready = _waiting(inst)
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
            _release(e.unit, waiting, users, ready)
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


def _slot(busy: list[tuple[int, int]], using: list[list[tuple[int, int]]], caps: list[int], ready: int, d: int) -> int:
    """The earliest start at ``ready`` or later of ``d`` on an agent busy over ``busy``, with
    each resource (its units' spans ``using``, its capacity ``caps``) not full throughout."""
    if d == 0:
        return ready
    for t in sorted(
        {ready} | {e for _, e in busy if e > ready} | {e for spans in using for _, e in spans if e > ready}
    ):
        if any(s < t + d and t < e for s, e in busy):
            continue
        if all(
            sum(1 for s, e in spans if s <= x < e) < cap
            for spans, cap in zip(using, caps)
            for x in {t} | {s for s, _ in spans if t < s < t + d}
        ):
            return t
    raise AssertionError("a slot after every end exists")  # pragma: no cover


def earliest_finish(inst: Instance, prio: dict[int, float] | None = None) -> list[Entry]:
    """List scheduling by agent choice: the ready unit with the longest remaining chain (or by
    ``prio``) goes into the first gap where it ends first, its resources allowing; it starts
    after the first maker of each object it needs ends."""
    order: dict[int, float] = dict(tails(inst)) if prio is None else prio
    placed: dict[int, Entry] = {}
    busy: dict[str, list[tuple[int, int]]] = {name: [] for name, _ in inst.agents}
    spans: dict[str, list[tuple[int, int]]] = {r: [] for r in inst.capacity}
    waiting, users, ready = _waiting(inst)
    while len(placed) < len(inst.units):
        if not ready:
            raise ValueError("list scheduling is stuck: a unit never ready")
        u = max(ready, key=lambda v: (order[v], -v))
        ready.discard(u)
        at = max((min(placed[m].end for m in ms if m in placed) for _, ms in inst.needs[u]), default=0)
        using = [spans[r] for r in inst.uses[u]]
        caps = [inst.capacity[r] for r in inst.uses[u]]
        choice = []
        for k, (name, kind) in enumerate(inst.agents):
            d = inst.durations[u].get(kind)
            if d is not None:
                t = _slot(busy[name], using, caps, at, d)
                choice.append((t + d, kind == HUMAN, k, name, t))
        if not choice:
            raise ValueError("list scheduling is stuck: a unit no agent can do")
        end, _, _, name, t = min(choice)
        placed[u] = Entry(u, name, t, end)
        if end > t:
            busy[name].append((t, end))
            for spans_r in using:
                spans_r.append((t, end))
        _release(u, waiting, users, ready)
    return list(placed.values())


def known_schedule(
    inst: Instance, target: int, tries: int = TRIES, human: int | None = None
) -> tuple[list[Entry], str]:
    """The best list schedule by makespan, then human units, and what made it: the baseline and,
    under ``tries`` seeded perturbations of its priorities, list and :func:`earliest_finish`
    schedules; it stops at one that reaches ``target`` with the fewest human units there
    (``human``: that count when known, else :func:`human_lower` at ``target``)."""
    base = tails(inst)
    rng = random.Random(0)
    kinds = len(inst.kinds) > 1
    low_human = cache(lambda: human_lower(inst, target) if human is None else human)  # once, when first needed

    def key(found: tuple[list[Entry], str]) -> tuple[int, int]:
        return makespan(found[0]), human_units(found[0])

    def done(entries: list[Entry]) -> bool:
        return makespan(entries) <= target and human_units(entries) <= low_human()

    best = (list_schedule(inst), "baseline")
    if kinds and not done(best[0]):
        best = min(best, (earliest_finish(inst), "earliest-finish list scheduling"), key=key)
    for _ in range(tries):
        if done(best[0]):
            break
        noisy = {u: base[u] * (1 + rng.uniform(-0.3, 0.3)) for u in inst.units}
        best = min(best, (list_schedule(inst, noisy), "a list schedule with perturbed priorities"), key=key)
        if not done(best[0]):
            found = (earliest_finish(inst, noisy), "earliest-finish list scheduling with perturbed priorities")
            best = min(best, found, key=key)
    return best
