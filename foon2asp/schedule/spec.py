"""What a schedule is for: the agents, how long each motion takes, who can do what, shared resources.

The file formats and the duration lookup are documented in docs/schedules.md.  Durations are
read as decimals and kept as whole milliseconds (:data:`TICKS` per second); every error is one
:class:`~foon2asp.errors.InputError` naming the file, line and entry.
"""

from __future__ import annotations

import difflib
import json
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from decimal import Decimal
from pathlib import Path

from foon2asp.errors import InputError
from foon2asp.foon import reading
from foon2asp.foon.model import norm

#: the kind of agent that is a person (success 1.0, counted by the tie-breaker)
HUMAN = "human"

#: durations are exact to this many seconds (kept as whole units of it)
PRECISION = Decimal("0.001")
#: time unit of every integer time in :mod:`foon2asp.schedule`: milliseconds per second
TICKS = 1000
#: the longest duration accepted (seconds); sums of durations stay within clingo's integers
MAX_SECONDS = 100_000

DEFAULT_AGENTS = (("robot", 1),)
#: the most agents of one kind
MAX_AGENTS = 64

_KIND = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")

#: how alike two kinds must be (difflib's ratio) for one to be taken for a misspelling of the other
CLOSE = 0.75


def kind_of(agent: str) -> str:
    """The kind of an agent name (``arm-2`` -> ``arm``)."""
    return agent.rsplit("-", 1)[0]


def parse_agents(text: str | None) -> tuple[tuple[str, int], ...]:
    """``KIND=N[,KIND=N...]`` as ``((kind, n), ...)`` in the order given (None or empty: ``robot=1``)."""
    if text is None or not text.strip():
        return DEFAULT_AGENTS
    out: dict[str, int] = {}
    for part in text.split(","):
        kind, eq, count = (s.strip() for s in part.partition("="))
        if not eq:
            raise InputError(f"agents {text!r}: {part.strip()!r} is not KIND=N (e.g. arm=2,human=1)")
        if not _KIND.match(kind):
            raise InputError(f"agents {text!r}: kind {kind!r} must be a letter, then letters, digits or _")
        if not count.isdigit() or not 1 <= int(count) <= MAX_AGENTS:
            raise InputError(f"agents {text!r}: the number of {kind!r} agents must be a whole number 1..{MAX_AGENTS}")
        if kind in out:
            raise InputError(f"agents {text!r}: kind {kind!r} is given twice")
        out[kind] = int(count)
    return tuple(out.items())


def _line_of(text: str, *keys: str) -> int | None:
    """The line of the JSON key path ``keys`` in ``text`` (each key searched after the one before)."""
    pos = 0
    for key in keys:
        found = text.find(json.dumps(key), pos)
        if found < 0:
            found = text.find(json.dumps(key, ensure_ascii=False), pos)
        if found < 0:
            return None
        pos = found + 1
    return text.count("\n", 0, pos) + 1


def _read(path: str | Path, what: str, shape: str) -> tuple[str, str, dict]:
    """The path, text and JSON object of a file, numbers as :class:`~decimal.Decimal` (exact);
    ``shape`` is the error when it is not an object."""
    text, _ = reading.load(path, what)
    doc = json.loads(text, parse_float=Decimal, parse_int=Decimal)
    if not isinstance(doc, dict):
        raise InputError(shape, str(path), 1)
    return str(path), text, doc


def _check_kind(kind: str, path: str, text: str) -> None:
    if not _KIND.match(kind):
        raise InputError(
            f"kind {json.dumps(kind)} must be a letter, then letters, digits or _", path, _line_of(text, kind)
        )


def _ticks(value: object, path: str, text: str, keys: tuple[str, ...]) -> int:
    """A duration in seconds as whole milliseconds; an error names the file, line and entry."""
    if isinstance(value, bool) or not isinstance(value, Decimal):
        wrong = f"must be a number of seconds, not {json.dumps(value, default=str)}"
    elif not value.is_finite() or value < 0:
        wrong = f"must be at least 0, not {value}"
    elif value > MAX_SECONDS:
        wrong = f"is {value} s, above the limit of {MAX_SECONDS} s"
    elif value / PRECISION != (value / PRECISION).to_integral_value():
        wrong = f"is {value} s: finer than the precision of {PRECISION} s"
    else:
        return int(value / PRECISION)
    where = " / ".join(json.dumps(k, ensure_ascii=False) for k in keys)
    raise InputError(f"duration {where} {wrong}", path, _line_of(text, *keys))


