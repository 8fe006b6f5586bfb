"""Motion-cost tables: what each motion costs, for the ``cost`` objective.

A table is a JSON object ``{"chop": 0.9, ...}`` or ``motion<TAB>cost`` lines.  Costs are
decimals in [0, :data:`MAX_COST`] exact to :data:`PRECISION`, used by the solver as integers
``cost * SCALE``; a motion the table does not list costs :data:`DEFAULT_COST`.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from decimal import Decimal, InvalidOperation
from pathlib import Path

from foon2asp.errors import InputError
from foon2asp.foon.model import motion_key
from foon2asp.foon.reading import MAX_NUMBER_CHARS, clipped, content_lines, name_and_value, read_text
from foon2asp.foon.reading import loads as safe_loads

#: costs are exact to this step; the solver's integer weight of a cost is cost * SCALE
PRECISION = Decimal("0.01")
SCALE = 100
#: the cost of a motion the table does not list
DEFAULT_COST = Decimal(1)
#: the largest cost accepted (its weight keeps the solver's sums far from overflow)
MAX_COST = Decimal(1000)

#: the precision in words (for help texts and docs)
PRECISION_TEXT = (
    f"costs are exact to {PRECISION} (the solver minimises the sum of cost*{SCALE} as integers); "
    f"a finer value is an error, a motion not in the table costs {DEFAULT_COST}"
)


@dataclass
class MotionCosts:
    """A motion-cost table: motion -> cost (exact decimals), and the file it came from."""

    costs: dict[str, Decimal] = field(default_factory=dict)
    path: str = ""

    def cost(self, motion: str) -> Decimal:
        """The cost of ``motion`` (:data:`DEFAULT_COST` when not listed)."""
        return self.costs.get(motion_key(motion), DEFAULT_COST)

    def weight(self, motion: str) -> int:
        """The solver's integer weight of ``motion``: its cost in hundredths."""
        return scaled(self.cost(motion))


def scaled(cost: Decimal) -> int:
    """``cost * SCALE`` as an integer (``cost`` is a multiple of :data:`PRECISION`)."""
    return int(cost * SCALE)


def unscaled(weight: int) -> Decimal:
    """The cost of an integer weight (a sum of weights: the tree's cost)."""
    return Decimal(weight) / SCALE


def as_number(cost: Decimal) -> int | float:
    """A cost for JSON and text: an integer when whole, else the decimal as a float (2 places at most)."""
    return int(cost) if cost == cost.to_integral_value() else float(cost)


def parse_cost(text: str, path: str, line: int | None, motion: str) -> Decimal:
    """One cost, checked: a decimal >= 0, at most :data:`MAX_COST`, exact to :data:`PRECISION`."""
    shown = clipped(text)
    if len(text) > MAX_NUMBER_CHARS:
        raise InputError(f"cost of {motion!r} is longer than {MAX_NUMBER_CHARS} characters", path, line)
    try:
        value = Decimal(text.strip())
    except InvalidOperation:
        raise InputError(f"cost of {motion!r} is not a number: {shown!r}", path, line) from None
    if not value.is_finite():
        raise InputError(f"cost of {motion!r} is not a finite number: {shown!r}", path, line)
    if value < 0:
        raise InputError(f"cost of {motion!r} is negative: {shown}", path, line)
    if value > MAX_COST:
        raise InputError(f"cost of {motion!r} is {shown}; at most {MAX_COST} is accepted", path, line)
    if value % PRECISION:  # exact: value is at most MAX_COST
        raise InputError(
            f"cost of {motion!r} is {shown}, finer than {PRECISION} (costs are used to two decimals)", path, line
        )
    return abs(value.quantize(PRECISION))  # exact (checked above); -0 -> 0


def _add(
    costs: dict[str, Decimal], where: dict[str, int | None], motion: str, value: Decimal, path: str, line: int
) -> None:
    key = motion_key(motion)
    if not key:
        raise InputError("empty motion in the motion-cost table", path, line)
    if key in costs and costs[key] != value:
        first = f" (line {where[key]})" if where[key] else ""
        raise InputError(f"motion {key!r} is listed twice with different costs{first}", path, line)
    costs.setdefault(key, value)
    where.setdefault(key, line)


def _json_entries(text: str, path: str) -> list[tuple[str, str, int]]:
    """``(motion, number text, line)`` per entry of a flat JSON object, in file order."""
    value = safe_loads(text, path, checked=True)
    if not isinstance(value, dict):
        raise InputError("expected a JSON object {motion: cost, ...} or 'motion<TAB>cost' lines", path, 1)
    dec = json.JSONDecoder(parse_float=str, parse_int=str, parse_constant=str)
    out: list[tuple[str, str, int]] = []
    pos = text.index("{") + 1
    while True:
        while text[pos] in " \t\r\n,":
            pos += 1
        if text[pos] == "}":
            return out
        line = text.count("\n", 0, pos) + 1
        key, pos = dec.raw_decode(text, pos)
        while text[pos] in " \t\r\n:":
            pos += 1
        quoted = text[pos] == '"'
        number, pos = dec.raw_decode(text, pos)
        if quoted or not isinstance(number, str):
            raise InputError(f"cost of {key!r} must be a number, not {json.dumps(number)[:40]}", path, line)
        out.append((key, number, line))


def parse_motion_costs(text: str, path: str = "<string>") -> MotionCosts:
    """A table from its text (a JSON object, or ``motion<TAB>cost`` lines)."""
    costs: dict[str, Decimal] = {}
    where: dict[str, int | None] = {}
    head = text.lstrip()[:1]
    if head == "[":
        raise InputError("expected a JSON object {motion: cost, ...}, not a list", path, 1)
    if head == "{":
        for motion, number, at in _json_entries(text, path):
            _add(costs, where, motion, parse_cost(number, path, at, motion), path, at)
        return MotionCosts(costs, path)
    for lineno, line in content_lines(text):
        parts = name_and_value(line)
        if len(parts) != 2 or not parts[0].strip():
            raise InputError(f"expected 'motion<TAB>cost', got {clipped(line.strip())!r}", path, lineno)
        _add(costs, where, parts[0], parse_cost(parts[1], path, lineno, motion_key(parts[0])), path, lineno)
    return MotionCosts(costs, path)


def read_motion_costs(path: str | Path) -> MotionCosts:
    """The motion-cost table in ``path``."""
    return parse_motion_costs(read_text(path, "motion-cost"), str(path))


def unit_weights(
    table: MotionCosts, motions: list[str] | set[str] | tuple[str, ...]
) -> tuple[dict[str, int], str | None]:
    """The integer weight (cost in hundredths) of each of ``motions`` (e.g. every motion of a
    FOON) and one warning naming the motions the table lacks (each costs 1), or None."""
    weights = {m: table.weight(m) for m in sorted(set(motions))}
    missing = [m for m in weights if motion_key(m) not in table.costs]
    if not missing:
        return weights, None
    shown = ", ".join(missing[:20]) + (f", ... ({len(missing) - 20} more)" if len(missing) > 20 else "")
    where = f"{table.path}: " if table.path else ""
    n = len(missing)
    return weights, (
        f"{where}{n} motion{'s are' if n > 1 else ' is'} not in the motion-cost table "
        f"and cost {DEFAULT_COST} each: {shown}"
    )
