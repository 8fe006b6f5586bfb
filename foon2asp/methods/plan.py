"""One plan per request: how each goal is answered, decided in one place.

A :class:`Request` is what is asked (a method, its solver options, the problem) and is checked
once, where it is built (:func:`request`).  :func:`plan` decides, for one goal, everything
about answering it: the route, the entry encoding and the fact programs, clingo's arguments
and the steps after the solve.  A :class:`Plan` is a frozen value;
:class:`~foon2asp.methods.runner.GoalRunner`, :class:`~foon2asp.asp.session.Session` and
:class:`~foon2asp.asp.multishot.driver.Driver` carry it out and decide nothing.

The routes (why each answer is proven: docs/proofs/solving.md, "The routes"):

========== ================================================================= ============
route      when                                                              proven by
========== ================================================================= ============
search     a search baseline (IDS, GBFS)                                     nothing
fixpoint   the goal cannot be made from the kitchen, or is a kitchen item    fixpoint
only-tree  every object of the relevant part has one producer                only-tree
prepared   clingo on the goal's prepared part (every goal with a choice)      clingo
clingo     clingo on the whole grounding or the goal's part (meals, depth,   clingo
           alternatives, human steps, greedy retrieval, substitutes, ...)
========== ================================================================= ============
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Literal, overload

from foon2asp.asp import dominance, objectives, substitute_facts
from foon2asp.asp.canonical import canonical_problem
from foon2asp.asp.constraints import FLAG_READS
from foon2asp.asp.facts import OPTIONAL
from foon2asp.asp.grounding import Decisions, Grounding
from foon2asp.asp.options import AspOptions
from foon2asp.asp.predicates import checkable, mentioned, only_constraints
from foon2asp.asp.prepared import Preparation
from foon2asp.asp.programs_check import ProgramsCheck
from foon2asp.asp.session import Session
from foon2asp.bounds.lower import Bounds
from foon2asp.bounds.lower import supports as bounds_supports
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem
from foon2asp.methods.parts import GROUNDINGS, Parts
from foon2asp.methods.registry import effective_options, get
from foon2asp.tree.tasktree import Goals, meal_of
from foon2asp.tree.weights import UNIT_WEIGHTS

#: objectives whose cost is a sum of non-negative weights of the used units
MONOTONE = frozenset(UNIT_WEIGHTS)

#: the routes and what proves their answers (None: nothing)
ROUTES: dict[str, str | None] = {
    "search": None,
    "fixpoint": "fixpoint",
    "only-tree": "only-tree",
    "prepared": "clingo",
    "clingo": "clingo",
}


def plain(options: AspOptions) -> bool:
    """Is this plain optimisation of monotone objectives (nothing but the objectives asked)?"""
    return options.plain and all(name in MONOTONE for name in objectives.ranked(options))


def preparable(options: AspOptions) -> bool:
    """May a goal take the prepared route (plain, perhaps with programs that only remove trees)?"""
    return plain(replace(options, programs=[])) and only_constraints(options.programs)


@dataclass(frozen=True, eq=False)
class Request:
    """What is asked: one method with its solver options over one problem (checked by :func:`request`)."""

    #: the registered method
    method: str
    #: ``asp`` or ``search``
    kind: str
    #: the problem solved (with substitutes, the one whose viability counts them)
    problem: Problem
    #: the method's solver options (the caller's, adjusted by the method)
    options: AspOptions
    #: the viable units and relevant parts of ``problem``, computed once
    parts: Parts
    #: ``whole`` (one grounding for every goal) or ``per-goal``
    grounding: str = "whole"
    #: goals without a choice are settled without clingo (``only-tree``)
    shortcuts: bool = True

    @property
    def ranked(self) -> tuple[str, ...]:
        """The objectives the solver optimises, most important first."""
        return objectives.ranked(self.options) if self.kind == "asp" else ()

    @property
    def label(self) -> str:
        """The method name the answers carry."""
        return self.options.method if self.kind == "asp" else self.method

    @property
    def allowed(self) -> frozenset[int] | None:
        """The units the caller allows (None: every unit)."""
        return None if self.options.units is None else frozenset(self.options.units)

    @cached_property
    def preparable(self) -> bool:
        """May goals take the prepared route?"""
        return self.kind == "asp" and preparable(self.options)

    @cached_property
    def depth_settles(self) -> bool:
        """The depth objective with nothing else asked: a goal without choice is settled first."""
        if self.kind != "asp" or "depth" not in self.ranked:
            return False
        return plain(replace(self.options, objective=tuple(o for o in self.options.objective if o != "depth")))

    @property
    def constrained(self) -> bool:
        """Under user programs the bounds tree is a hint only and nothing is pruned."""
        return bool(self.options.programs)

    @cached_property
    def checkable(self) -> bool:
        """Can a tree be checked against the user's programs?"""
        return self.constrained and checkable(self.options.programs)

    @cached_property
    def bounded(self) -> bool:
        """Do the bounds handle these objectives on the prepared route?"""
        return self.preparable and bounds_supports(self.ranked)

    @cached_property
    def free(self) -> Request:
        """The same request without the user's programs (its optimum is checked against them)."""
        return replace(self, options=replace(self.options, programs=[]))

    @cached_property
    def programs_check(self) -> ProgramsCheck:
        """The user's programs grounded once, asked tree by tree."""
        return ProgramsCheck(self.problem, self.options.programs, self.options.units, self.options.time_limit)

    def allows(self, tree: Iterable[int]) -> bool:
        """Does ``tree`` satisfy the user's programs (no programs: yes; unchecked: no)?"""
        if not self.constrained:
            return True
        return self.checkable and self.programs_check.allows(tree)

    @cached_property
    def whole(self) -> Grounding:
        """The one grounding of every goal: all viable (or allowed) units, any goal."""
        units = self.options.units if self.options.units is not None else tuple(sorted(self.parts.viable))
        return grounding(self.problem, replace(self.options, units=tuple(units)))


