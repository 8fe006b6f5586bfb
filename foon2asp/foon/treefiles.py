"""Task trees read from files, in every form foon2asp and the earlier programs write.

:func:`read_trees` tells the forms apart: FOON text (one tree per ``# task tree for GOAL
(...)`` header), FOON JSON, foon2asp JSON results (also the JSON lines of ``batch``), unit
lists and plans of classical planners; another file is one error saying what it seems to be
and which forms ``check`` reads.  ``foon2asp export pddl`` names the action of FOON unit ``N`` ``uN-MOTION``
(:func:`action_name`), so a plan (one ``(action-name args...)`` per line, ``;`` comments)
maps back to units by the number alone.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path

from foon2asp.errors import InputError
from foon2asp.foon import foonjson, unitlist
from foon2asp.foon.foonjson import object_from_json, unit_from_json
from foon2asp.foon.goals import parse_object_text
from foon2asp.foon.model import FoonObject, Unit
from foon2asp.foon.parser import parse_lines
from foon2asp.foon.problem import Problem
from foon2asp.foon.reading import first_line, line_numbers, lines_of, loads, located, read_text


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
    #: what the reader skipped or merged (one line each, naming the file and the unit)
    warnings: list[str] = field(default_factory=list)
    #: what a foon2asp result says proved it (``proven_by``), and the witness of a ``bounds`` proof
    proven_by: str | None = None
    landmarks: list[int] | None = None
    landmark_sets: list[list[int]] = field(default_factory=list)
    landmark_cases: dict | None = None
    derivation_level: int | None = None

    def where(self, tu: TreeUnit) -> str:
        return f"{self.path}:{tu.line}" if tu.line else f"{self.path} step {tu.step}"


#: one plan step: ``(name args...)``, optionally ``N: (name ...) [cost]`` as some planners print
_STEP = re.compile(r"^\s*(?:\d+(?:\.\d+)?\s*:\s*)?\(\s*([^\s()]+)([^()]*)\)\s*(?:\[[^\]]*\])?\s*$")
_ACTION = re.compile(r"^u(\d+)(?:-|$)")
_COST = re.compile(r";\s*cost\s*=\s*(\d+(?:\.\d+)?)")


def _slug(text: str) -> str:
    """``text`` as a PDDL name part: lower-case letters, digits and single dashes."""
    out = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")
    return out or "unit"


def action_name(problem: Problem, u: int) -> str:
    """The PDDL action of FOON unit ``u``: ``u<id>-<motion>`` (the id alone maps it back)."""
    return f"u{u}-{_slug(problem.units[u].motion)}"


def unit_of_action(name: str) -> int | None:
    """The FOON unit id an exported action name stands for (None: not such a name)."""
    m = _ACTION.match(name.strip().lower())
    return int(m.group(1)) if m else None


def looks_like_plan(text: str) -> bool:
    """Does ``text`` look like a plan file: ``(name ...)`` lines and ``;`` comments only?"""
    steps = [line for line in map(str.strip, text.splitlines()) if line and not line.startswith(";")]
    return bool(steps) and all(_STEP.match(line) for line in steps)


#: the line ``solve --format foon`` writes before each tree (serialize.tree_foon)
_HEADER = re.compile(
    r"^#\s*task tree for (?P<goal>.+) \((?P<method>[^(),]+), (?P<status>[^(),]+), (?P<n>\d+) units?\)\s*$"
)


def _read_foon_tree(text: str, path: str) -> list[TreeFile]:
    """One tree, or one per ``# task tree for GOAL (...)`` line (``solve --format foon``
    for several goals); the goal and method of such a line are kept."""
    lines = list(lines_of(text))
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
        raise InputError(
            "no functional units in the tree file (expected FOON text, FOON JSON, foon2asp JSON or a unit list)", path
        )
    return trees


def _read_foon_json_trees(docs: list, path: str) -> list[TreeFile]:
    """FOON JSON (foon_api's schema): one tree per document."""
    trees = []
    for doc in docs:
        foon = foonjson.read_official(doc, path)
        if not foon.units:
            raise InputError("no functional units in the tree file", path)
        trees.append(TreeFile(path, [TreeUnit(u, step, None) for step, u in enumerate(foon.units, 1)]))
    return trees


def _read_unit_list_trees(text: str, path: str, strict: bool, parsed: tuple[object, list[int]]) -> list[TreeFile]:
    """The unit-list form: one tree, or one per inner list; each unit's step is its number in its list."""
    trees, warnings = unitlist.read_unit_lists(text, path, strict, parsed)
    out = [TreeFile(path, [TreeUnit(u, k, line) for u, k, line in units], line=start) for units, start in trees]
    out = [t for t in out if t.units] or out[:1]
    if not any(t.units for t in out):
        raise InputError("no usable unit in the tree file (every unit was skipped; see the warnings)", path)
    out[0].warnings = warnings
    return out


def _result_tree(result: object, path: str, line: int, expected: str) -> TreeFile:
    """The tree of one foon2asp result (``solve --format json``, a line of ``batch``) at ``line``;
    ``expected`` says what the file should hold when ``result`` is no result."""
    if not isinstance(result, dict) or not isinstance(result.get("units"), list):
        raise InputError(f"expected {expected}", path, line)
    goal = object_from_json(result["goal"], path, line) if result.get("goal") is not None else None
    units = [TreeUnit(unit_from_json(u, path, f"unit {i}", line), i, None) for i, u in enumerate(result["units"], 1)]
    method = result.get("method") if isinstance(result.get("method"), str) else None
    found = TreeFile(path, units, goal, method, line)
    if isinstance(result.get("proven_by"), str):
        found.proven_by = result["proven_by"]
    marks = result.get("landmarks")
    if marks is not None:
        if not isinstance(marks, list) or not all(isinstance(u, int) and not isinstance(u, bool) for u in marks):
            raise InputError("'landmarks' must be a list of unit ids (whole numbers)", path, line)
        found.landmarks = marks
    sets = result.get("landmark_sets", [])
    ids = lambda s: isinstance(s, list) and all(isinstance(u, int) and not isinstance(u, bool) for u in s)  # noqa: E731
    if not isinstance(sets, list) or not all(ids(s) for s in sets):
        raise InputError("'landmark_sets' must be a list of lists of unit ids (whole numbers)", path, line)
    found.landmark_sets = sets
    cases = result.get("landmark_cases")
    if cases is not None and not isinstance(cases, dict):
        raise InputError("'landmark_cases' must be an object with 'object' and 'cases'", path, line)
    found.landmark_cases = cases
    level = result.get("derivation_level")
    if level is not None and (not isinstance(level, int) or isinstance(level, bool)):
        raise InputError("'derivation_level' must be a whole number", path, line)
    found.derivation_level = level
    return found


def _read_json_tree(text: str, path: str, strict: bool = False) -> list[TreeFile]:
    data, tops = located(text, path, checked=True)
    if unitlist.is_unit_list(data) or unitlist.is_unit_lists(data):
        return _read_unit_list_trees(text, path, strict, (data, tops))
    results = data if isinstance(data, list) else [data]
    if results and all(foonjson.is_foon_json(d) for d in results):
        return _read_foon_json_trees(results, path)
    # the line each result starts on, for messages
    starts = line_numbers(text, tops) if isinstance(data, list) else [first_line(text)]
    expected = (
        "a foon2asp result (an object with a 'units' list) or a list of units {input_nodes, motion_node, output_nodes}"
    )
    trees = [_result_tree(result, path, line, expected) for result, line in zip(results, starts)]
    if not trees:
        raise InputError("the JSON list holds no task tree", path, 1)
    return trees


#: the key of the first line of a results file of ``batch`` (foon2asp.batch.results_file)
RESULTS_HEADER = "foon2asp_results"


def is_json_lines(text: str) -> bool:
    """Is ``text`` JSON lines: a first line that is a whole JSON object, and more after it?"""
    first, _, rest = text.lstrip().partition("\n")
    if not first.startswith("{") or not rest.strip():
        return False
    try:
        return isinstance(json.loads(first), dict)
    except ValueError:
        return False


def _read_json_lines(text: str, path: str) -> list[TreeFile]:
    """The trees of a results file of ``batch``: one result per line, the header line skipped."""
    trees = []
    for number, line in enumerate(lines_of(text), 1):
        if not line.strip():
            continue
        try:
            value = loads(line, path, checked=True)
        except InputError as err:  # located in the line alone: move it to the line of the file
            raise InputError(err.message, path, number, err.column) from None
        if isinstance(value, dict) and RESULTS_HEADER in value:
            continue
        trees.append(_result_tree(value, path, number, "a result of 'batch' (an object with a 'units' list)"))
    if not trees:
        raise InputError("the results file holds no result yet (only the header of 'batch')", path)
    return trees


#: what ``check`` reads, for the message about a file it does not
TREE_FORMATS = (
    "check reads FOON text, FOON JSON, foon2asp JSON ('solve --format json', 'batch' results), the unit lists"
    " of generated trees ('solve --format units-json'), plans for 'export pddl' (with --data or --foon) and"
    " schedules ('schedule --format json')"
)


def _looks_like_foon(text: str) -> bool:
    """Does the first line of ``text`` that is neither blank nor a ``#`` comment start a FOON text line?"""
    for line in lines_of(text):
        body = line.strip()
        if not body or body.startswith("#"):
            continue
        tab = line.find("\t")
        return line.startswith("//") or line[:1] in "OSM" and tab > 0 and (tab == 1 or line[1:tab].isdecimal())
    return True  # empty: the FOON reader says there are no units


def _what_it_is(text: str, problem: Problem | None) -> str:
    """What a file that is no task tree seems to be, as a phrase (or "")."""
    head = text.lstrip()[:2000].lower()
    if "(define (domain" in head or "(define (problem" in head:
        return "a PDDL domain or problem ('export pddl' writes them; a planner's plan for them is a tree)"
    if problem is None and looks_like_plan(text):
        return "a plan (checked with --data or --foon: the FOON its actions come from)"
    if head.startswith("<"):
        return "an SVG, HTML or XML document (a drawing or a report)"
    first = head.partition("\n")[0]
    if "," in first and "\t" not in first:
        return "a CSV table"
    return ""


def not_a_tree(text: str, path: str, problem: Problem | None = None) -> InputError:
    """The one-line error for a file that is no task tree: what it seems to be and what ``check`` reads."""
    what = _what_it_is(text, problem)
    return InputError(f"not a task tree{': ' + what if what else ''}; {TREE_FORMATS}", path)


def _read_plan(problem: Problem, text: str, path: str) -> list[TreeFile]:
    """A plan (:func:`looks_like_plan`): per step the FOON unit its action names; an unknown
    action (or an id whose motion does not match, a plan for another FOON) becomes a unit that
    matches nothing in the FOON, so ``check`` reports it as unknown, with its line."""
    units: list[TreeUnit] = []
    cost = None
    for number, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if line.startswith(";"):
            m = _COST.search(line)
            cost = float(m.group(1)) if m else cost
        elif line:
            step = _STEP.match(line)
            assert step is not None  # looks_like_plan matched every step
            name = step.group(1).lower()
            u = unit_of_action(name)
            if u is not None and 0 <= u < len(problem.units) and action_name(problem, u) == name:
                units.append(TreeUnit(problem.units[u], len(units) + 1, number))
            else:
                units.append(TreeUnit(Unit(f"action {name}", (), ()), len(units) + 1, number))
    method = "plan" if cost is None else f"plan, reported cost {cost:g}"
    return [TreeFile(path, units, method=method)]


def read_trees(path: str | Path, problem: Problem | None = None, strict: bool = False) -> list[TreeFile]:
    """The tree(s) in ``path``: FOON text (one tree), FOON JSON, foon2asp JSON or unit lists (one
    or more), or (with ``problem``, whose unit ids the action names carry) a plan.  ``strict``: a
    unit of a unit list that would be skipped with a warning is an error."""
    text = read_text(path, "tree")
    if is_json_lines(text):
        return _read_json_lines(text, str(path))
    if text.lstrip()[:1] in ("[", "{"):
        return _read_json_tree(text, str(path), strict)
    if problem is not None and looks_like_plan(text):
        return _read_plan(problem, text, str(path))
    if not _looks_like_foon(text):
        raise not_a_tree(text, str(path), problem)
    return _read_foon_tree(text, str(path))
