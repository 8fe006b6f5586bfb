"""What one clingo control grounds and how it solves: a :class:`Grounding`, and its facts.

A grounding is decided by :func:`foon2asp.methods.plan.plan` (never here): the entry
encoding clingo loads, the fact programs Python writes, the units and kitchen they cover,
clingo's arguments and how the search runs (depth rounds, the canonical tree, loop cuts).
:func:`fact_programs` writes the facts it names; :class:`foon2asp.asp.session.Session`
carries it out.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from foon2asp.asp import dominance, objectives, substitute_facts
from foon2asp.asp.canonical import canonical_problem, chain_facts
from foon2asp.asp.facts import facts
from foon2asp.asp.options import AspOptions
from foon2asp.asp.prepared import Preparation, decision_facts
from foon2asp.foon.problem import Problem
from foon2asp.tree.gap import levels as level_names

#: the kinds of fact programs a grounding may name, in the order they are added
FACT_KINDS = (
    "problem",
    "objectives",
    "input_nodes",
    "motion_costs",
    "ranks",
    "human_limit",
    "human_order",
    "dominated",
    "substitutes",
    "goal",
    "preparation",
    "chain",
)

#: how the canonical tree (the smallest optimal tree in unit id order) is found after the search
CANONICAL = ("none", "hint", "here", "session", "driver")

#: how the depth objective or bound is searched (the multi-shot driver's rounds)
DEPTH = ("none", "bound", "first", "later")


@dataclass(frozen=True, eq=False)
class Grounding:
    """One clingo control: what it grounds and how it solves (decided by the plan)."""

    #: the problem whose facts are written (the kitchen may be cut down to a goal's part)
    problem: Problem
    #: the request's solver options (objectives, user programs, limits, alternatives)
    options: AspOptions
    #: the entry encoding (``encodings/NAME.lp``)
    entry: str
    #: the units whose facts are written
    units: tuple[int, ...]
    #: the fact programs, by kind (:data:`FACT_KINDS`)
    facts: tuple[str, ...]
    #: the optional fact predicates not written (no encoding or user program reads them)
    leave_out: tuple[str, ...] = ()
    #: write every kitchen item the facts' objects meet (False: only those among the units' objects)
    whole_kitchen: bool = True
    #: write ``unit/1`` and ``object/1``
    declare: bool = True
    #: the goal (or meal) grounded as facts; None: any goal, switched per solve (``any_goal.lp``)
    goal: tuple[int, ...] | None = None
    #: clingo's arguments
    args: tuple[str, ...] = ()
    #: one solve call per grounding (``--single-shot``): a second solve grounds afresh
    single_shot: bool = False
    #: clingo's arguments for the rounds after a loop cut of a single-shot grounding: one
    #: multi-shot control, grounded afresh once, to which each further cut is added
    cut_args: tuple[str, ...] = ()
    #: the prepared part of the goal (candidates, landmarks, the bounds tree), for the prepared route
    prepared: Preparation | None = None
    #: the prepared part is searched as closed sets with loop cuts (``solve_closed.lp``)
    closed: bool = False
    #: the features beyond one optimisation run on the multi-shot driver
    driven: bool = False
    #: greedy retrieval: the first model under the heuristic (``solve_greedy.lp``)
    greedy: bool = False
    #: how the depth objective or bound is searched (:data:`DEPTH`)
    depth: str = "none"
    #: how the canonical tree is found (:data:`CANONICAL`)
    canonical: str = "none"
    #: no answer within the time limit: a cheapest-first tree as ``feasible``
    fallback: bool = False

    @property
    def ranked(self) -> tuple[str, ...]:
        """The objectives the solver optimises, most important first."""
        return objectives.ranked(self.options)

    @property
    def levels(self) -> tuple[str, ...]:
        """The names of the solver's priority levels, highest first."""
        return level_names(self.ranked, "substitutes" in self.facts, "human_limit" in self.facts)

    def files(self) -> list[str]:
        """The encoding files clingo loads: the entry, and ``any_goal`` without a fixed goal."""
        return [self.entry] if self.goal is not None else [self.entry, "any_goal"]


@dataclass(frozen=True, eq=False)
class Decisions:
    """One clingo control for many goals: each goal's prepared part decided at its bound, the
    cost of its bounds tree, which meets the goal's lower bound (decided by the plan)."""

    #: the problem whose facts are written
    problem: Problem
    #: the objectives of the solver cost, most important first (a bound per objective)
    ranked: tuple[str, ...]
    #: the goals' prepared groundings, each with a bound (``prepared.bound``), in goal order
    groundings: tuple[Grounding, ...]
    #: the entry encoding (``encodings/NAME.lp``)
    entry: str = "decide_many"
    #: clingo's arguments
    args: tuple[str, ...] = ("--heuristic=Domain",)
    #: seconds the one search may take (None: no limit)
    time_limit: float | None = None

    @property
    def preparations(self) -> list[Preparation]:
        """The goals' prepared parts, in goal order (goal K is the K-th, from 1)."""
        return [g.prepared for g in self.groundings if g.prepared is not None]

    def describe(self) -> dict:
        """How the goals were decided, for each goal's ``stats.plan``: the entry, clingo's arguments
        and how many goals the one call was asked."""
        return {"entry": f"encodings/{self.entry}.lp", "args": list(self.args), "decided_with": len(self.groundings)}

    def facts(self) -> str:
        """The facts ``decide_many.lp`` reads: per goal K its part and bounds, the candidates'
        objects and weights, the kitchen items among them."""
        return decision_facts(self.problem, self.ranked, self.preparations)


def fact_programs(grounding: Grounding) -> list[tuple[str, str]]:
    """The facts ``grounding`` names, as (name, text) programs in :data:`FACT_KINDS` order,
    then the user's programs."""
    g = grounding
    problem, options, units = g.problem, g.options, list(g.units)
    ranked = g.ranked
    writers = {
        "problem": lambda: facts(
            problem, units=units, leave_out=g.leave_out, whole_kitchen=g.whole_kitchen, declare=g.declare
        ),
        "objectives": lambda: objectives.objective_facts(ranked),
        "input_nodes": lambda: objectives.input_node_facts(problem, units),
        "motion_costs": lambda: objectives.motion_cost_facts(problem, options, units),
        "ranks": lambda: objectives.rank_facts(problem, str(options.heuristic), units),
        "human_limit": lambda: f"human_limit({int(options.human_steps or 0)}).\n",
        "human_order": lambda: objectives.human_order_facts(problem, units),
        "dominated": lambda: dominance.dominance_facts(problem, units, ranked),
        "substitutes": lambda: substitute_facts.substitute_facts(
            problem, options.substitutes, units, options.max_substitutions
        ),
        "goal": lambda: "".join(f"goal({o}).\n" for o in g.goal or ()),
        "preparation": lambda: g.prepared.facts() if g.prepared is not None else "",
        "chain": lambda: chain_facts(units),
    }
    out = [(kind, writers[kind]()) for kind in FACT_KINDS if kind in g.facts]
    return out + list(options.programs)


def canonical_grounding(grounding: Grounding, meal: tuple[int, ...]) -> Grounding:
    """``grounding`` for ``meal``'s canonical session: the meal's part alone, its kitchen cut down
    to the part, the goal as facts, the canonical tree searched on it."""
    view, part = canonical_problem(grounding.problem, meal)
    kinds = tuple(k for k in FACT_KINDS if k in grounding.facts or k == "goal")
    return replace(
        grounding,
        problem=view,
        options=replace(grounding.options, units=part),
        units=part,
        facts=kinds,
        goal=meal,
        canonical="here",
    )
