"""A FOON problem as PDDL: a delete-free STRIPS domain and a problem.

The mapping and what a plan means: docs/formats.md, "PDDL".
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from foon2asp.asp.constraints import ConstraintSpec, motion_name, normalise
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem, walk_back
from foon2asp.foon.treefiles import action_name
from foon2asp.tree.weights import unit_weight

#: objectives that PDDL can state (action costs per unit; "units" is plan length)
PDDL_OBJECTIVES = ("units", "success", "inputs", "cost")


@dataclass
class PddlTask:
    """The two PDDL texts and what their names stand for."""

    domain: str
    problem: str
    #: action name -> FOON unit id
    actions: dict[str, int] = field(default_factory=dict)
    #: constant name -> FOON object id
    objects: dict[str, int] = field(default_factory=dict)
    goals: tuple[int, ...] = ()


def exported_units(problem: Problem, goals: Iterable[int], spec: ConstraintSpec | None = None) -> list[int]:
    """The units a tree for ``goals`` can use once the filters of ``spec`` (forbidden motions and
    objects, as the ASP constraints read them) removed units; raises InputError for constraints
    that are not unit filters."""
    spec = spec or ConstraintSpec()
    given = {
        "--constraint": spec.files or spec.extra,
        "--rule": spec.rules,
        "--require-motion": spec.require_motion,
        "--require-object": spec.require_object,
        "--max-units": spec.max_units is not None,
    }
    bad = [flag for flag, on in given.items() if on]
    if bad:
        raise InputError(
            f"{', '.join(bad)} cannot be exported to PDDL (only --forbid-motion and --forbid-object, which remove units)"
        )
    motions = {motion_name(m) for m in spec.forbid_motion}
    labels = {normalise(x) for x in spec.forbid_object}
    keep = [
        u
        for u, unit in enumerate(problem.units)
        if unit.motion not in motions and not any(o.label in labels for o in (*unit.inputs, *unit.outputs))
    ]
    _, unit_level = problem.derivation_levels(keep)  # fires from the kitchen without the removed units
    producers: dict[int, list[int]] = {}
    for u in sorted(unit_level):
        for o in problem.products[u]:
            producers.setdefault(o, []).append(u)
    units, _, _ = walk_back(list(goals), problem.kitchen, producers, problem.required)
    return sorted(units)


def _comment(text: object) -> str:
    return " ".join(str(text).split())


def export(
    problem: Problem,
    goals: Iterable[int],
    objective: str = "units",
    spec: ConstraintSpec | None = None,
    name: str = "foon",
) -> PddlTask:
    """Domain and problem PDDL for making every goal of ``goals``; raises InputError for an
    objective or constraint PDDL cannot state."""
    goals = tuple(dict.fromkeys(goals))
    if not goals:
        raise InputError("no goal to export")
    if objective not in PDDL_OBJECTIVES:
        raise InputError(
            f"objective {objective!r} cannot be exported to PDDL (have {', '.join(PDDL_OBJECTIVES)}; "
            "a lexicographic list cannot be one action cost)"
        )
    units = exported_units(problem, goals, spec)
    costs = objective != "units"
    objs = sorted({*goals, *(o for u in units for o in (*problem.required[u], *problem.products[u]))})
    const = {o: f"o{o}" for o in objs}
    actions = {action_name(problem, u): u for u in units}

    cost_of = unit_weight(problem, objective)
    goal_lines = [f"; goal {const[g]}: {_comment(problem.objects[g])}" for g in goals]
    table = [f";   {const[o]:<8} {_comment(problem.objects[o])}" for o in objs]
    what = {
        "units": "plan length = number of units",
        "success": "action cost = round(-1000 ln p) of the unit's motion success rate p",
        "inputs": "action cost = the unit's number of input nodes",
        "cost": "action cost = the unit's motion cost in hundredths (--motion-cost)",
    }[objective]
    head = [
        "; written by foon2asp export pddl: a FOON problem as delete-free STRIPS",
        f"; objective: {objective} ({what})",
        "; action u<N>-<motion> is FOON unit N (unit ids as in 'foon2asp facts')",
        *goal_lines,
    ]
    dom = head + [
        "; objects (constants):",
        *table,
        f"(define (domain {name})",
        "  (:requirements :strips" + (" :action-costs" if costs else "") + ")",
        "  (:constants " + " ".join(const[o] for o in objs) + ")",
        "  (:predicates (have ?o))",
    ]
    if costs:
        dom.append("  (:functions (total-cost) - number)")
    for act, u in actions.items():
        unit = problem.units[u]
        path, line = problem.foon.origins[u] if u < len(problem.foon.origins) else (None, None)
        where = f" ({path}:{line})" if path else ""
        dom.append(f"  ; unit {u}: {_comment(unit.motion)}{where}")
        dom.append(f"  (:action {act}")
        dom.append("    :parameters ()")
        req = problem.required[u]
        if req:
            dom.append("    :precondition (and " + " ".join(f"(have {const[o]})" for o in req) + ")")
        effects = [f"(have {const[o]})" for o in problem.products[u]]
        if costs:
            effects.append(f"(increase (total-cost) {cost_of(u)})")
        dom.append("    :effect (and " + " ".join(effects) + "))")
    dom.append(")")
    init = [f"(have {const[o]})" for o in objs if o in problem.kitchen]
    if costs:
        init.append("(= (total-cost) 0)")
    prob = head + [
        "; objects:",
        *table,
        f"(define (problem {name}-task)",
        f"  (:domain {name})",
        "  (:init",
        *[f"    {atom}" for atom in init],
        "  )",
        "  (:goal (and " + " ".join(f"(have {const[g]})" for g in goals) + "))",
    ]
    if costs:
        prob.append("  (:metric minimize (total-cost))")
    prob.append(")")
    return PddlTask("\n".join(dom) + "\n", "\n".join(prob) + "\n", actions, {c: o for o, c in const.items()}, goals)
