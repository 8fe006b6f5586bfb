"""The answers the commands give, as plain values the renderers of :mod:`foon2asp.report` print.

They live below :mod:`foon2asp.analysis` and :mod:`foon2asp.batch`, which make them, so that
rendering them needs neither.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from decimal import Decimal

import clingo

from foon2asp.foon.model import FoonObject
from foon2asp.foon.motioncost import as_number
from foon2asp.foon.treefiles import TreeFile, TreeUnit
from foon2asp.tree.tasktree import TaskTree
from foon2asp.tree.validate import AloneVerdict, Finding, Validation


@dataclass
class Report:
    """Everything ``foon2asp check`` says about one tree."""

    tree: TreeFile
    goal: int
    ids: list[int | None]  # FOON unit id per tree unit (None: unknown)
    valid: bool
    finding: Finding | None
    validation: Validation | None
    order_problem: str | None  # None when the order as written is executable
    cost: dict
    optimum: TaskTree | None = None
    goal_source: str = ""
    #: every goal when the tree is checked for a meal (else empty)
    goals: tuple[int, ...] = ()
    #: with substitutes: the ones a valid tree uses, ``{"needed", "used"}`` texts (None: no substitutes)
    substitutions: list[dict] | None = None
    #: the proof the tree's file claims, re-verified: ``{"proven_by", "verified", "problem"}`` (None: none claimed)
    proof: dict | None = None
    #: the optimum's ``bounds`` proof, re-verified the same way (None: the optimum is proven otherwise)
    optimum_proof: dict | None = None

    @property
    def meal(self) -> tuple[int, ...]:
        return self.goals or (self.goal,)


@dataclass
class AloneReport:
    """``check`` of a tree on its own (no FOON): the verdict of
    :func:`foon2asp.tree.validate.judge_alone`; valid means the units fire in the order written
    and make the goal."""

    tree: TreeFile
    verdict: AloneVerdict
    #: where the goal came from: ``--goal``, ``named in the file`` or ``the products of its last unit``
    goal_source: str = ""
    #: where the kitchen came from: ``its leaves`` or a kitchen file
    kitchen_source: str = "its leaves"

    @property
    def valid(self) -> bool:
        return self.verdict.in_order


@dataclass
class Candidate:
    """One candidate file of ``consolidate``: its units as read (distinct, in file order)."""

    path: str
    units: list[TreeUnit]
    warnings: list[str] = field(default_factory=list)


@dataclass
class CandidateVerdict:
    """A candidate judged for one goal of ``consolidate``: on its own units, in file order, from
    the consolidation's kitchen; its measures in the merged FOON; the steps the result uses."""

    candidate: Candidate
    verdict: AloneVerdict
    #: the merged FOON's unit id of each of its units
    ids: list[int]
    cost: dict
    #: steps (numbers in its file, from 1) of its units that the consolidated tree uses
    used: list[int]

    @property
    def valid(self) -> bool:
        return self.verdict.in_order


@dataclass
class Consolidation:
    """One goal (or one meal) of ``consolidate``: the proven-best tree of the merged candidates,
    each unit's source files, every candidate's verdict and, when unreachable, what to add."""

    goals: tuple[int, ...]
    tree: TaskTree
    #: per unit id of the merged FOON: the candidate files holding that unit, in the order given
    sources: list[list[str]]
    candidates: list[CandidateVerdict]
    #: the fewest objects to add to the kitchen (only when the goal is unreachable)
    missing: MissingResult | None = None
    goal_source: str = ""
    kitchen_source: str = "leaves"
    kitchen: list[FoonObject] = field(default_factory=list)


@dataclass
class Row:
    """One goal: the tree of each method (``valid`` set on each)."""

    goal: int
    trees: dict[str, TaskTree]


@dataclass
class MealRow:
    """A meal's tree beside the single optima of its goals (``compare --together``)."""

    goals: tuple[int, ...]
    meal: TaskTree
    singles: list[TaskTree]

    def total(self) -> dict:
        """The single optima added up (units, inputs, cost; success multiplied); {} if one has no tree."""
        if not all(t.has_tree for t in self.singles):
            return {}
        success = math.prod(t.cost.get("success", 1.0) for t in self.singles)
        total = {
            "units": sum(t.cost["units"] for t in self.singles),
            "success": float(f"{success:.6g}"),
            "inputs": sum(t.cost["inputs"] for t in self.singles),
            "depth": max(t.cost["depth"] or 0 for t in self.singles),
        }
        if all("cost" in t.cost for t in self.singles):
            # exact: each cost has at most two decimals
            total["cost"] = as_number(sum((Decimal(str(t.cost["cost"])) for t in self.singles), Decimal(0)))
        return total


def record_object(value: object) -> FoonObject | None:
    """The object a result record's ``goal`` (``{"label", "states", ...}``) names (None: not one)."""
    if not isinstance(value, dict) or not isinstance(value.get("label"), str):
        return None
    return FoonObject.make(
        value["label"],
        [str(s) for s in value.get("states") or []],
        [str(i) for i in value.get("ingredients") or []],
        value.get("container") if isinstance(value.get("container"), str) else None,
    )


@dataclass
class BatchReport:
    """What a batch did: counts, times and all records of the requested pairs."""

    done: int
    skipped: int
    elapsed_s: float
    records: list[dict]
    workers: int
    output: str | None
    #: the grounding used, and why when --grounding auto chose it
    grounding: str = ""
    grounding_reason: str = ""


@dataclass
class MissingResult:
    """What to add to the kitchen so ``goal`` can be made, and the tree it allows."""

    goal: int
    #: ``optimal`` (proven minimal), ``feasible`` (time ran out), ``unreachable``, ``unknown``
    status: str
    #: object ids to add, in id order
    missing: list[int] = field(default_factory=list)
    #: the tree (unit ids in executable order, with the added objects in the kitchen)
    units: list[int] = field(default_factory=list)
    cost: dict = field(default_factory=dict)
    time_s: float = 0.0
    #: why nothing helps, in words (only when unreachable)
    reason: str | None = None
    #: a cycle that blocks the goal: (object, unit) pairs, each unit makes its
    #: object and needs the next object (the last needs the first)
    cycle: list[tuple[int, int]] = field(default_factory=list)
    #: objects leading from the goal to the cycle, as (object, unit) pairs
    path: list[tuple[int, int]] = field(default_factory=list)
    #: every object that may be added (relevant to the goal)
    buyable: list[int] = field(default_factory=list)
    #: with substitutes: the ones the tree uses, ``{"needed", "used"}`` texts (None: no substitutes)
    substitutions: list[dict] | None = None
    #: every goal of a meal (``missing --together``; empty for one goal)
    goals: tuple[int, ...] = ()

    @property
    def has_tree(self) -> bool:
        return self.status in ("optimal", "feasible")


@dataclass
class ShownModel:
    """What a query shows of one model: its cost vector, whether its optimality is proven, and
    its shown atoms (any atoms, not a tree)."""

    cost: tuple[int, ...]
    proven: bool
    symbols: list[clingo.Symbol]


@dataclass
class QueryResult:
    """The models of the user's program (``query``)."""

    status: str
    answers: list[ShownModel]
    time_s: float
    #: clingo's info messages about the user's program (atoms no rule or fact defines)
    warnings: list[str] = field(default_factory=list)
    #: the encodings loaded, with the ones those asked for depend on
    encodings: list[str] = field(default_factory=list)
