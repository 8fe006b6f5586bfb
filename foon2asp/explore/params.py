"""The page's question: its query parameters, named as the command-line options, read and
checked into one value, and written back as the page's address.

``/?goal=<text>`` plus one parameter per control: ``objective``, ``time-limit``,
``forbid-motion``, ``forbid-object``, ``require-motion``, ``require-object``, ``rule``,
``max-units``, ``max-depth``, ``human-steps`` (as ``solve`` takes them), ``without`` (a kitchen
item taken out of the kitchen) and ``agents`` (the schedule view's, as ``schedule`` takes them).
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Iterable
from dataclasses import asdict, dataclass, fields, replace
from typing import Any

from foon2asp import api
from foon2asp.api.request import NOT_A_TIME_LIMIT
from foon2asp.errors import BAD_CHAR, InputError, char_name

#: the most characters of a question's address (the query string), of one value, of one rule
MAX_QUERY = 16_384
MAX_VALUE = 1_000
MAX_RULE = 4_000
#: the most values of a parameter that repeats
MAX_REPEATS = 100
#: the largest integer a count may be (the solver's integers are 32-bit)
MAX_INT = 2**31 - 1

#: parameter -> field; the ones that repeat hold tuples
SCALARS = {
    "goal": "goal",
    "objective": "objective",
    "time-limit": "time_limit",
    "max-units": "max_units",
    "max-depth": "max_depth",
    "human-steps": "human_steps",
    "agents": "agents",
}
LISTS = {
    "forbid-motion": "forbid_motion",
    "forbid-object": "forbid_object",
    "require-motion": "require_motion",
    "require-object": "require_object",
    "rule": "rule",
    "without": "without",
}
PARAMETERS = {**SCALARS, **LISTS}
#: the least value of each count
LEAST = {"max_units": 0, "max_depth": 1, "human_steps": 0}

#: clingo directives a rule may not hold: embedded code, and reading files
_REFUSED = re.compile(r"#\s*(script|include)\b", re.IGNORECASE)

#: a line of a rule as strings, comments and the code between them (an unclosed string is code; a block
#: comment is taken line by line)
_CODE = re.compile(r'"(?:[^"\\]|\\.)*"|%.*$|(?P<code>"?[^"%]*)')

#: what each answer of the page depends on (the other fields do not change it)
PANEL_FIELDS = {
    "tree": ("goal", "objective", "time_limit", "max_units", "max_depth", "human_steps", *LISTS.values()),
    "missing": ("goal", "objective", "time_limit", "max_units", "max_depth", "human_steps", *LISTS.values()),
    "baselines": ("goal", "objective", "time_limit", "without"),
    "schedule": ("goal", "objective", "time_limit", "max_units", "max_depth", "human_steps", "agents", *LISTS.values()),
}


@dataclass(frozen=True)
class Question:
    """What the page asks: a goal and the request's settings, each as the command line takes it."""

    goal: str | None = None
    objective: tuple[str, ...] = ("units",)
    time_limit: float | None = None
    max_units: int | None = None
    max_depth: int | None = None
    human_steps: int | None = None
    agents: str | None = None
    forbid_motion: tuple[str, ...] = ()
    forbid_object: tuple[str, ...] = ()
    require_motion: tuple[str, ...] = ()
    require_object: tuple[str, ...] = ()
    rule: tuple[str, ...] = ()
    without: tuple[str, ...] = ()

    @classmethod
    def parse(cls, items: Iterable[tuple[str, str]], most_seconds: float = math.inf) -> Question:
        """The question of the query parameters ``items`` (in order); an unknown or repeated
        parameter, a bad value, too much input or a refused rule is an :class:`InputError`;
        ``time-limit`` may be at most ``most_seconds``."""
        found: dict[str, Any] = {}
        lists: dict[str, list[str]] = {name: [] for name in LISTS.values()}
        for key, value in items:
            name = PARAMETERS.get(key)
            if name is None:
                close = difflib.get_close_matches(key, list(PARAMETERS), n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else f"; the parameters are {', '.join(PARAMETERS)}"
                raise InputError(f"unknown parameter {_shown(key)}{hint}")
            limit = MAX_RULE if name == "rule" else MAX_VALUE
            if len(value) > limit:
                raise InputError(f"{key}: {len(value)} characters is too long (at most {limit})")
            bad = BAD_CHAR.search(value)
            if bad:
                raise InputError(f"{key}: {char_name(bad.group(0))} is not allowed")
            value = value.strip()
            if name in lists:
                if len(lists[name]) >= MAX_REPEATS:
                    raise InputError(f"{key}: more than {MAX_REPEATS} values")
                if value and value not in lists[name]:
                    lists[name].append(value)
                continue
            if name in found:
                raise InputError(f"{key} is given twice")
            if value:
                found[name] = _scalar(key, name, value, most_seconds)
        for n, rule in enumerate(lists["rule"], 1):
            check_rule(f"--rule #{n}", rule)
        found.update((name, tuple(values)) for name, values in lists.items())
        return cls(**found)

    def items(self) -> list[tuple[str, str]]:
        """The query parameters of this question, in a fixed order, defaults left out."""
        out: list[tuple[str, str]] = []
        for key, name in PARAMETERS.items():
            value = getattr(self, name)
            if name in LISTS.values():
                out += [(key, v) for v in value]
            elif name == "objective":
                if value != Question.objective:
                    out.append((key, ",".join(value)))
            elif value is not None:
                out.append((key, f"{value:g}" if isinstance(value, float) else str(value)))
        return out

    def only(self, panel: str) -> Question:
        """The question with only what the answer ``panel`` depends on (a cache key)."""
        keep = PANEL_FIELDS[panel]
        return replace(Question(), **{f.name: getattr(self, f.name) for f in fields(self) if f.name in keep})

    def settings(self, seconds: float, shared: dict[str, Any] | None = None) -> dict[str, Any]:
        """The keywords of :meth:`foon2asp.api.Options.of` for this question, its time limit
        ``seconds`` when it names none, with the ``shared`` settings."""
        given: dict[str, Any] = {
            "objective": self.objective,
            "time_limit": self.time_limit or seconds,
            "forbid_motions": self.forbid_motion,
            "forbid_objects": self.forbid_object,
            "require_motions": self.require_motion,
            "require_objects": self.require_object,
            "rules": self.rule,
            "max_units": self.max_units,
            "max_depth": self.max_depth,
            "human_steps": self.human_steps,
        }
        return {**(shared or {}), **{k: v for k, v in given.items() if v not in (None, ())}}

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, found: dict[str, Any]) -> Question:
        given: dict[str, Any] = {k: tuple(v) if isinstance(v, list) else v for k, v in found.items()}
        return cls(**given)