@dataclass(frozen=True)
class Durations:
    """Durations in milliseconds by kind and motion (see the module docstring for the lookup)."""

    #: motion -> ms for every kind (``"*"``: the default motion)
    motions: Mapping[str, int] = field(default_factory=dict)
    #: kind -> motion -> ms (kind ``"*"``: kinds not listed; motion ``"*"``: the kind's default)
    kinds: Mapping[str, Mapping[str, int]] = field(default_factory=dict)

    def of(self, kind: str, motion: str) -> int:
        """How long ``motion`` takes an agent of ``kind``, in milliseconds."""
        motion = norm(motion)
        table = self.kinds.get(kind, self.kinds.get("*", {}))
        for source in (table, self.motions):
            if motion in source:
                return source[motion]
            if "*" in source:
                return source["*"]
        return TICKS


def load_durations(path: str | Path) -> Durations:
    """Read a durations file (``{motion: seconds}`` or ``{KIND: {motion: seconds}}``)."""
    shape = "a durations file is a JSON object {motion: seconds} or {KIND: {motion: seconds}}"
    p, text, doc = _read(path, "durations", shape)
    motions: dict[str, int] = {}
    kinds: dict[str, dict[str, int]] = {}
    for key, value in doc.items():
        if isinstance(value, dict):
            if key != "*":
                _check_kind(key, p, text)
            kinds[key] = {norm(m) if m != "*" else "*": _ticks(v, p, text, (key, m)) for m, v in value.items()}
        else:
            motions[norm(key) if key != "*" else "*"] = _ticks(value, p, text, (key,))
    return Durations(motions, kinds)


def load_capabilities(path: str | Path) -> dict[str, frozenset[str]]:
    """Read a capabilities file ``{KIND: [motion, ...]}``: kind -> the motions it can do."""
    p, text, doc = _read(path, "capabilities", "a capabilities file is a JSON object {KIND: [motion, ...]}")
    out: dict[str, frozenset[str]] = {}
    for kind, motions in doc.items():
        _check_kind(kind, p, text)
        if not isinstance(motions, list) or not all(isinstance(m, str) for m in motions):
            raise InputError(
                f"capabilities of {json.dumps(kind)} must be a list of motion names", p, _line_of(text, kind)
            )
        out[kind] = frozenset(norm(m) for m in motions)
    return out


def load_resources(path: str | Path) -> dict[str, int]:
    """Read a resources file ``{label: capacity}``: label -> how many units using it may run at once."""
    p, text, doc = _read(path, "resources", "a resources file is a JSON object {label: capacity}")
    out: dict[str, int] = {}
    for label, cap in doc.items():
        if isinstance(cap, bool) or not isinstance(cap, Decimal) or cap != cap.to_integral_value() or cap < 1:
            raise InputError(
                f"capacity of {json.dumps(label, ensure_ascii=False)} must be a whole number of at least 1",
                p,
                _line_of(text, label),
            )
        if not norm(label):
            raise InputError("a resource label must not be empty", p, _line_of(text, label))
        out[norm(label)] = min(int(cap), 10**6)
    return out


def _did_you_mean(kind: str, names: list[str]) -> list[str]:
    """The names closest to ``kind`` (a misspelling of one of them), best first."""
    return difflib.get_close_matches(kind, sorted(set(names) - {kind}), n=3, cutoff=CLOSE)


def _suggestion(near: list[str]) -> str:
    return f"; did you mean {' or '.join(near)}?" if near else ""