def check(name: str, kind: str, options: AspOptions) -> None:
    """The one check of which options combine, for method ``name`` of ``kind`` (``asp`` or
    ``search``): a one-line InputError when the method cannot honour them."""
    if not options.substitutes:
        return  # substitutes are the one setting some methods cannot honour
    if kind != "asp":
        raise InputError(f"method {name!r} is a search baseline and cannot use substitutes; use an ASP method (asp)")
    effective = effective_options(name, options)
    if effective.heuristic:
        raise InputError(f"method {name!r} is greedy retrieval and cannot use substitutes; use an ASP method (asp)")
    if effective.max_depth is not None or "depth" in effective.objective:
        raise InputError(
            f"method {name!r} with depth rounds or the depth objective cannot use substitutes;"
            " use another objective and no --max-depth"
        )


def request(
    name: str,
    problem: Problem,
    options: AspOptions,
    grounding: str = "whole",
    shortcuts: bool = True,
    parts: Parts | None = None,
    goals: Iterable[Goals] | None = None,
) -> Request:
    """The request of method ``name`` with the caller's ``options`` over ``problem``, checked once:
    the method and grounding exist, the options combine; ``goals``: the goals it will be asked, if
    known (a grounding then holds only their units); ``parts``: the caller's :class:`Parts` of ``problem``."""
    if grounding not in GROUNDINGS:
        raise ValueError(f"unknown grounding {grounding!r}")
    method = get(name)
    check(name, method.kind, options)
    if method.kind == "asp":
        options = effective_options(name, options)
    solved = substitute_facts.prepare(problem, options)
    if options.substitutes:  # a goal's part would leave out the kitchen items that stand in
        grounding = "whole"
    if goals is not None and method.kind == "asp" and options.units is None:
        options = replace(options, units=solved.units_for({g for goal in goals for g in meal_of(goal)}))
    if parts is None or parts.problem is not solved:
        parts = Parts(solved)
    return Request(name, method.kind, solved, options, parts, grounding, shortcuts and options.shortcuts)


@dataclass(frozen=True, eq=False)
class Plan:
    """How one goal is answered: its route and, for clingo, the grounding it solves on."""

    route: str
    #: the goal as a meal (one goal: a 1-tuple)
    goal: tuple[int, ...]
    #: the method name the answer carries
    method: str
    #: the objectives of the answer's solver cost, most important first
    ranked: tuple[str, ...] = ()
    #: the grounding clingo solves on (routes prepared and clingo)
    grounding: Grounding | None = None
    #: the grounding is the request's one whole grounding, grounded once for every goal
    shared: bool = False
    #: the answer settled without clingo: its units (only-tree, bounds)
    tree: tuple[int, ...] = ()
    #: first the optimum without the user's programs, kept when it satisfies them
    free_first: Plan | None = None
    #: when trees exist but the user's programs rule them all out, name each program that alone does
    explain: bool = False
    #: the names of the user's programs the answer is under
    programs: tuple[str, ...] = field(default=())

    @property
    def proven_by(self) -> str | None:
        """What proves a proven answer of this route."""
        return ROUTES[self.route]

    def describe(self) -> dict:
        """The plan as plain values (``stats.plan`` in JSON)."""
        out: dict = {"route": self.route, "proven_by": self.proven_by}
        g = self.grounding
        if g is not None:
            out.update(
                entry=f"encodings/{g.entry}.lp",
                facts=list(g.facts),
                args=list(g.args),
                units=len(g.units),
                shared=self.shared,
                goal="fixed" if g.goal is not None else "any",
                depth=g.depth,
                canonical=g.canonical,
            )
        if self.free_first is not None:
            out["free_first"] = self.free_first.describe()
        if self.explain:
            out["explain"] = True
        return out