def check_rule(name: str, text: str) -> None:
    """Refuse a rule that runs code (``#script``) or reads files (``#include``), and a character
    clingo cannot take outside a string or a comment (only ASCII: its message about one would
    not be readable)."""
    refused = _REFUSED.search(text)
    if refused:
        what = "run code" if refused.group(1).lower() == "script" else "read files"
        raise InputError(f"#{refused.group(1)} is refused here: a rule may not {what}", name)
    for number, line in enumerate(text.splitlines(), 1):
        for match in _CODE.finditer(line):
            if match.group("code") is None:
                continue
            bad = re.search(r"[^\x00-\x7f]", match.group("code"))
            if bad:
                column = match.start("code") + bad.start() + 1
                raise InputError(
                    f"{bad.group(0)!r} outside a string: clingo takes only ASCII there", name, number, column
                )


def _shown(text: str) -> str:
    """``text`` quoted for a one-line message, cut to 60 characters."""
    return repr(text if len(text) <= 60 else text[:59] + "\u2026")


def _scalar(key: str, name: str, value: str, most_seconds: float) -> Any:
    """The value of the parameter ``key`` (field ``name``), checked."""
    if name == "objective":
        return tuple(p.strip() for p in value.split(",") if p.strip()) or ("units",)
    if name == "time_limit":
        try:
            seconds = float(value)
        except ValueError:
            raise InputError(f"time-limit: {_shown(value)} is not a number of seconds") from None
        if not 0 < seconds < math.inf:
            raise InputError(f"time-limit: {_shown(value)} {NOT_A_TIME_LIMIT}")
        if seconds > most_seconds:
            raise InputError(f"time-limit: at most {most_seconds:g} seconds here (the explorer's --time-limit)")
        return seconds
    if name == "agents":
        api.parse_agents(value)
        return value
    if name in LEAST:
        if not re.fullmatch("[0-9]{1,10}", value) or not LEAST[name] <= int(value) <= MAX_INT:
            raise InputError(f"{key}: {_shown(value)} is not a whole number {LEAST[name]}..{MAX_INT}")
        return int(value)
    return value
