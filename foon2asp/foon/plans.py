"""Plans from classical planners, read back as task trees.

``foon2asp export pddl`` names the action of FOON unit ``N`` ``uN-MOTION``
(:func:`action_name`), so a plan (one ``(action-name args...)`` per line, ``;``
comments, as Fast Downward writes it) maps back to units by the number alone and
``check`` judges it exactly as a tree.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from foon2asp.errors import InputError
from foon2asp.foon.model import Unit
from foon2asp.foon.problem import Problem

#: one plan step: ``(name args...)``, optionally ``N: (name ...) [cost]`` as some planners print
_STEP = re.compile(r"^\s*(?:\d+(?:\.\d+)?\s*:\s*)?\(\s*([^\s()]+)([^()]*)\)\s*(?:\[[^\]]*\])?\s*$")
_ACTION = re.compile(r"^u(\d+)(?:-|$)")
_COST = re.compile(r";\s*cost\s*=\s*(\d+(?:\.\d+)?)")


def slug(text: str) -> str:
    """``text`` as a PDDL name part: lower-case letters, digits and single dashes."""
    out = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")
    return out or "unit"


def action_name(problem: Problem, u: int) -> str:
    """The PDDL action of FOON unit ``u``: ``u<id>-<motion>`` (the id alone maps it back)."""
    return f"u{u}-{slug(problem.units[u].motion)}"


def unit_of_action(name: str) -> int | None:
    """The FOON unit id an exported action name stands for (None: not such a name)."""
    m = _ACTION.match(name.strip().lower())
    return int(m.group(1)) if m else None


@dataclass
class PlanStep:
    action: str
    line: int
    unit: int | None


@dataclass
class Plan:
    path: str
    steps: list[PlanStep] = field(default_factory=list)
    #: the cost the planner reported in a ``; cost = N`` comment, if any
    cost: float | None = None


def looks_like_plan(text: str) -> bool:
    """Does ``text`` look like a plan file: ``(name ...)`` lines and ``;`` comments only?"""
    steps = [line for line in map(str.strip, text.splitlines()) if line and not line.startswith(";")]
    return bool(steps) and all(_STEP.match(line) for line in steps)


def parse_plan(text: str, path: str) -> Plan:
    """The steps and reported cost of a plan file (bad lines are an InputError naming the line)."""
    plan = Plan(path)
    for number, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith(";"):
            m = _COST.search(line)
            if m:
                plan.cost = float(m.group(1))
            continue
        m = _STEP.match(line)
        if not m:
            raise InputError(f"not a plan step (expected '(action-name)'): {line[:60]!r}", path, number)
        name = m.group(1).lower()
        plan.steps.append(PlanStep(name, number, unit_of_action(name)))
    return plan


def plan_units(problem: Problem, plan: Plan) -> list[tuple[Unit, int]]:
    """``(unit, line)`` per step: the FOON unit the action names; an unknown action (or an id
    whose motion does not match, a plan for another FOON) becomes a unit that matches nothing
    in the FOON, so ``check`` reports it as unknown, with its line."""
    out = []
    for s in plan.steps:
        if s.unit is not None and 0 <= s.unit < len(problem.units) and action_name(problem, s.unit) == s.action:
            out.append((problem.units[s.unit], s.line))
        else:
            out.append((Unit(f"action {s.action}", (), ()), s.line))
    return out