def plan(req: Request, goal: Goals) -> Plan:
    """How ``goal`` (an object id, or a tuple of them: a meal) is answered under ``req``."""
    meal = meal_of(goal)
    base = Plan("search", meal, req.label, req.ranked, programs=tuple(name for name, _ in req.options.programs))
    if req.kind != "asp":
        if len(meal) > 1:
            raise InputError(f"meals (several goals in one tree) need an ASP method; {req.method!r} is not one")
        return base
    explain = req.constrained
    if len(meal) > 1 or not (req.preparable or req.depth_settles):
        return _clingo(req, base, explain)
    problem, (g,) = req.problem, meal
    if g not in problem.derivable or g in problem.kitchen:
        return replace(base, route="fixpoint")
    units, _, choice = req.parts.relevant(g)
    if req.allowed is not None and not req.allowed.issuperset(units):
        return _clingo(req, base, explain)  # the caller's units cut into the part
    if req.depth_settles:
        if req.shortcuts and not choice:
            return replace(base, route="only-tree", tree=tuple(units))
        return _clingo(req, base, explain)
    if req.shortcuts and not choice and req.allows(units):
        return replace(base, route="only-tree", tree=tuple(units))
    free = req.free if req.constrained else req
    # a goal with a choice in its part is clingo's, also one whose bounds tree meets the lower bound:
    # clingo then decides with the bounds tree's cost as the bound
    bounded = _bounded(free, g) if free.bounded else None
    prepared = _pruned(free, *bounded) if bounded is not None else preparation(free, g)
    if req.checkable:
        first = replace(base, route="prepared", programs=(), grounding=_grounding(free, prepared))
        return replace(
            base, route="prepared", grounding=_grounding(req, preparation(req, g)), free_first=first, explain=explain
        )
    if req.constrained:
        prepared = preparation(req, g)
    return replace(base, route="prepared", grounding=_grounding(req, prepared), explain=explain)


def decisions(req: Request, plans: Iterable[Plan]) -> Decisions | None:
    """The goals of ``plans`` clingo decides together, in one call: those whose prepared part is
    searched for a tree within its bounds tree's cost, which meets the goal's lower bound, and
    whose answer is then that tree (the hint; no user programs, progress reports, alternatives or
    steps after the solve); None when fewer than two are."""
    chosen = []
    for p in plans:
        g = p.grounding
        if p.route != "prepared" or p.free_first is not None or p.explain or p.programs or g is None:
            continue
        prep = g.prepared
        if prep is None or prep.bound is None or not g.closed or g.canonical != "hint":
            continue
        if g.depth != "none" or len(g.facts) != len(_DECIDABLE_FACTS & set(g.facts)):
            continue
        chosen.append(g)
    options = req.options
    if len(chosen) < 2 or options.progress is not None or options.threads > 1:
        return None
    limit = DECIDE_S if options.time_limit is None else min(DECIDE_S, options.time_limit)
    return Decisions(req.problem, req.ranked, tuple(chosen), time_limit=limit)


#: seconds a grouped decision may take before its goals are left to their own searches (each
#: goal's bounds tree is the domain heuristic's first try, so a model is found at once)
DECIDE_S = 5.0

#: the fact programs of a prepared grounding that a grouped decision writes as well (a grounding
#: with others, e.g. substitutes or human steps, is decided on its own)
_DECIDABLE_FACTS = frozenset({"problem", "objectives", "input_nodes", "goal", "preparation"})


def _grounding(req: Request, prep: Preparation) -> Grounding:
    """The prepared route's grounding: the goal's prepared part."""
    return grounding(req.problem, req.options, prepared=prep)