def check_kinds(
    agents: tuple[tuple[str, int], ...], named: Mapping[str, tuple[str | Path | None, list[str]]]
) -> list[str]:
    """Check the agents' kinds against the kinds the durations and capabilities name (``what ->
    (its file or None, kinds)``): a kind they name that no agent has, or an agent kind that they do
    not name but is a misspelling of one that is known (theirs, or ``human``), is an
    :class:`InputError` naming the file (or the agents) and the kind, with the closest kinds.
    Returns a note for each agent kind they do not name while they name some: it takes the default
    durations, or can do every motion."""
    have = [kind for kind, _ in agents]
    given = ",".join(f"{kind}={n}" for kind, n in agents)
    for what, (path, kinds) in named.items():
        for kind in kinds:
            if kind not in have:
                hint = _suggestion(_did_you_mean(kind, have))
                wrong = f"no agent has the kind {json.dumps(kind)} (the agents: {given}){hint}"
                if path is None:
                    raise InputError(f"{what}: {wrong}")
                raise InputError(wrong, str(path), _line_of(reading.load(path, what)[0], kind))
    mentioned = {kind for _, kinds in named.values() for kind in kinds}
    notes = []
    for kind in have:
        if kind in mentioned:
            continue
        near = [] if kind == HUMAN else _did_you_mean(kind, [*mentioned, HUMAN])
        if near:
            person = f" and is not {json.dumps(HUMAN)} (a person)" if HUMAN in near else ""
            raise InputError(
                f"agents {given!r}: the kind {json.dumps(kind)} is named in no file{person}{_suggestion(near)}"
            )
        if mentioned:
            notes.append(kind)
    files = [what for what, (_, kinds) in named.items() if kinds]
    takes = {"durations": "takes the default durations", "capabilities": "can do every motion"}
    return [
        f"agents {given!r}: no {' or '.join(files)} file names the kind {json.dumps(kind)}:"
        f" it {' and '.join(takes[what] for what in files)}"
        for kind in notes
    ]


@dataclass(frozen=True)
class ScheduleSpec:
    """The agents (``((kind, n), ...)``), durations, capabilities and resources of a schedule."""

    agents: tuple[tuple[str, int], ...] = DEFAULT_AGENTS
    durations: Durations = field(default_factory=Durations)
    #: kind -> motions it can do; a kind not listed can do every motion
    capabilities: Mapping[str, frozenset[str]] = field(default_factory=dict)
    #: object label -> capacity
    resources: Mapping[str, int] = field(default_factory=dict)
    #: one-line notes about the request (:func:`check_kinds`: agent kinds no file names)
    warnings: tuple[str, ...] = field(default=(), init=False, compare=False)

    def __post_init__(self) -> None:
        """The kinds the agents have and the durations and capabilities name, checked (:func:`check_kinds`)."""
        named = {
            "durations": (None, [kind for kind in self.durations.kinds if kind != "*"]),
            "capabilities": (None, list(self.capabilities)),
        }
        object.__setattr__(self, "warnings", tuple(check_kinds(self.agents, named)))

    @classmethod
    def from_files(
        cls,
        agents: str | None = None,
        durations: str | Path | None = None,
        capabilities: str | Path | None = None,
        resources: str | Path | None = None,
    ) -> ScheduleSpec:
        """The spec of an ``--agents`` text and the three files (each optional), the kinds the
        agents have and the files name checked against each other (:func:`check_kinds`; an error
        names the file and line)."""
        kinds = parse_agents(agents)
        table = load_durations(durations) if durations is not None else Durations()
        can = load_capabilities(capabilities) if capabilities is not None else {}
        named = {
            "durations": (durations, [kind for kind in table.kinds if kind != "*"]),
            "capabilities": (capabilities, list(can)),
        }
        check_kinds(kinds, named)
        return cls(kinds, table, can, load_resources(resources) if resources is not None else {})

    def agent_list(self) -> list[tuple[str, str]]:
        """``(name, kind)`` of every agent, numbered per kind: ``arm-1``, ``arm-2``, ``human-1``."""
        return [(f"{kind}-{i}", kind) for kind, n in self.agents for i in range(1, n + 1)]

    def can(self, kind: str, motion: str) -> bool:
        """Can an agent of ``kind`` do ``motion``?"""
        allowed = self.capabilities.get(kind)
        return allowed is None or norm(motion) in allowed

    def has_human(self) -> bool:
        return any(kind == HUMAN for kind, _ in self.agents)
