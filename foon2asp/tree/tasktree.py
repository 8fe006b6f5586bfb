"""Task trees: a goal, units in executable order, status and measures."""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field
from decimal import Decimal
from typing import TYPE_CHECKING

from foon2asp.foon.motioncost import as_number
from foon2asp.foon.problem import Problem

if TYPE_CHECKING:
    import clingo

#: statuses of an answer with a tree (result records too)
WITH_TREE = ("optimal", "ranked", "feasible", "found")

#: statuses of an answer proven best (``ranked``: once the better trees are excluded)
PROVEN = ("optimal", "ranked")

#: the goal of a tree read from a model until it is finished for its goal
NO_GOAL = -1


@dataclass
class TaskTree:
    """The answer for one goal (or one meal: several goals at once) by one method.

    ``units``: unit ids in executable order (empty: no tree).  ``status``: optimal, ranked,
    feasible, unreachable, infeasible (the user's constraints rule out every tree), unknown,
    or found/not-found (the search baselines).  ``goals``: every goal of a meal
    (``goal`` the first), empty for one goal.  ``alternatives``: further trees found with
    this one, best first, not part of its JSON.  The optional fields after ``proven_by`` say
    what else is known of the answer; None where it does not apply (left out of the JSON).

    The solver's callback reads each model straight into a tree (:meth:`from_model`); once the
    search is over, the answer's tree is finished in place for its goal
    (:func:`foon2asp.asp.answers.finish`).
    """

    goal: int
    method: str
    status: str
    units: list[int] = field(default_factory=list)
    cost: dict = field(default_factory=dict)
    time_s: float = 0.0
    stats: dict = field(default_factory=dict)
    goals: tuple[int, ...] = ()
    alternatives: list[TaskTree] = field(default_factory=list)
    #: the best proven lower bound per objective level, in the units of ``cost``
    #: (foon2asp.tree.gap); for a proven answer its cost; None: not known (search baselines)
    bound: dict | None = None
    #: the relative gap between the answer and ``bound`` on the first objective (0: proven)
    gap: float | None = None
    #: what proved the answer: "clingo", "fixpoint", "only-tree", "bounds" (None: not proven,
    #: or a search baseline's answer; foon2asp.methods.runner)
    proven_by: str | None = None
    #: the solver's cost vector, one integer weight per priority level, highest first
    asp_cost: list[int] | None = None
    #: the landmark units the bounds proof rests on (proven by "bounds"; foon2asp.bounds)
    landmarks: list[int] | None = None
    #: the landmark sets the bounds proof rests on: one unit of each set is in every tree
    landmark_sets: list[list[int]] | None = None
    #: the case split the bounds proof rests on: ``{"object": O, "cases": [{"unit", "landmarks",
    #: "landmark_sets"}, ...]}``, one case per unit that makes O, an object every tree makes
    landmark_cases: dict | None = None
    #: the goal's derivation level the bounds proof rests on (``units``: no tree has fewer units)
    derivation_level: int | None = None
    #: the units a person does (``--human-steps``), in executable order
    human_steps: list[int] | None = None
    #: the positions (from 1) of :attr:`human_steps` in :attr:`units`
    human_step_numbers: list[int] | None = None
    #: the depth bound the tree was found within (the depth objective, searched depth first)
    depth_bound: int | None = None
    #: how many smaller depth bounds were refuted, by "grounder" (the fixpoint) and "solver"
    depth_refuted: dict[str, int] | None = None
    #: the tree's place among the trees found for its goal (``--models``, ``--all-optimal``), from 1
    rank: int | None = None
    #: how a tree was found when the solver gave none in time ("cheapest-first")
    fallback: str | None = None
    #: what the solver says about the answer (a fallback tree, a cut list of optimal trees)
    note: str | None = None
    #: with substitutes: the substitutions the tree uses, ``{"needed", "used"}`` texts
    substitutions: list[dict] | None = None
    #: an infeasible answer: the user's programs that alone rule out every tree
    infeasible_by: list[str] | None = None
    #: why there is no tree (a depth bound, the user's programs, unreachable goals of a meal)
    reason: str | None = None
    #: an unreachable meal: those of its goals that cannot be made alone, as JSON objects
    unreachable_goals: list[dict] | None = None
    #: the names of the user's programs the answer was sought under (``--rule``, ``--forbid-motion``, ...)
    constraints: list[str] | None = None
    #: the independent validator's verdict (foon2asp.analysis.compare.judge); None: not judged
    valid: bool | None = None
    #: why the validator rejects the tree
    problem: str | None = None

    @classmethod
    def from_model(cls, model: clingo.Model, proven: bool | None = None) -> TaskTree:
        """The tree of a clingo ``model`` as the solver reports it: its ``use/1`` units (sorted by id),
        its cost vector (:attr:`asp_cost`), its ``human/1`` units (:attr:`human_steps`, sorted by id;
        None: none), status ``optimal`` when its optimality is proven (``proven``: the caller says)
        and else ``feasible``.  Not finished: its goal is :data:`NO_GOAL`, its method empty, its
        units not yet in executable order and it has no measures."""
        units: list[int] = []
        human: list[int] = []
        for s in model.symbols(shown=True):
            name = s.name
            if name == "use" or name == "human":
                args = s.arguments
                if len(args) == 1:
                    (units if name == "use" else human).append(args[0].number)
        done = model.optimality_proven if proven is None else proven
        units.sort()
        human.sort()
        return cls(
            NO_GOAL, "", "optimal" if done else "feasible", units, asp_cost=list(model.cost), human_steps=human or None
        )

    @property
    def proven(self) -> bool:
        """Is the tree proven best (status ``optimal``, or ``ranked``)?  A tree read from a model is
        ``optimal`` exactly when the solver proved it (:meth:`from_model`)."""
        return self.status in PROVEN

    def optional(self) -> dict:
        """The optional fields that are set (not None), in the order of :data:`OPTIONAL`."""
        return {name: value for name in OPTIONAL if (value := getattr(self, name)) is not None}

    @property
    def has_tree(self) -> bool:
        return self.status in WITH_TREE

    @property
    def meal(self) -> tuple[int, ...]:
        """Every goal of the tree (one for a single goal)."""
        return self.goals or (self.goal,)

    @property
    def is_meal(self) -> bool:
        return len(self.goals) > 1


