"""Lower bounds on the makespan of an instance (:class:`foon2asp.schedule.instances.Instance`; ms).

The chain, work and energy bounds (:func:`bounds`) and the fewest units a person must do at a
makespan (:func:`human_lower`); why each is a bound: docs/proofs/schedules.md.
"""

from __future__ import annotations

import bisect
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

from foon2asp.schedule.instances import Instance, divisor, earliest, successors, tails
from foon2asp.schedule.spec import HUMAN

#: unit -> milliseconds (durations, earliest starts, tails)
Times = dict[int, int]
Gaps = list[tuple[float, float]]


@dataclass(frozen=True)
class MakespanBounds:
    """Lower bounds on the makespan (milliseconds)."""

    #: the longest chain of minimum durations
    chain: int
    #: total minimum work over the number of agents, rounded up
    work: int
    #: energetic reasoning over windows (:func:`energy_over`, :func:`kind_energy`); at least the other two
    energy: int = 0

    @property
    def lower(self) -> int:
        return max(self.chain, self.work, self.energy)


def energy_over(
    parts: list[list[int]], d: Times, start: Times, tail: Times, servers: int, floor: int, step: int
) -> int:
    """Energetic reasoning: the least makespan at least ``floor``, a multiple of ``step``, at
    which every window between a unit's earliest start and a tail can hold the parts of
    ``parts`` (lists of units of which one runs, durations ``d``) on ``servers``."""
    return _clear(_gaps(parts, d, start, tail, servers), floor, step)


def pools(inst: Instance) -> list[tuple[list[int], dict[int, int], int]]:
    """Sets of units sharing fewer servers than the agents, as ``(units, durations, servers)``:
    for each set of kinds but all, and for each resource."""
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


def window_length(c: Sequence[float], m: int) -> float:
    """The least L > 0 with sum(min(c_i, L)) <= m L for parts of lengths ``c``: the shortest
    window that holds them on m servers (0 when they need no window; inf when none does)."""
    c = sorted(c)
    n = len(c)
    prefix = 0.0
    for j in range(n + 1):
        slope = m - (n - j)
        if slope > 0:
            root = max(c[j - 1] if j else 0, prefix / slope)
            if j == n or root < c[j]:
                return root
        if j < n:
            prefix += c[j]
    return math.inf


def _gaps(parts: list[list[int]], d: Times, start: Times, tail: Times, servers: int) -> Gaps:
    """The makespans :func:`energy_over` rules out: open intervals (low, high)."""
    units = [u for g in parts for u in g]
    if not units:
        return []
    after = sorted({tail[u] - d[u] for u in units})
    out: Gaps = []
    for a in sorted({start[u] for u in units}):
        # each unit's part within [a, ...) before the tail cuts it
        head = [[min(d[u], start[u] + d[u] - a) for u in g] for g in parts]
        for b in after:
            c = [x for x in (min(min(x, tail[u] - b) for x, u in zip(h, g)) for h, g in zip(head, parts)) if x > 0]
            if len(c) < servers:
                continue  # fewer parts than servers: no window needed
            length = window_length(c, servers)
            if length > 0:
                out.append((a + b, a + b + length))
    return out