def _clingo(req: Request, base: Plan, explain: bool) -> Plan:
    """The clingo route: the whole grounding (grounded once) or, per goal, the goal's part."""
    meal = base.goal
    if req.grounding == "whole" or len(meal) > 1:
        return replace(base, route="clingo", grounding=req.whole, shared=True, explain=explain)
    units, objects, _ = req.parts.relevant(meal[0])
    allowed = req.allowed
    if allowed is not None:
        units = [u for u in units if u in allowed]
    view = req.problem.with_kitchen(o for o in objects if o in req.problem.kitchen)
    found = grounding(view, replace(req.options, units=tuple(units)))
    return replace(base, route="clingo", grounding=found, explain=explain)


def preparation(req: Request, goal: int) -> Preparation:
    """What Python hands clingo for ``goal`` (a derivable goal that is no kitchen item): the part
    to search (pruned to the units an optimal tree may use), its landmarks, the bounds tree and
    its cost, the lower bound."""
    if not req.bounded:
        units, _, _ = req.parts.relevant(goal)
        return Preparation(goal, tuple(units), landmarks(req, goal))
    bounds, prep = _bounded(req, goal)
    return _pruned(req, bounds, prep)


def _bounded(req: Request, goal: int) -> tuple[Bounds, Preparation]:
    """The bounds of ``goal``'s part and the preparation they give, its part not yet pruned."""
    parts = req.parts
    units, _, _ = parts.relevant(goal)
    ranked = req.ranked
    bounds = parts.bounds_for(ranked, units)
    tree = bounds.tree(goal) or ()
    lower = bounds.lower(goal)
    if tree:  # the splits of the witness bound reach further than the lower bound's
        lower = max(lower, bounds.witness(goal, bounds.weight(tree)).bound)
    scale = len(req.problem.units) + 1

    def meets(cost: tuple[int, ...]) -> bool:
        weight = cost[0] if len(cost) == 1 else cost[0] * scale + cost[1]
        return weight <= lower

    return bounds, Preparation(
        goal,
        tuple(units),
        tuple(sorted(bounds.landmarks(goal))),
        hint=tuple(tree),
        known=None if req.constrained else tuple(bounds.cost(tree)),
        floor=bounds.first_lower(goal),
        meets=meets if len(ranked) <= 2 else None,
    )


def _pruned(req: Request, bounds: Bounds, prep: Preparation) -> Preparation:
    """``prep`` with its part cut to the units an optimal tree may use (none cut under user programs,
    which may need any relevant unit)."""
    if req.constrained:
        return prep
    goal, ranked = prep.goal, req.ranked
    units = bounds.keep(goal, prep.candidates)
    if dominance.applies(req.options, ranked):
        dominated = req.parts.dominators(ranked).dominated(goal, units)
        units = [u for u in units if u not in dominated or u in prep.hint]
    return replace(prep, candidates=tuple(units))


def landmarks(req: Request, goal: int) -> tuple[int, ...]:
    """The units every tree for ``goal`` uses (sorted)."""
    units, _, _ = req.parts.relevant(goal)
    return tuple(sorted(req.parts.bounds_for(("units",), units).landmarks(goal)))


@overload
def explanations(req: Request, meal: tuple[int, ...]) -> list[tuple[str, Grounding]]: ...
@overload
def explanations(req: Request, meal: tuple[int, ...], alone: Literal[False]) -> Grounding: ...
def explanations(req: Request, meal: tuple[int, ...], alone: bool = True) -> list[tuple[str, Grounding]] | Grounding:
    """For an infeasible answer: each user program alone on the meal's part (does it alone rule
    out every tree?), as (program name, grounding); ``alone=False``: the part with ``req``'s
    programs, as one grounding."""
    units, objects, _ = req.parts.relevant(meal)
    view = req.problem.with_kitchen(o for o in objects if o in req.problem.kitchen)
    if not alone:
        return grounding(view, replace(req.options, units=tuple(units)), goal=meal)
    return [
        (name, grounding(view, replace(req.options, programs=[(name, text)], units=tuple(units)), goal=meal))
        for name, text in req.options.programs
    ]


def reads(options: AspOptions) -> frozenset[str]:
    """The optional fact predicates (``foon2asp.asp.facts.OPTIONAL``, ``input_nodes``) that the
    objectives and the user's programs of ``options`` read."""
    ranked = objectives.ranked(options)
    read = {"neglog"} if "success" in ranked else set()
    if "inputs" in ranked:
        read.add("input_nodes")
    names = mentioned(options.programs)
    if names is None:  # a program that cannot be parsed: write everything, clingo names the error
        return frozenset((*OPTIONAL, "input_nodes"))
    for name in names:
        read.update(FLAG_READS.get(name, (name,)))
    return frozenset(read)


