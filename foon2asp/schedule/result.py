"""A schedule for one goal: its JSON shape (:meth:`ScheduleResult.to_dict`) and text timeline.

Times are kept in milliseconds and written in seconds; the fields: docs/schedules.md, "JSON".
"""

from __future__ import annotations

from dataclasses import dataclass, field
from decimal import Decimal

from foon2asp.asp.objectives import success_product
from foon2asp.foon.problem import Problem
from foon2asp.schedule.instances import Entry
from foon2asp.schedule.lower_bounds import MakespanBounds
from foon2asp.schedule.spec import HUMAN, TICKS, kind_of
from foon2asp.tree.serialize import goal_heading, tree_json
from foon2asp.tree.tasktree import TaskTree


def seconds(ticks: int | None) -> float | None:
    """Milliseconds as seconds (exact: every millisecond count is a short decimal)."""
    return None if ticks is None else float(Decimal(ticks) / TICKS)


def seconds_text(ticks: int | None) -> str:
    """``1.5``, ``2``, ``0.125``: seconds with the digits they need."""
    if ticks is None:
        return "-"
    whole, rest = divmod(ticks, TICKS)
    return str(whole) if not rest else f"{whole}.{rest:03d}".rstrip("0")


@dataclass
class ScheduleResult:
    """The schedule of one goal's tree (or, joint, of the tree chosen with it)."""

    problem: Problem
    #: the scheduled tree (joint: the chosen one)
    tree: TaskTree
    status: str
    agents: list[str]
    entries: list[Entry] = field(default_factory=list)
    bounds: MakespanBounds | None = None
    #: makespan of list scheduling, longest remaining chain first
    baseline: int | None = None
    joint: bool = False
    #: joint scheduling: the result for the given tree alone
    fixed: ScheduleResult | None = None
    reason: str | None = None
    time_s: float = 0.0
    stats: dict = field(default_factory=dict)
    #: joint scheduling cut short: a lower bound on the makespan of every tree (milliseconds)
    joint_bound: int | None = None

    def __post_init__(self) -> None:
        order = {name: k for k, name in enumerate(self.agents)}
        self.entries = sorted(self.entries, key=lambda e: (e.start, order.get(e.agent, 0), e.end, e.unit))

    @property
    def has_schedule(self) -> bool:
        return self.status in ("optimal", "feasible")

    @property
    def makespan(self) -> int | None:
        """Milliseconds (None without a schedule)."""
        return max((e.end for e in self.entries), default=0) if self.has_schedule else None

    @property
    def human(self) -> list[int]:
        """The units done by a person."""
        return [e.unit for e in self.entries if kind_of(e.agent) == HUMAN]

    @property
    def human_units_proven(self) -> bool | None:
        """Are the human units proven the fewest at this makespan (the makespan proven, and the
        tie-breaker's search ended or met its bound)?  None without a person or a schedule."""
        if not self.has_schedule or not any(kind_of(a) == HUMAN for a in self.agents):
            return None
        return self.status == "optimal" and self.stats.get("tie_breakers") != "time"

    def success(self) -> float | None:
        """The product of the motion success rates of the units done by robots (a person's step succeeds)."""
        if not self.has_schedule:
            return None
        return success_product(self.problem, [e.unit for e in self.entries], self.human)

    def to_dict(self) -> dict:
        """The JSON object of the goal's schedule (``schedule`` sorted by start, then agent)."""
        tree = tree_json(self.problem, self.tree)
        goal = {k: tree[k] for k in ("goal", "goals") if k in tree}
        b = self.bounds
        base = {} if self.baseline is None else {"method": "longest-chain-first", "makespan": seconds(self.baseline)}
        rows = [(self.problem.units[e.unit].to_json(), e.agent, seconds(e.start), seconds(e.end)) for e in self.entries]
        out: dict = {
            **goal,
            "status": self.status,
            "makespan": seconds(self.makespan),
            "bounds": {} if b is None else {k: seconds(getattr(b, k)) for k in ("chain", "work", "energy", "lower")},
            "baseline": base,
            "agents": list(self.agents),
            "schedule": [dict(zip(("unit", "agent", "start", "end"), row)) for row in rows],
            "tree": tree,
            "success": self.success(),
            "human_units": len(self.human) if self.has_schedule else None,
            "joint": self.joint,
            "encoding": self.stats.get("encoding"),
            "time_s": round(self.time_s, 6),
        }
        if self.human_units_proven is not None:
            out["human_units_proven"] = self.human_units_proven
        if self.reason:
            out["reason"] = self.reason
        if self.fixed is not None:
            f = self.fixed
            out["fixed_tree"] = {"status": f.status, "makespan": seconds(f.makespan), "units": len(f.tree.units)}
        if self.joint_bound is not None:
            out["joint_bound"] = seconds(self.joint_bound)
        return out

    def headline(self) -> str:
        """``Status: optimal  Makespan: 7.5 s  (list scheduling 8 s; lower bound before the search 6 s: chain 6 s,
        work 5.5 s, energy 6 s)``: the bounds are those known before the search (the makespan's proof may raise it)."""
        line = f"Status: {self.status}"
        if self.has_schedule:
            b = self.bounds
            line += f"  Makespan: {seconds_text(self.makespan)} s"
            if b is not None and self.baseline is not None:
                line += (
                    f"  (list scheduling {seconds_text(self.baseline)} s;"
                    f" lower bound before the search {seconds_text(b.lower)} s:"
                    f" chain {seconds_text(b.chain)} s, work {seconds_text(b.work)} s, energy {seconds_text(b.energy)} s)"
                )
        if self.status == "optimal" and self.human_units_proven is False:
            line += "  (the fewest human units at this makespan not proven in time)"
        if self.fixed is not None:
            line += f"  Given tree: {seconds_text(self.fixed.makespan)} s ({self.fixed.status})"
        if self.joint_bound is not None:
            line += f"  Every tree: at least {seconds_text(self.joint_bound)} s"
        if self.reason:
            line += f"  ({self.reason})"
        return line

    def to_text(self) -> str:
        """The goal, the headline, then one timeline per agent: ``start - end  motion -> products``."""
        lines = [goal_heading(self.problem, self.tree), self.headline()]
        if not self.has_schedule:
            return "\n".join(lines) + "\n"
        lines.append(f"Units: {len(self.entries)}  Agents: {', '.join(self.agents)}")
        width = max((len(seconds_text(e.end)) for e in self.entries), default=1)
        for agent in self.agents:
            mine = [e for e in self.entries if e.agent == agent]
            lines.append(f"  {agent}:" + ("" if mine else " (idle)"))
            for e in mine:
                unit = self.problem.units[e.unit]
                made = "; ".join(str(o) for o in unit.outputs if not o.is_bare())
                span = f"{seconds_text(e.start):>{width}} - {seconds_text(e.end):>{width}}"
                lines.append(f"    {span}  {unit.motion}" + (f" -> {made}" if made else ""))
        return "\n".join(lines) + "\n"