def _clear(gaps: Gaps, floor: int, step: int) -> int:
    """The least multiple of ``step`` at least ``floor`` in none of the open intervals ``gaps``."""
    best = -(-floor // step) * step
    while True:
        inside = [high for low, high in gaps if low < best < high]
        if not inside:
            return best
        best = math.ceil(max(inside) / step) * step


def bounds(inst: Instance) -> MakespanBounds:
    """The chain, work and energy bounds, the energy bound also over :func:`pools` and, with
    several kinds, :func:`kind_energy`."""
    start = earliest(inst)
    if len(start) < len(inst.units):
        raise ValueError("some unit never becomes ready")
    chain = max((start[u] + inst.min_duration(u) for u in inst.units), default=0)
    work = -(-sum(inst.min_duration(u) for u in inst.units) // len(inst.agents))
    tail = tails(inst)
    d = {u: inst.min_duration(u) for u in inst.units}
    gaps = _gaps([[u] for u in inst.units], d, start, tail, len(inst.agents))
    floor = max(chain, work)
    for units, pd, servers in pools(inst):
        gaps += _gaps([[u] for u in units], pd, start, tail, servers)
        floor = max(floor, -(-sum(pd.values()) // servers))
    step = divisor(inst)
    energy = _clear(gaps, floor, step)
    return MakespanBounds(chain, work, kind_energy(inst, start, tail, energy, step))


# ---------------------------------------------------------------- kinds of agents


def _classes(inst: Instance) -> list[tuple[int, Times, int, Times]]:
    """Two classes of agents per test of :func:`kind_energy`, one kind and the other kinds as
    one: ``(agents, durations, agents, durations)`` (a unit missing where nobody can do it)."""
    kinds = sorted(inst.kinds)
    if len(kinds) < 2:
        return []
    out = []
    for kind in kinds if len(kinds) > 2 else kinds[:1]:
        rest = [k for k in kinds if k != kind]
        mine = {u: t[kind] for u, t in inst.durations.items() if kind in t}
        theirs = {u: min(t[k] for k in rest if k in t) for u, t in inst.durations.items() if any(k in t for k in rest)}
        out.append((inst.kinds[kind], mine, sum(inst.kinds[k] for k in rest), theirs))
    return out


#: a window test of :func:`window_tests`: the class split (an index of :func:`_classes`), the
#: window of its first class and that of its second
Window = tuple[int, tuple[int, int], tuple[int, int]]


def _splits(inst: Instance, r: Times, e: Times) -> list[tuple[int, int, _Parts, list[int], list[int]] | None]:
    """For each class split of :func:`_classes`: its agents, the units' mandatory parts and the
    window ends (earliest or latest starts, latest or earliest ends); None when a unit fits
    neither class within ``[r, e]``."""
    units = [u for u in inst.units if inst.durations[u]]
    out: list[tuple[int, int, _Parts, list[int], list[int]] | None] = []
    for n_x, dur_x, n_y, dur_y in _classes(inst):
        # each unit's duration on a class, if it fits its window there
        px = {u: dur_x[u] for u in units if u in dur_x and dur_x[u] <= e[u] - r[u]}
        py = {u: dur_y[u] for u in units if u in dur_y and dur_y[u] <= e[u] - r[u]}
        if any(u not in px and u not in py for u in units):
            out.append(None)
            continue
        lefts = sorted({*(r[u] for u in units), *(e[u] - p for u, p in px.items()), *(e[u] - p for u, p in py.items())})
        rights = sorted(
            {*(e[u] for u in units), *(r[u] + p for u, p in px.items()), *(r[u] + p for u, p in py.items())}
        )
        out.append((n_x, n_y, _Parts(units, r, e, px, py), lefts, rights))
    return out


def _per_class(
    parts: _Parts, e: Times, lefts: list[int], rights: list[int]
) -> list[tuple[tuple[int, int], tuple[int, int]]]:
    """The pairs of windows, one per class, that both start at the first left end or both end
    at the last right end (none when the units take as long on both classes)."""
    units = list(e)
    if all(parts.px.get(u) == parts.py.get(u) for u in units):
        return []
    lo, hi = lefts[0], rights[-1]
    ends = [(lo, b) for b in sorted(set(e.values())) if b > lo]
    begins = [(a, hi) for a in sorted({parts.r[u] for u in units}) if a < hi]
    return [(wx, wy) for windows in (ends, begins) for wx in windows for wy in windows if wx != wy]


def _kinds_fit(inst: Instance, start: Times, tail: Times, horizon: int) -> bool:
    """Can the units end by ``horizon`` as far as energetic reasoning over two classes of
    agents (:func:`_classes`) tells?"""
    units = [u for u in inst.units if inst.durations[u]]
    if not units:
        return True
    r = {u: start[u] for u in units}
    e = {u: horizon - tail[u] + inst.min_duration(u) for u in units}
    if any(e[u] - r[u] < inst.min_duration(u) for u in units):
        return False
    for split in _splits(inst, r, e):
        if split is None:
            return False
        n_x, n_y, parts, lefts, rights = split
        # windows from an earliest start or a latest start to a latest end or an earliest end
        for a in lefts:
            if not all(parts.fit((a, b), (a, b), n_x, n_y, keep=False) for b in rights if b > a):
                return False
        if not all(parts.fit(wx, wy, n_x, n_y) for wx, wy in _per_class(parts, e, lefts, rights)):
            return False
    return True


def window_tests(inst: Instance, r: Times, e: Times) -> list[Window]:
    """Every window :func:`_kinds_fit` tests, for units within ``[r, e]`` (ms)."""
    out: list[Window] = []
    for i, split in enumerate(_splits(inst, r, e)):
        if split is not None:
            _, _, parts, lefts, rights = split
            out += [(i, (a, b), (a, b)) for a in lefts for b in rights if b > a]
            out += [(i, wx, wy) for wx, wy in _per_class(parts, {u: e[u] for u in parts.r}, lefts, rights)]
    return out


def slack_of_windows(
    inst: Instance, r: Times, e: Times, tests: list[Window], count: int = 0
) -> tuple[float, list[Window]]:
    """The least slack of ``tests`` (work the second class could still take; negative: the
    units within ``[r, e]`` do not fit) and the ``count`` tightest tests; -1 when a unit fits
    no class."""
    splits = _splits(inst, r, e)
    if any(s is None for s in splits):
        return -1.0, []
    found = []
    for i, wx, wy in tests:
        split = splits[i]
        assert split is not None
        n_x, n_y, parts = split[:3]
        found.append((parts.slack(wx, wy, n_x, n_y), i, wx, wy))
    found.sort()
    least = found[0][0] if found else 0.0
    return least, [(i, wx, wy) for _, i, wx, wy in found[:count]]


class _Parts:
    """The mandatory parts of units in windows, on two classes of agents (durations ``px``
    and ``py``; a unit missing from one cannot go there), each unit within ``[r, e]``."""

    def __init__(self, units: list[int], r: Times, e: Times, px: Times, py: Times) -> None:
        self.r, self.e, self.px, self.py = r, e, px, py
        self.both = [u for u in units if u in px and u in py]
        self.cache: dict[tuple[int, int, bool], tuple[dict[int, int], int, int]] = {}

    def parts(self, window: tuple[int, int], x: bool, keep: bool) -> tuple[dict[int, int], int, int]:
        """Each unit's least part within ``window`` on class x (``x``) or y, if it can go there;
        the sum over the units only that class can do, and over those both can (``keep``: cached)."""
        key = (*window, x)
        if key in self.cache:
            return self.cache[key]
        a, b = window
        mine, other = (self.px, self.py) if x else (self.py, self.px)
        part = {u: max(0, min(b - a, d, self.r[u] + d - a, b - (self.e[u] - d))) for u, d in mine.items()}
        found = part, sum(m for u, m in part.items() if u not in other), sum(part[u] for u in self.both)
        if keep:
            self.cache[key] = found
        return found

    def fit(self, wx: tuple[int, int], wy: tuple[int, int], n_x: int, n_y: int, keep: bool = True) -> bool:
        """Can the parts be split: class x's in ``wx`` on its ``n_x`` agents, y's in ``wy``?"""
        return self.slack(wx, wy, n_x, n_y, keep) >= -1e-6

    def slack(self, wx: tuple[int, int], wy: tuple[int, int], n_x: int, n_y: int, keep: bool = True) -> float:
        """How much work class y could still take after the best split of :meth:`fit` (negative:
        none fits)."""
        (on_x, only_x, both_x), (on_y, only_y, both_y) = self.parts(wx, True, keep), self.parts(wy, False, keep)
        cap_x = n_x * (wx[1] - wx[0]) - only_x
        cap_y = n_y * (wy[1] - wy[0]) - only_y
        if cap_x < 0 or cap_y < 0:
            return min(cap_x, cap_y)
        if both_x <= cap_x or both_y <= cap_y:  # all of them on one class
            return max(cap_x - both_x, cap_y - both_y)
        return _split([(on_x[u], on_y[u]) for u in self.both], cap_x, cap_y)


def _split(work: list[tuple[int, int]], cap_x: int, cap_y: int) -> float:
    """The room left on y when parts of ``(work on x, work on y)`` are split, fractionally,
    within the capacities (negative: they cannot be)."""
    work = sorted(work, key=lambda w: -(w[1] / w[0]) if w[0] > 0 else -math.inf)
    room, left = float(cap_x), 0.0
    for x, y in work:
        taken = 1.0 if x == 0 else min(max(room / x, 0.0), 1.0)
        room -= x
        left += (1 - taken) * y
    return cap_y - left


def kind_energy(inst: Instance, start: Times, tail: Times, floor: int, step: int) -> int:
    """The least makespan at least ``floor``, a multiple of ``step``, that :func:`_kinds_fit`
    allows (``floor`` itself with a single kind)."""
    low = -(-floor // step) * step
    if len(inst.kinds) < 2 or _kinds_fit(inst, start, tail, low):
        return low
    jump = step
    while not _kinds_fit(inst, start, tail, low + jump):
        low, jump = low + jump, 2 * jump
    high = low + jump  # low fails, high fits
    while high - low > step:
        mid = low + (high - low) // step // 2 * step
        if _kinds_fit(inst, start, tail, mid):
            high = mid
        else:
            low = mid
    return high


def human_lower(inst: Instance, horizon: int) -> int:
    """The fewest units a person (an agent of kind ``human``) does in every schedule of
    makespan at most ``horizon`` (0 without a person): the larger of a capacity count and a
    chain count (docs/proofs/schedules.md)."""
    if HUMAN not in inst.kinds:
        return 0
    start, tail = earliest(inst), tails(inst)
    return max(_capacity_human(inst, horizon, start, tail), _chain_human(inst, horizon, start, tail))


def _chain_human(inst: Instance, horizon: int, start: Times, tail: Times) -> int:
    """The fewest units done by a person for every unit to fit its window and precede the unit
    after it, each at the duration of the kind doing it, over a forest of the precedence;
    every unit when no assignment fits."""
    after = successors(inst.preds)
    before: dict[int, list[int]] = {u: [] for u in inst.units}
    roots = []
    for u in inst.units:
        if after[u]:
            before[max(after[u], key=lambda v: (tail[v], v))].append(u)
        else:
            roots.append(u)
    latest = {u: horizon - tail[u] + inst.min_duration(u) for u in inst.units}
    memo: dict[tuple[int, int], float] = {}

    def fewest(v: int, end: int) -> float:
        end = min(end, latest[v])
        if (v, end) not in memo:
            best = math.inf
            for kind, d in inst.durations[v].items():
                if v not in start or end - d < start[v]:
                    continue
                count: float = 1 if kind == HUMAN else 0
                for p in before[v]:
                    count += fewest(p, end - d)
                    if count >= best:
                        break
                best = min(best, count)
            memo[(v, end)] = best
        return memo[(v, end)]

    total = sum(fewest(r, horizon) for r in roots)
    return len(inst.units) if math.isinf(total) else int(total)


def _capacity_human(inst: Instance, horizon: int, start: Times, tail: Times) -> int:
    """The capacity count of :func:`human_lower`."""
    return human_capacity(
        inst, {u: (start[u], horizon - tail[u] + inst.min_duration(u)) for u in inst.units if u in start}
    )


def human_capacity(inst: Instance, span: dict[int, tuple[int, int]]) -> int:
    """The capacity count of :func:`human_lower` for units each within its ``span`` (earliest
    start, latest end): the fewest units a person does in every schedule that keeps to them."""
    others = [k for k in inst.kinds if k != HUMAN]
    servers = sum(inst.kinds[k] for k in others)
    robot: dict[int, int] = {}  # each unit's shortest duration on the others, if it fits its window
    for u, (x, y) in span.items():
        d = min((inst.durations[u][k] for k in others if k in inst.durations[u]), default=None)
        if d is not None and d <= y - x:
            robot[u] = d
    lefts = sorted({a for a, _ in span.values()})
    rights = sorted({b for _, b in span.values()})
    found: list[tuple[int, int, int]] = []
    for a in lefts:
        for b in rights:
            if b <= a:
                continue
            inside = [u for u, (x, y) in span.items() if a <= x < b and y <= b]  # a unit in one of two that meet
            room = servers * (b - a)
            fit = 0
            for d in sorted(robot[u] for u in inside if u in robot):
                if d > room:
                    break
                room -= d
                fit += 1
            if len(inside) > fit:
                found.append((b, a, len(inside) - fit))
    found.sort()
    ends, best = [-1], [0]
    for b, a, gain in found:  # the best set of windows that do not overlap, by their ends
        value = best[bisect.bisect_right(ends, a) - 1] + gain
        if value > best[-1]:
            ends.append(b)
            best.append(value)
    return best[-1]