#: the optional fields of :class:`TaskTree`, in the order its JSON gives them
OPTIONAL = (
    "asp_cost",
    "landmarks",
    "landmark_sets",
    "landmark_cases",
    "derivation_level",
    "human_steps",
    "human_step_numbers",
    "depth_bound",
    "depth_refuted",
    "rank",
    "fallback",
    "note",
    "substitutions",
    "infeasible_by",
    "reason",
    "unreachable_goals",
    "constraints",
    "valid",
    "problem",
)

Goals = int | tuple[int, ...]


def meal_of(goal: int | Iterable[int]) -> tuple[int, ...]:
    """A goal id or several as a tuple of distinct ids (first occurrence kept)."""
    if isinstance(goal, int):
        return (goal,)
    out = tuple(dict.fromkeys(int(g) for g in goal))
    if not out:
        raise ValueError("a meal needs at least one goal")
    return out


def goal_fields(goal: int | Iterable[int]) -> dict:
    """``goal`` and ``goals`` keyword arguments of :class:`TaskTree` for one goal or a meal."""
    meal = meal_of(goal)
    return {"goal": meal[0], "goals": meal if len(meal) > 1 else ()}


def executable_order(problem: Problem, units: list[int] | set[int]) -> list[int]:
    """``units`` sorted so each runs after the units that make its inputs; units that can
    never fire go last, in id order (validity is :mod:`foon2asp.tree.validate`'s)."""
    units = sorted(set(units))
    _, level = problem.derivation_levels(units)
    return sorted(units, key=lambda u: (level.get(u, math.inf), u))


def measures(problem: Problem, goal: int | Iterable[int], units: list[int]) -> dict:
    """Every measure of a tree: units, success product, input nodes, depth (of a meal: the
    greatest of its goals'; None when one is not made) and, with a motion-cost table
    (:attr:`Problem.motion_costs`), the exact summed cost of its motions."""
    obj_level, _ = problem.derivation_levels(list(units))
    success = math.prod(problem.rates[u] for u in units)
    levels = [obj_level.get(g) for g in meal_of(goal)]
    depth = None if any(d is None for d in levels) else max(d for d in levels if d is not None)
    out = {
        "units": len(units),
        "success": float(f"{success:.6g}"),
        "inputs": sum(len(problem.inputs[u]) for u in units),
        "depth": depth,
    }
    if problem.motion_costs is not None:
        table = problem.motion_costs
        out["cost"] = as_number(sum((table.cost(problem.units[u].motion) for u in units), Decimal(0)))
    return out
