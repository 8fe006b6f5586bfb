"""An independent checker of schedules in the JSON shape of :mod:`foon2asp.schedule.result`.

It uses neither clingo nor :mod:`foon2asp.schedule.instances`: units are matched against the FOON
and the schedule is replayed in time; the checks run in the order of docs/schedules.md.
"""

from __future__ import annotations

from collections.abc import Mapping
from decimal import Decimal

from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.problem import Problem, required_flags
from foon2asp.schedule.spec import TICKS, ScheduleSpec, kind_of
from foon2asp.tree.validate import validate


def _object(doc: object) -> FoonObject:
    if not isinstance(doc, Mapping) or not isinstance(doc.get("label"), str):
        raise ValueError("an object needs a label")
    return FoonObject.make(doc["label"], doc.get("states") or (), doc.get("ingredients") or (), doc.get("container"))


def _unit(doc: object) -> Unit:
    if not isinstance(doc, Mapping) or not isinstance(doc.get("motion"), str):
        raise ValueError("a unit needs a motion")
    ins, outs = doc.get("inputs"), doc.get("outputs")
    if not isinstance(ins, list) or not isinstance(outs, list):
        raise ValueError("a unit needs lists of inputs and outputs")
    return Unit(doc["motion"], tuple(_object(o) for o in ins), tuple(_object(o) for o in outs))


def _ticks(value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"{value!r} is not a number of seconds")
    exact = Decimal(repr(value)) * TICKS
    if not exact.is_finite() or exact != exact.to_integral_value():
        raise ValueError(f"{value!r} is not exact to 0.001 s")
    return int(exact)


def _rows(problem: Problem, doc: Mapping) -> list[tuple[int, str, int, int]]:
    """(FOON unit id, agent, start, end) of each entry; ValueError on a malformed one."""
    ids = {u.key(): k for k, u in enumerate(problem.units)}
    agents = doc.get("agents")
    if not isinstance(agents, list) or not all(isinstance(a, str) for a in agents):
        raise ValueError("'agents' must be a list of agent names")
    entries = doc.get("schedule")
    if not isinstance(entries, list):
        raise ValueError("'schedule' must be a list")
    rows = []
    for k, e in enumerate(entries, 1):
        if not isinstance(e, Mapping):
            raise ValueError(f"entry {k} is not an object")
        try:
            unit = _unit(e.get("unit"))
            start, end = _ticks(e.get("start")), _ticks(e.get("end"))
        except ValueError as exc:
            raise ValueError(f"entry {k}: {exc}") from None
        uid = ids.get(unit.key())
        if uid is None:
            raise ValueError(f"entry {k}: unit {unit.motion!r} is not in the FOON")
        if e.get("agent") not in agents:
            raise ValueError(f"entry {k}: agent {e.get('agent')!r} is not in 'agents'")
        if not 0 <= start <= end:
            raise ValueError(f"entry {k}: start {e.get('start')} and end {e.get('end')} are not 0 <= start <= end")
        rows.append((uid, e["agent"], start, end))
    seen: set[int] = set()
    for k, (u, *_) in enumerate(rows, 1):
        if u in seen:
            raise ValueError(f"entry {k}: unit {u} ({problem.units[u].motion}) is scheduled twice")
        seen.add(u)
    return rows


def _goals(problem: Problem, doc: Mapping) -> list[int]:
    given = doc.get("goals") if "goals" in doc else [doc.get("goal")]
    if not isinstance(given, list):
        raise ValueError("'goals' must be a list")
    out = []
    for g in given:
        obj = _object(g)
        if obj not in problem.foon.object_ids:
            raise ValueError(f"goal {obj} is not an object of the FOON")
        out.append(problem.foon.object_ids[obj])
    return out


def _precedence(problem: Problem, rows: list[tuple[int, str, int, int]]) -> str | None:
    """Replay ``rows`` in time: each unit, when it starts, must have every required input that is
    not a kitchen item made by a unit that fired before it and ended by then."""
    kitchen = set(problem.kitchen_items)
    made: dict[FoonObject, int] = {}  # object -> earliest end of a unit that made it

    def missing(u: int, start: int) -> FoonObject | None:
        unit = problem.units[u]
        flags = required_flags(unit, problem.utensils, problem.utensil_rule)
        return next(
            (o for o, f in zip(unit.inputs, flags) if f and o not in kitchen and made.get(o, start + 1) > start), None
        )

    pending = sorted(rows, key=lambda r: (r[2], r[3], r[0]))
    while pending:
        k = next((k for k, (u, _, start, _) in enumerate(pending) if missing(u, start) is None), None)
        if k is None:
            u, _, start, _ = pending[0]
            return f"unit {u} ({problem.units[u].motion}) starts at {_fmt(start)} s before {missing(u, start)} is made"
        u, _, _, end = pending.pop(k)
        for o in problem.units[u].outputs:
            if not o.is_bare():
                made[o] = min(made.get(o, end), end)
    return None


def _fmt(ticks: int) -> str:
    return f"{ticks / TICKS:g}"


def check_schedule(problem: Problem, doc: Mapping, spec: ScheduleSpec) -> str | None:
    """The first violation of the schedule ``doc`` (a :meth:`ScheduleResult.to_dict`), None if valid."""
    if doc.get("status") not in ("optimal", "feasible"):
        return f"status {doc.get('status')!r} holds no schedule"
    try:
        rows = _rows(problem, doc)
        goals = _goals(problem, doc)
    except ValueError as exc:
        return str(exc)
    names = [name for name, _ in spec.agent_list()]
    stranger = next((a for a in doc["agents"] if a not in names), None)
    if stranger is not None:
        return f"agent {stranger!r} is not one of the agents {', '.join(names)}"
    units = [u for u, *_ in rows]
    for g in goals:
        v = validate(problem, g, units)
        if not v.valid:
            return f"the tree is not valid: {v.problem}"
    for u, agent, start, end in rows:
        unit = problem.units[u]
        kind = kind_of(agent)
        if not spec.can(kind, unit.motion):
            return f"unit {u} ({unit.motion}): agent {agent} cannot do {unit.motion!r}"
        want = spec.durations.of(kind, unit.motion)
        if end - start != want:
            return f"unit {u} ({unit.motion}) on {agent} takes {_fmt(end - start)} s, not {_fmt(want)} s"
    late = _precedence(problem, rows)
    if late:
        return late
    for agent in doc["agents"]:
        busy: tuple[int, int] | None = None  # (end, unit) of the latest-ending unit so far
        for u, _, start, end in sorted((r for r in rows if r[1] == agent and r[2] < r[3]), key=lambda r: r[2]):
            if busy is not None and start < busy[0]:
                return f"agent {agent} does units {busy[1]} and {u} at once (at {_fmt(start)} s)"
            if busy is None or end > busy[0]:
                busy = (end, u)
    for label, cap in spec.resources.items():
        events = []
        for u, _, start, end in rows:
            if start < end and any(o.label == label for o in problem.units[u].inputs):
                events += [(start, 1, u), (end, -1, u)]
        running = 0
        for t, delta, u in sorted(events, key=lambda e: (e[0], e[1])):
            running += delta
            if running > cap:
                return f"{running} units using {label!r} (capacity {cap}) run at {_fmt(t)} s, unit {u} among them"
    latest = max((end for *_, end in rows), default=0)
    if "makespan" in doc and doc["makespan"] is not None and _ticks(doc["makespan"]) != latest:
        return f"makespan {doc['makespan']} is not the latest end {_fmt(latest)}"
    return None
