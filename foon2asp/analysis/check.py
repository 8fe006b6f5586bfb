"""Checking a task tree from a file: does it exist in the FOON, is it well-founded?

A tree is read as a plan (``(action-name)`` lines and ``;`` comments, as Fast
Downward writes them for a problem of ``export pddl``; see
:mod:`foon2asp.analysis.plans`), as FOON text (units closed by ``//``, in the
official dialect with ids or the ID-less one, as ``solve --format foon|foon-plain``
and the earlier search programs write; a leading ``//`` and ``#`` comment lines
are fine), as FOON JSON (foon_api's ``{"functional_units": [...]}``, ``solve
--format foon-json``) or as foon2asp JSON (the list ``solve --format json``
prints, or one such result).  Each unit is matched to a FOON
unit by :meth:`Unit.key` (motion, set of inputs, set of outputs).

The verdict comes from the independent validator (:mod:`foon2asp.validate`):
the tree is valid iff every unit is in the FOON, every unit fires from the
kitchen using only units of the tree, and the goal is made.  When it is not
valid, :func:`diagnose` names the first problem found walking back from the
goal: an unknown unit, a missing input (nothing in the tree makes it and it
is not in the kitchen), or circular support, with the cycle spelled out as
object -> unit -> object ... back to the start.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from foon2asp.analysis import plans
from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon import foonjson
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.goals import parse_object_text
from foon2asp.foon.loaders import object_from_json
from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.parser import parse_lines
from foon2asp.foon.problem import Problem, required_flags
from foon2asp.foon.safejson import loads as safe_loads
from foon2asp.foon.safetext import lines_of, read_text
from foon2asp.methods.planner import solve_goals
from foon2asp.tree.tasktree import Goals, TaskTree, meal_of, measures
from foon2asp.tree.validate import Validation, check_order, validate


@dataclass
class TreeUnit:
    """One unit as read from the tree file."""

    unit: Unit
    step: int  # 1-based position in the file
    line: int | None  # line in the file (None when not known)


@dataclass
class TreeFile:
    """One tree read from a file: its units and, when the file says, its goal."""

    path: str
    units: list[TreeUnit]
    goal: FoonObject | None = None
    method: str | None = None
    line: int | None = None  # where this tree starts (JSON lists hold several)

    def where(self, tu: TreeUnit) -> str:
        return f"{self.path}:{tu.line}" if tu.line else f"{self.path} step {tu.step}"


@dataclass
class Finding:
    """The first problem of an invalid tree."""

    kind: str  # "unknown-unit" | "missing-input" | "cycle" | "goal-not-made"
    message: str
    #: for a cycle: (object, unit) pairs -- the object is made by the unit, which
    #: needs the next pair's object; the last unit needs the first object
    cycle: list[tuple[int, int]] = field(default_factory=list)
    #: the object that is missing or not made (missing-input, goal-not-made)
    obj: int | None = None
    #: the unit that needs the missing object
    unit: int | None = None


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

    @property
    def meal(self) -> tuple[int, ...]:
        return self.goals or (self.goal,)


# ---------------------------------------------------------------- reading


def _looks_like_json(text: str) -> bool:
    return text.lstrip()[:1] in ("[", "{")


#: the line ``solve --format foon`` writes before each tree (serialize.tree_foon)
_HEADER = re.compile(
    r"^#\s*task tree for (?P<goal>.+) \((?P<method>[^(),]+), (?P<status>[^(),]+), (?P<n>\d+) units?\)\s*$"
)


def _read_foon_tree(text: str, path: str) -> list[TreeFile]:
    """One tree, or one per ``# task tree for GOAL (...)`` line (``solve --format foon``
    for several goals); the goal and method of such a line are kept."""
    lines = lines_of(text)
    starts = [i for i, line in enumerate(lines) if _HEADER.match(line)]
    if not starts or starts[0] != 0 and any(ln.strip() and not ln.startswith("#") for ln in lines[: starts[0]]):
        starts = [0, *starts]
    trees: list[TreeFile] = []
    for k, start in enumerate(starts):
        end = starts[k + 1] if k + 1 < len(starts) else len(lines)
        # blank out the other trees' lines so that line numbers stay those of the file
        part = [ln if start <= i < end else "" for i, ln in enumerate(lines)]
        foon = parse_lines(part, path, strict=True)
        header = _HEADER.match(lines[start])
        goal = method = None
        if header:
            goal = parse_object_text(header["goal"]) or FoonObject.make(header["goal"])
            method = header["method"].strip()
        units = [TreeUnit(u, step, origin[1]) for step, (u, origin) in enumerate(zip(foon.units, foon.origins), 1)]
        if not units and header is None:
            continue
        trees.append(TreeFile(path, units, goal, method, start + 1 if header else None))
    if not trees or not any(t.units for t in trees) and not any(t.goal for t in trees):
        raise InputError("no functional units in the tree file (expected FOON text or foon2asp JSON)", path)
    return trees


def _line_of(text: str, pos: int) -> int:
    return text.count("\n", 0, pos) + 1


def _json_unit(value: object, path: str, line: int, step: int) -> Unit:
    if not isinstance(value, dict) or not isinstance(value.get("motion"), str):
        raise InputError(f"unit {step} is not an object with a 'motion' string", path, line)
    parts = []
    for side in ("inputs", "outputs"):
        items = value.get(side)
        if not isinstance(items, list):
            raise InputError(f"unit {step} has no '{side}' list", path, line)
        parts.append(tuple(object_from_json(o, path, line) for o in items))
    return Unit(" ".join(value["motion"].split()).lower().rstrip("*").strip(), parts[0], parts[1])


def _is_foon_json(data: object) -> bool:
    return isinstance(data, dict) and "functional_units" in data


def _read_foon_json_trees(data: object, path: str) -> list[TreeFile]:
    """FOON JSON (foon_api's schema): one tree, or a list of trees."""
    trees = []
    for doc in data if isinstance(data, list) else [data]:
        foon = foonjson.parse_json(json.dumps(doc), path)
        if not foon.units:
            raise InputError("no functional units in the tree file", path)
        units = [TreeUnit(u, step, None) for step, u in enumerate(foon.units, 1)]
        trees.append(TreeFile(path, units))
    return trees


def _read_json_tree(text: str, path: str) -> list[TreeFile]:
    data = safe_loads(text, path, checked=True)
    if _is_foon_json(data) or (isinstance(data, list) and data and all(_is_foon_json(d) for d in data)):
        return _read_foon_json_trees(data, path)
    results = data if isinstance(data, list) else [data]
    # the line each top-level result starts on, for messages
    starts: list[int] = []
    if isinstance(data, list):
        dec = json.JSONDecoder()
        pos = text.index("[") + 1
        line, counted = 1, 0
        for _ in results:
            while text[pos] in " \t\r\n,":
                pos += 1
            line += text.count("\n", counted, pos)
            counted = pos
            starts.append(line)
            pos = dec.raw_decode(text, pos)[1]
    else:
        starts.append(_line_of(text, len(text) - len(text.lstrip())))
    trees = []
    for result, line in zip(results, starts):
        if not isinstance(result, dict) or not isinstance(result.get("units"), list):
            raise InputError("expected a foon2asp result: an object with a 'units' list", path, line)
        goal = object_from_json(result["goal"], path, line) if result.get("goal") is not None else None
        units = [TreeUnit(_json_unit(u, path, line, i), i, None) for i, u in enumerate(result["units"], 1)]
        method = result.get("method") if isinstance(result.get("method"), str) else None
        trees.append(TreeFile(path, units, goal, method, line))
    if not trees:
        raise InputError("the JSON list holds no task tree", path, 1)
    return trees


def _read_plan(problem: Problem, text: str, path: str) -> list[TreeFile]:
    plan = plans.parse_plan(text, path)
    units = [TreeUnit(unit, step, line) for step, (unit, line) in enumerate(plans.plan_units(problem, plan), 1)]
    method = "plan" if plan.cost is None else f"plan, reported cost {plan.cost:g}"
    return [TreeFile(path, units, method=method)]


def read_trees(path: str | Path, problem: Problem | None = None) -> list[TreeFile]:
    """The tree(s) in ``path``: FOON text (one tree), FOON JSON or foon2asp JSON (one or more),
    or (with ``problem``, whose unit ids the action names carry) a plan."""
    text = read_text(path, "tree")
    if _looks_like_json(text):
        return _read_json_tree(text, str(path))
    if problem is not None and plans.looks_like_plan(text):
        return _read_plan(problem, text, str(path))
    return _read_foon_tree(text, str(path))


# ---------------------------------------------------------------- matching


def unit_index(problem: Problem) -> dict[tuple, int]:
    """FOON unit id by :meth:`Unit.key`."""
    return {u.key(): i for i, u in enumerate(problem.units)}


def nearest_hint(problem: Problem, unit: Unit) -> str:
    """Which objects of ``unit`` the most similar FOON unit (same motion) lacks."""
    ins, outs = set(unit.inputs), set(unit.outputs)
    best, best_score = None, 0
    for i, other in enumerate(problem.units):
        if other.motion != unit.motion:
            continue
        score = len(ins & set(other.inputs)) + len(outs & set(other.outputs))
        if score > best_score:
            best, best_score = i, score
    if best is None:
        known = any(u.motion == unit.motion for u in problem.units)
        return "" if known else f"; no FOON unit has the motion {unit.motion!r}"
    other = problem.units[best]
    extra = [f"input {o}" for o in unit.inputs if o not in set(other.inputs)]
    extra += [f"output {o}" for o in unit.outputs if o not in set(other.outputs)]
    lack = [f"input {o}" for o in other.inputs if o not in ins]
    lack += [f"output {o}" for o in other.outputs if o not in outs]
    path, line = problem.foon.origins[best]
    where = f"{path}:{line}" if path else f"unit {best}"
    parts = []
    if extra:
        parts.append("has " + " | ".join(extra))
    if lack:
        parts.append("lacks " + " | ".join(lack))
    return f"; compared with the nearest FOON unit ({where}) it " + " and ".join(parts) if parts else ""


def infer_goal(problem: Problem, tree: TreeFile, goal_objects: list[FoonObject]) -> int:
    """The goal of a tree file that does not name it, from the units as written.

    The tree's only sink (the one product no unit of the tree needs) wins;
    else a goals-file entry that the tree makes (preferring one no unit of the
    tree needs); else the single product of the last unit that no unit needs
    (the earlier programs write the goal's unit last); else its single product.
    """
    units = [tu.unit for tu in tree.units]
    made = list(dict.fromkeys(o for u in units for o in u.outputs if not o.is_bare()))
    needed = {
        o for u in units for o, f in zip(u.inputs, required_flags(u, problem.utensils, problem.utensil_rule)) if f
    }
    tops = [o for o in made if o not in needed]
    goal_set = set(goal_objects)
    last = [o for o in units[-1].outputs if not o.is_bare()] if units else []
    for pool in (
        tops if len(tops) == 1 else [],
        [o for o in tops if o in goal_set],
        [o for o in made if o in goal_set],
        [o for o in last if o in tops],
        last,
    ):
        pool = list(dict.fromkeys(pool))
        if len(pool) == 1 and pool[0] in problem.foon.object_ids:
            return problem.foon.object_ids[pool[0]]
    hint = ""
    if len(last) == 1 and last[0] not in problem.foon.object_ids:
        hint = f" (the last unit makes {last[0]}, which is not a FOON object)"
    listing = ""
    if 1 < len(tops) <= 10:
        listing = "; it makes " + " | ".join(str(o) for o in tops) + " without using them"
    raise InputError(
        f"cannot tell which object is the goal of this tree{hint}{listing}; use --goal TEXT or --goals FILE",
        tree.path,
    )


# ---------------------------------------------------------------- diagnosis


def _had(problem: Problem, order: list[int]) -> set[int]:
    have = set(problem.kitchen)
    for u in order:
        have.update(problem.products[u])
    return have


def describe_unit(problem: Problem, u: int, tree: TreeFile | None = None, ids: list[int | None] | None = None) -> str:
    """``unit 12 (mix, step 3 at tree.txt:40)``."""
    where = ""
    if tree is not None and ids is not None and u in ids:
        tu = tree.units[ids.index(u)]
        where = f", step {tu.step}" + (f" at line {tu.line}" if tu.line else "")
    return f"unit {u} ({problem.units[u].motion}{where})"


def diagnose(
    problem: Problem, goal: int, units: list[int], validation: Validation, name: Callable[[int], str] | None = None
) -> Finding | None:
    """The first problem of a tree that does not validate, walking back from the goal.

    Every unit that cannot fire lacks a required input; each such input is
    either made by no unit of the tree (a missing input) or only by units
    that cannot fire either, and following those back must close a cycle.
    ``name(u)`` words a unit in messages.
    """
    if validation.valid:
        return None
    name = name or (lambda u: describe_unit(problem, u))
    have = _had(problem, validation.order)
    makers: dict[int, list[int]] = {}
    for u in dict.fromkeys(units):
        for o in problem.products[u]:
            makers.setdefault(o, []).append(u)

    def missing(u: int) -> list[int]:
        return [i for i in problem.required[u] if i not in have]

    done: set[int] = set()

    def edges(obj: int):
        return iter([(u, i) for u in makers.get(obj, []) for i in missing(u)])

    def walk(root: int, needed_by: int | None) -> Finding | None:
        """Depth-first search over objects not had; an object on the path again closes a cycle."""
        if root in done or root in have:
            return None
        if not makers.get(root):
            return _missing(problem, root, needed_by, goal, name)
        path: list[list] = [[root, None]]  # [object, unit being tried for it]
        on_path = {root: 0}
        stack = [edges(root)]
        while stack:
            step = next(stack[-1], None)
            if step is None:
                obj = path.pop()[0]
                stack.pop()
                del on_path[obj]
                done.add(obj)
                continue
            u, nxt = step
            path[-1][1] = u
            if nxt in on_path:
                return _cycle(problem, [(o, uu) for o, uu in path[on_path[nxt] :]], name)
            if nxt in done:
                continue
            if not makers.get(nxt):
                return _missing(problem, nxt, u, goal, name)
            on_path[nxt] = len(path)
            path.append([nxt, None])
            stack.append(edges(nxt))
        return None

    if goal not in have:
        found = walk(goal, None)
        if found:
            return found
    for u in validation.stuck:
        for i in missing(u):
            found = walk(i, u)
            if found:
                return found
    return Finding("goal-not-made", validation.problem or "the tree is not valid", obj=goal)


def _missing(problem: Problem, obj: int, needed_by: int | None, goal: int, name: Callable[[int], str]) -> Finding:
    if needed_by is None:
        return Finding("goal-not-made", f"no unit of the tree makes the goal {problem.objects[goal]}", obj=goal)
    return Finding(
        "missing-input",
        f"missing input: {problem.objects[obj]} is needed by {name(needed_by)} "
        "but is not in the kitchen and no unit of the tree makes it",
        obj=obj,
        unit=needed_by,
    )


def _cycle(problem: Problem, cycle: list[tuple[int, int]], name: Callable[[int], str]) -> Finding:
    steps = []
    for k, (o, u) in enumerate(cycle):
        nxt = cycle[(k + 1) % len(cycle)][0]
        steps.append(f"[{problem.objects[o]}] is made by {name(u)}, which needs [{problem.objects[nxt]}]")
    return Finding("cycle", "circular support: " + "; ".join(steps), list(cycle))


def cycle_lines(problem: Problem, finding: Finding, tree: TreeFile | None = None, ids=None) -> list[str]:
    """The cycle of ``finding`` as indented lines, one object or unit per line."""
    lines = []
    for o, u in finding.cycle:
        lines.append(f"    {problem.objects[o]}")
        lines.append(f"      is made in this tree by {describe_unit(problem, u, tree, ids)}, which needs")
    lines.append(f"    {problem.objects[finding.cycle[0][0]]}   (back to the start)")
    return lines


# ---------------------------------------------------------------- checking


def check_units(
    problem: Problem, goal: int, units: list[int], name: Callable[[int], str] | None = None
) -> tuple[Validation, Finding | None]:
    """Validate FOON unit ids for ``goal`` and explain the first problem."""
    validation = validate(problem, goal, units)
    return validation, diagnose(problem, goal, units, validation, name)


def check_tree(problem: Problem, tree: TreeFile, goal: Goals, index: dict[tuple, int] | None = None) -> Report:
    """Match the units of ``tree`` to the FOON and judge them for ``goal`` (for a meal, a
    tuple of goals: valid when every goal is made; the first goal with a problem is explained)."""
    meal = meal_of(goal)
    if len(meal) > 1:
        reports = [check_tree(problem, tree, g, index) for g in meal]
        first = next((r for r in reports if not r.valid), reports[0])
        first.goals = meal
        first.valid = all(r.valid for r in reports)
        first.order_problem = next((r.order_problem for r in reports if r.order_problem), None)
        known = list(dict.fromkeys(u for u in first.ids if u is not None))
        first.cost = measures(problem, meal, known)
        return first
    goal = meal[0]
    index = index if index is not None else unit_index(problem)
    ids = [index.get(tu.unit.key()) for tu in tree.units]
    unknown = [tu for tu, u in zip(tree.units, ids) if u is None]
    known = list(dict.fromkeys(u for u in ids if u is not None))
    if unknown:
        tu = unknown[0]
        more = f" ({len(unknown)} units are unknown)" if len(unknown) > 1 else ""
        finding = Finding(
            "unknown-unit",
            f"unknown unit: step {tu.step} at {tree.where(tu)} ({tu.unit.motion}) is not in the FOON"
            f"{nearest_hint(problem, tu.unit)}{more}",
        )
        validation = validate(problem, goal, known)
        return Report(tree, goal, ids, False, finding, validation, None, measures(problem, goal, known))
    validation, found = check_units(problem, goal, known, lambda u: describe_unit(problem, u, tree, ids))
    order_problem = check_order(problem, goal, known)
    return Report(tree, goal, ids, validation.valid, found, validation, order_problem, measures(problem, goal, known))


# ---------------------------------------------------------------- output


# ---------------------------------------------------------------- a whole file


def resolve_goal(
    data,
    problem: Problem,
    tree: TreeFile,
    goal_label: str | tuple[str, ...] | None,
    among: list[int] | None = None,
) -> tuple[Goals, str]:
    """The goal (several labels: a meal) and where it came from: ``--goal``, the one of
    ``among`` (``--goals``) the tree makes, the file (JSON result or FOON header), or
    inferred from the units."""
    if isinstance(goal_label, str):
        goal_label = (goal_label,)
    if goal_label:
        meal = meal_of(goals_mod.resolve_goal(data, problem, label) for label in goal_label)
        return (meal if len(meal) > 1 else meal[0]), "--goal"
    if among is not None:
        chosen = _among(problem, tree, among)
        if chosen is not None:
            return chosen, "--goals"
    if tree.goal is not None:
        return goals_mod.goal_id(problem, tree.goal, tree.path, tree.line), "named in the file"
    return infer_goal(problem, tree, [obj for obj, _ in data.goals]), "inferred from the units"


def _among(problem: Problem, tree: TreeFile, among: list[int]) -> int | None:
    """The one goal of ``among`` the tree names or makes (preferring products no unit of it needs)."""
    if tree.goal is not None and problem.foon.object_ids.get(tree.goal) in among:
        return problem.foon.object_ids[tree.goal]
    oid = problem.foon.object_ids
    made = [oid[o] for tu in tree.units for o in tu.unit.outputs if o in oid]
    needed = {oid[o] for tu in tree.units for o in tu.unit.inputs if o in oid}
    wanted = set(among)
    for pool in ([o for o in made if o in wanted and o not in needed], [o for o in made if o in wanted]):
        pool = list(dict.fromkeys(pool))
        if len(pool) == 1:
            return pool[0]
    return None


def check_file(
    data,
    problem: Problem,
    path: str | Path,
    goal_label: str | tuple[str, ...] | None = None,
    optimum: bool = True,
    among: list[int] | None = None,
) -> list[Report]:
    """Check every tree (or plan) in ``path``; with ``optimum`` the ASP optimum is solved for
    each goal (for several ``goal_label``: the meal's optimum).

    ``among`` (``--goals``): each tree's goal is the one of these it makes.
    """
    trees = read_trees(path, problem)
    index = unit_index(problem)
    reports = []
    for tree in trees:
        goal, source = resolve_goal(data, problem, tree, goal_label, among)
        report = check_tree(problem, tree, goal, index)
        report.goal_source = source
        reports.append(report)
    if optimum and reports:
        meals = list(dict.fromkeys(r.meal for r in reports))
        best = dict(zip(meals, solve_goals(problem, meals, "asp", AspOptions())))
        for r in reports:
            r.optimum = best[r.meal]
    return reports
