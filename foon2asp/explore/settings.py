"""How an explorer is started: the data it loads, what every answer shares, and its limits."""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field, fields
from os import PathLike
from typing import Any

from foon2asp import api
from foon2asp.api.load import Reading
from foon2asp.api.request import NOT_A_TIME_LIMIT, check_keywords
from foon2asp.errors import InputError

#: the most seconds one answer may take unless the explorer is started with another ``time_limit``
MAX_SECONDS = 30.0
#: the seconds an answer may take when the page does not say (at most the explorer's limit)
DEFAULT_SECONDS = 10.0
#: solves running at once, each in a worker process of its own
DEFAULT_WORKERS = 2


@dataclass(frozen=True)
class Setup:
    """The data of an explorer (the arguments of :func:`foon2asp.api.load`), the request settings
    every answer shares (motion costs, substitutes), the schedule's tables, the default agents
    and the limits; plain values, so each worker process loads the same knowledge base."""

    path: str | None = None
    foon: tuple[str, ...] = ()
    goals: str | None = None
    #: :class:`foon2asp.api.load.Reading`'s fields: kitchen, motion, utensils, level, ...
    reading: dict[str, Any] = field(default_factory=dict)
    motion_cost: str | None = None
    substitutes: str | None = None
    max_substitutions: int | None = None
    #: the schedule view's default agents (``arm=2,human=1``; None: one robot) and tables (files)
    agents: str | None = None
    durations: str | None = None
    capabilities: str | None = None
    resources: str | None = None
    #: the most seconds one answer may take; the page's ``time-limit`` is at most this
    time_limit: float = MAX_SECONDS
    workers: int = DEFAULT_WORKERS

    def __post_init__(self) -> None:
        limit = self.time_limit
        if isinstance(limit, bool) or not isinstance(limit, int | float) or not 0 < limit < math.inf:
            raise InputError(f"time_limit: {limit!r} {NOT_A_TIME_LIMIT}")
        if isinstance(self.workers, bool) or not isinstance(self.workers, int) or not 1 <= self.workers <= 64:
            raise InputError(f"workers must be 1..64, not {self.workers!r}")
        self.schedule_spec(None)  # bad agents or tables are an error now, not on the page

    @classmethod
    def of(cls, path: str | PathLike | None = None, **keywords: Any) -> Setup:
        """The setup of ``load(path, ...)``'s arguments and this class's own keywords."""
        names = [f.name for f in fields(Reading)]
        check_keywords(keywords, ({f.name for f in fields(cls)} - {"path", "reading"}) | set(names), "explore: ")
        reading = {k: _plain(keywords.pop(k)) for k in names if k in keywords}
        foon = keywords.pop("foon", None)
        foons = () if foon is None else (str(foon),) if isinstance(foon, str | PathLike) else tuple(map(str, foon))
        given = {k: _plain(v) for k, v in keywords.items()}
        return cls(_plain(path), foons, reading=reading, **given)

    def load(self) -> api.KnowledgeBase:
        """The knowledge base of this setup."""
        return api.load(self.path, foon=list(self.foon) or None, goals=self.goals, **self.reading)

    def shared(self) -> dict[str, Any]:
        """The request settings every answer shares, as :meth:`foon2asp.api.Options.of` takes them."""
        given: dict[str, Any] = {"motion_cost": self.motion_cost, "substitutes": self.substitutes}
        given["max_substitutions"] = self.max_substitutions
        return {k: v for k, v in given.items() if v is not None}

    def schedule_spec(self, agents: str | None) -> api.ScheduleSpec:
        """The schedule's agents (``agents``, else the default) with this setup's tables."""
        return api.ScheduleSpec.from_files(agents or self.agents, self.durations, self.capabilities, self.resources)

    def to_json(self) -> str:
        return json.dumps(asdict(self))

    @classmethod
    def from_json(cls, text: str) -> Setup:
        found = json.loads(text)
        found["foon"] = tuple(found["foon"])
        return cls(**found)


def _plain(value: Any) -> Any:
    """A path as text; any other value itself."""
    return str(value) if isinstance(value, PathLike) else value