def grounding(
    problem: Problem,
    options: AspOptions,
    units: Iterable[int] | None = None,
    goal: Goals | None = None,
    prepared: Preparation | None = None,
) -> Grounding:
    """The grounding of ``options`` over ``problem``: ``units`` (None: ``options.units``, else the
    viable units), for ``goal`` alone (None: any goal, or the prepared part's goal)."""
    ranked = objectives.ranked(options)
    meal = meal_of(goal) if goal is not None else None
    whole = prepared is None
    if prepared is not None:
        meal = (prepared.goal,)
        units = prepared.candidates
    elif units is None:
        units = options.units if options.units is not None else sorted(problem.viable_units)
    units = tuple(units)
    closed = prepared is not None and not (options.programs or options.threads > 1)
    if prepared is not None:
        entry = "solve_closed" if closed else "solve_prepared"
    else:
        entry = "solve_greedy" if options.heuristic else "solve"
    read = reads(options)
    kinds = ["problem", "objectives"]
    kinds += ["input_nodes"] if "input_nodes" in read else []
    kinds += ["motion_costs"] if "cost" in ranked else []
    kinds += ["ranks"] if options.heuristic else []
    if options.human_steps is not None:
        kinds += ["human_limit"] + (["human_order"] if "success" in ranked and options.human_steps > 0 else [])
    kinds += ["dominated"] if whole and dominance.applies(options, ranked) else []
    kinds += ["substitutes"] if substitute_facts.applies(options) else []
    kinds += ["goal"] if meal is not None else []
    kinds += ["preparation"] if prepared is not None else []
    if options.canonical and not options.heuristic and (whole or options.threads > 1):
        kinds.append("chain")  # the unit order canonical.lp searches the smallest optimal tree in
    own = []
    if prepared is not None and prepared.hint:
        if prepared.bound is not None or (options.opt_strategy or "").startswith("bb"):
            own.append("--heuristic=Domain")  # the hint steers a decision or a search from above
    single = prepared is not None and prepared.bound is None and options.threads == 1
    cut_args = tuple(options.args(own)) if single else ()  # after a loop cut: rounds on one multi-shot control
    if single:
        own.append("--single-shot")  # one solve call: clingo may preprocess as for one shot
    depth = "none" if options.max_depth is None else "bound"
    if "depth" in ranked:
        depth = "first" if ranked[0] == "depth" else "later"
    return Grounding(
        problem=problem,
        options=options,
        entry=entry,
        units=units,
        facts=tuple(kinds),
        leave_out=tuple(p for p in OPTIONAL if p not in read),
        whole_kitchen=whole,
        declare=whole or bool(options.programs),  # prepared.lp reads neither unit/1 nor object/1
        goal=meal,
        args=tuple(options.args(own)),
        single_shot=single,
        cut_args=cut_args,
        prepared=prepared,
        closed=closed,
        driven=prepared is None and options.driven,
        greedy=bool(options.heuristic),
        depth=depth,
        canonical=_canonical(problem, options, units, meal, prepared),
        fallback=options.plain,
    )


def _canonical(
    problem: Problem,
    options: AspOptions,
    units: tuple[int, ...],
    meal: tuple[int, ...] | None,
    prepared: Preparation | None,
) -> str:
    """How the canonical tree is found (:data:`foon2asp.asp.grounding.CANONICAL`)."""
    if prepared is not None:
        return "here" if options.canonical and options.threads > 1 else "hint"
    if not options.canonical or options.heuristic:
        return "none"
    if options.driven:
        return "driver"
    if meal is not None:
        view, part = canonical_problem(problem, meal)
        if units == part and problem.kitchen == view.kitchen:
            return "here"
    return "session"


def session_of(
    problem: Problem,
    options: AspOptions | None = None,
    goal: Goals | None = None,
    prepared: Preparation | None = None,
) -> Session:
    """A session of ``options`` over ``problem`` as :func:`grounding` grounds it: every viable
    (or ``options.units``) unit for any goal, or for ``goal`` alone, or ``prepared``'s part."""
    options = options or AspOptions()
    check("asp", "asp", options)
    return Session(grounding(substitute_facts.prepare(problem, options), options, goal=goal, prepared=prepared))
