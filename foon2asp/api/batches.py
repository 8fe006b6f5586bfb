"""A batch run through the library: what it did, its records and summary, and the schedules of its trees."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Unpack

from foon2asp import report
from foon2asp.api.files import write_file
from foon2asp.api.options import Options, Settings
from foon2asp.api.results import Raw, Schedule, Source, schedules_json
from foon2asp.api.schedules import make_spec
from foon2asp.batch import schedules as batch_schedules
from foon2asp.batch.pool import AUTO
from foon2asp.batch.results import summarize
from foon2asp.errors import InputError
from foon2asp.schedule import DEFAULT_ENCODING, ScheduleSpec
from foon2asp.tree.results import BatchReport


@dataclass
class BatchRun:
    """What a batch did: counts, times, the grounding and every record of the requested pairs."""

    kb: Source
    raw: BatchReport
    #: :meth:`schedule`'s schedules, one per goal (empty until it runs)
    schedules: list[Schedule] = field(default_factory=list)
    done = Raw[int]("Results computed now.")
    skipped = Raw[int]("Results already in the file (``resume``).")
    elapsed_s = Raw[float]()
    records = Raw[list[dict]]("The JSON lines of the requested (goal, method) pairs, old and new.")
    workers = Raw[int]()
    output = Raw[str | None]()
    grounding = Raw[str]("``whole`` or ``per-goal``: the grounding used.")
    grounding_reason = Raw[str]('Why ``grounding="auto"`` chose it (empty otherwise).')

    def schedule(
        self,
        spec: ScheduleSpec | None = None,
        *,
        agents: str | dict[str, int] | None = None,
        durations: str | Path | None = None,
        capabilities: str | Path | None = None,
        resources: str | Path | None = None,
        method: str | None = None,
        joint: bool = False,
        encoding: str = DEFAULT_ENCODING,
        output: str | Path | None = None,
        options: Options | None = None,
        **settings: Unpack[Settings],
    ) -> list[Schedule]:
        """Schedule the tree of every goal of the run (of ``method``; default the first asked for)
        as :meth:`Tree.schedule` does; ``output``: also write them there as ``schedule --format json``."""
        solver = self.kb.options(options, **settings)
        chosen = make_spec(spec, agents, durations, capabilities, resources)
        view = partial(self.kb.judging_problem, solver)
        found = batch_schedules.schedule_records(
            self.kb.solving_problem(solver), self.raw.records, chosen, solver, method, joint, encoding, view
        )
        self.schedules = [Schedule(self.kb, r, chosen) for r in found]
        if output is not None:
            write_file(Path(output), schedules_json(self.schedules).encode("utf-8"))
        return self.schedules

    def summary(self) -> list[dict]:
        """One row per method: results per status, trees, valid trees, tree sizes and times."""
        return summarize(self.raw.records)

    def render(self, fmt: str = "text") -> str:
        """The summary ``batch`` prints, in a format of ``batch --summary``."""
        # the HTML page draws the schedules, and the FOON for kitchen items and cycles
        extra = [[s.to_dict() for s in self.schedules], self.kb.problem] if fmt == "html" else []
        return report.render("summary", fmt, self.summary(), self.raw, *extra)


def workers_count(workers: int | str) -> int:
    """``workers`` of :meth:`foon2asp.api.KnowledgeBase.batch` as the pool takes it (``"auto"``: :data:`AUTO`)."""
    if isinstance(workers, str) and workers.strip().lower() == "auto":
        return AUTO
    if isinstance(workers, bool) or not isinstance(workers, int) or not 1 <= workers <= 1024:
        raise InputError(f"workers must be 1..1024 or 'auto', not {workers!r}")
    return workers
