"""Ingredient substitutes: which kitchen items may stand in for a needed object.

A substitutes file (docs/matching.md) is JSON or ``label: substitute, other=COST`` lines; an
object that is not a kitchen item is available when the kitchen holds it with its label, or
one ingredient, replaced by a substitute (:func:`candidates`).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject, norm
from foon2asp.foon.problem import Problem
from foon2asp.foon.reading import check_text, content_lines, read_text
from foon2asp.foon.reading import loads as safe_loads

#: the cost of a substitute given without ``=COST``
DEFAULT_COST = 1

#: characters that end a line (a label holding one is refused)
LINE_BREAKS = frozenset("\n\r\v\f\x1c\x1d\x1e\x85\u2028\u2029")


@dataclass(frozen=True, order=True)
class Substitute:
    """``used`` may stand in for ``needed`` (normalised labels) at ``cost``."""

    needed: str
    used: str
    cost: int = DEFAULT_COST


@dataclass(frozen=True, order=True)
class StandIn:
    """The object ``needed`` (an object id, not a kitchen item) is available as the kitchen item ``used``."""

    needed: int
    used: FoonObject
    cost: int


def _cost(text: str, path: str, line: int | None) -> int:
    text = text.strip()
    if not text.isdecimal() or int(text) < 1 or len(text) > 9:
        raise InputError(f"a substitute's cost must be a positive integer, not {text!r}", path, line)
    return int(text)


def _add(
    out: dict[tuple[str, str], Substitute], needed: str, used: str, cost: int, path: str, line: int | None
) -> None:
    for text in (needed, used):
        if any(c in LINE_BREAKS for c in text):
            raise InputError(f"a label cannot hold a line break: {text!r}", path, line)
    needed, used = norm(needed), norm(used)
    if not needed or not used:
        raise InputError("a substitute needs a label on both sides", path, line)
    if needed == used:
        raise InputError(f"{needed!r} cannot be its own substitute", path, line)
    if (needed, used) in out:
        raise InputError(f"{used!r} is listed twice as a substitute for {needed!r}", path, line)
    out[(needed, used)] = Substitute(needed, used, cost)


def _from_json(value: object, path: str) -> dict[tuple[str, str], Substitute]:
    if not isinstance(value, dict):
        raise InputError('expected a JSON object {"label": ["substitute", ...], ...}', path)
    out: dict[tuple[str, str], Substitute] = {}
    for needed, subs in value.items():
        if isinstance(subs, list) and all(isinstance(s, str) for s in subs):
            pairs: list[tuple[str, object]] = [(s, DEFAULT_COST) for s in subs]
        elif isinstance(subs, dict):
            pairs = list(subs.items())
        else:
            raise InputError(f"the substitutes of {needed!r} must be a list of labels or an object label -> cost", path)
        for used, cost in pairs:
            if isinstance(cost, bool) or not isinstance(cost, int) or cost < 1:
                raise InputError(f"the cost of {used!r} for {needed!r} must be a positive integer", path)
            _add(out, needed, used, cost, path, None)
    return out


def _from_lines(text: str, path: str) -> dict[tuple[str, str], Substitute]:
    out: dict[tuple[str, str], Substitute] = {}
    for lineno, line in content_lines(text):
        body = line.strip()
        needed, colon, rest = body.partition(":")
        if not colon:
            raise InputError(f"expected 'label: substitute, ...', got {body[:60]!r}", path, lineno)
        if not rest.strip():
            raise InputError(f"no substitutes listed for {needed.strip()!r}", path, lineno)
        for item in rest.split(","):
            used, eq, cost = item.rpartition("=")
            if not eq:
                used, cost = cost, ""
            _add(out, needed, used, _cost(cost, path, lineno) if eq else DEFAULT_COST, path, lineno)
    return out


def parse_substitutes(text: str, path: str = "<substitutes>") -> tuple[Substitute, ...]:
    """The substitutes of a file's text: JSON when it starts with ``{`` or ``[``, else lines."""
    check_text(text, path)
    if text.lstrip()[:1] in ("{", "["):
        table = _from_json(safe_loads(text, path, checked=True), path)
    else:
        table = _from_lines(text, path)
    return tuple(table.values())


def read_substitutes(path: str | Path) -> tuple[Substitute, ...]:
    """The substitutes file ``path`` (see the module docstring)."""
    return parse_substitutes(read_text(path, "substitutes"), str(path))


def by_needed(substitutes: Iterable[Substitute]) -> dict[str, list[Substitute]]:
    """The substitutes of each needed label, in order."""
    table: dict[str, list[Substitute]] = {}
    for s in substitutes:
        table.setdefault(s.needed, []).append(s)
    return table


def stand_ins(obj: FoonObject, table: dict[str, list[Substitute]]) -> list[tuple[FoonObject, int]]:
    """The objects that may stand in for ``obj`` with their costs: ``obj`` with its label,
    or one of its ingredients, replaced by a substitute of ``table`` (:func:`by_needed`)."""
    out: list[tuple[FoonObject, int]] = []
    for s in table.get(obj.label, ()):
        out.append((FoonObject(s.used, obj.states, obj.ingredients, obj.container), s.cost))
    for ingredient in obj.ingredients:
        for s in table.get(ingredient, ()):
            rest = {i for i in obj.ingredients if i != ingredient} | {s.used}
            out.append((FoonObject(obj.label, obj.states, tuple(sorted(rest)), obj.container), s.cost))
    return out


def _stood_in_for(used: FoonObject, by_used: dict[str, list[Substitute]]) -> list[FoonObject]:
    """The objects the kitchen item ``used`` may stand in for: a superset of the inverse of
    :func:`stand_ins` (docs/proofs/preparation.md, "Substitutes")."""
    out = [FoonObject(s.needed, used.states, used.ingredients, used.container) for s in by_used.get(used.label, ())]
    for ingredient in used.ingredients:
        for s in by_used.get(ingredient, ()):
            rest = set(used.ingredients)
            for ingredients in (rest - {ingredient} | {s.needed}, rest | {s.needed}):
                out.append(FoonObject(used.label, used.states, tuple(sorted(ingredients)), used.container))
    return out


def candidates(problem: Problem, substitutes: Iterable[Substitute]) -> list[StandIn]:
    """Every (needed object, kitchen item, cost) where the kitchen item may stand in for
    an object of the FOON that is not a kitchen item; by object id, then substitute order.
    A kitchen item reached by two substitutions of one object keeps the cheaper."""
    table = by_needed(substitutes)
    if not table:
        return []
    by_used: dict[str, list[Substitute]] = {}
    for subs in table.values():
        for sub in subs:
            by_used.setdefault(sub.used, []).append(sub)
    kitchen = set(problem.kitchen_items)
    ids = problem.foon.object_ids
    needed: set[int] = set()
    for item in kitchen:
        if item.label in by_used or any(i in by_used for i in item.ingredients):
            needed.update(ids[o] for o in _stood_in_for(item, by_used) if o in ids and o not in kitchen)
    out: list[StandIn] = []
    for oid in sorted(needed):
        best: dict[FoonObject, int] = {}
        for used, cost in stand_ins(problem.objects[oid], table):
            if used in kitchen and cost < best.get(used, cost + 1):
                best[used] = cost
        out += [StandIn(oid, used, cost) for used, cost in best.items()]
    return out


def with_substitutes(problem: Problem, substitutes: Iterable[Substitute]) -> Problem:
    """``problem`` whose viability (the least fixpoint, viable units, the units a tree may
    use) counts every object a substitute can stand in for as available; ``problem``
    itself when that is already so (or there are no substitutes)."""
    needed = frozenset(c.needed for c in candidates(problem, substitutes))
    if needed == problem.substitutable:
        return problem
    return problem.with_substitutable(needed)


def judged_on(problem: Problem, substitutes: Iterable[Substitute], goals: Iterable[int] = ()) -> Problem:
    """The problem a tree that may rely on ``substitutes`` is judged on by the independent
    validator: every object a substitute can stand in for, but ``goals``, is a kitchen item
    (``problem`` itself without substitutes)."""
    substitutes = tuple(substitutes)
    if not substitutes:
        return problem
    skip = set(goals)
    return substituted_kitchen(problem, [c.needed for c in candidates(problem, substitutes) if c.needed not in skip])


def substituted_kitchen(problem: Problem, used: Iterable[int | FoonObject]) -> Problem:
    """``problem`` with the objects ``used`` substitutions stand in for (ids or objects) as
    kitchen items, for the independent validator."""
    extra = [problem.objects[o] if isinstance(o, int) else o for o in used]
    ids = problem.foon.object_ids
    view = problem.with_kitchen(problem.kitchen | frozenset(ids[o] for o in extra if o in ids))
    view.kitchen_items = list(dict.fromkeys([*problem.kitchen_items, *extra]))
    return view
