"""Small hand-made FOONs and a brute-force oracle for tests.

``run_cli`` runs a command in this process, ``demo_copy`` copies the demo data;
``build`` makes a Problem from a compact description; ``brute_force`` tries
every subset of the goal's candidate units and keeps those the independent
validator accepts, so tests can compare the solver with exhaustive search.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import pytest

from foon2asp.errors import InputError
from foon2asp.foon.model import Foon, FoonObject, Unit
from foon2asp.foon.problem import Problem, product_outputs
from foon2asp.tree.tasktree import measures
from foon2asp.tree.validate import validate


def obj(label: str, *states: str, contains=(), inside=None) -> FoonObject:
    """obj("tomato", "chopped", inside="bowl")"""
    return FoonObject.make(label, states, contains, inside)


def as_obj(x) -> FoonObject:
    return x if isinstance(x, FoonObject) else FoonObject.make(x, ["s"]) if isinstance(x, str) else obj(*x)


def build(units, kitchen, rates=None, utensils=(), utensil_rule="starter") -> Problem:
    """``units``: list of (motion, inputs, outputs); objects as FoonObject or
    plain strings (a string ``"a"`` is the object labelled a with state "s")."""
    foon = Foon()
    for motion, ins, outs in units:
        foon.add_unit(Unit(motion, tuple(as_obj(i) for i in ins), tuple(as_obj(o) for o in outs)))
    return Problem(foon, [as_obj(k) for k in kitchen], dict(rates or {}), frozenset(utensils), utensil_rule)


def goal_id(problem: Problem, x) -> int:
    return problem.foon.object_ids[as_obj(x)]


def brute_force(problem: Problem, goal: int, limit: int = 16) -> list[tuple[int, ...]]:
    """Every valid tree (as a sorted tuple of unit ids) that is minimal by inclusion
    is not required: all valid subsets of the units are returned."""
    n = len(problem.units)
    assert n <= limit, f"brute force over {n} units is too slow"
    target = problem.objects[goal]
    return [subset for subset, had in _fireable(problem) if target in had]


_FIREABLE: dict[tuple, list[tuple[tuple[int, ...], frozenset[FoonObject]]]] = {}


def _fireable(problem: Problem) -> list[tuple[tuple[int, ...], frozenset[FoonObject]]]:
    """Every subset of the units whose units all fire (as the validator judges: it is a
    valid tree for each object it has), with the objects it has; once per FOON, kitchen
    and utensil rule (tests build the same small FOON for several objectives)."""
    key = (
        tuple(problem.units),
        frozenset(problem.kitchen_items),
        frozenset(problem.utensils),
        problem.utensil_rule,
    )
    if key not in _FIREABLE:
        n, probe = len(problem.units), problem.objects[0]
        out = []
        for k in range(n + 1):
            for subset in itertools.combinations(range(n), k):
                verdict = validate(problem, probe, list(subset))
                if not verdict.stuck:  # every unit fired (the probe had or not)
                    had = set(problem.kitchen_items).union(*(product_outputs(problem.units[u]) for u in subset))
                    out.append((subset, frozenset(had)))
        if len(_FIREABLE) > 64:
            _FIREABLE.clear()
        _FIREABLE[key] = out
    return _FIREABLE[key]


def against_brute_force(problem: Problem, goals, solve):
    """(goal, brute-force trees, answers) for each of ``goals`` that has a tree; ``solve(goal)``
    gives the solver's answers, and a goal without a tree must be answered ``unreachable``."""
    for g in goals:
        trees = brute_force(problem, g)
        found = solve(g)
        if not trees:
            assert found[0].status == "unreachable", (g, found[0].status)
            continue
        yield g, trees, found


def best(problem: Problem, goal: int, key) -> tuple[float, list[tuple[int, ...]]]:
    """The best value of ``key(measures)`` over all valid trees, and the trees reaching it."""
    trees = brute_force(problem, goal)
    if not trees:
        return math.inf, []
    scored = [(key(measures(problem, goal, list(t))), t) for t in trees]
    top = min(s for s, _ in scored)
    return top, [t for s, t in scored if s == top]


def goal_part(problem: Problem, goal: int, limit: int = 12) -> tuple[Problem, int] | None:
    """The goal's relevant units as a FOON of their own (same kitchen, rates, utensils) and the
    goal's id there; None when the goal has no part or more than ``limit`` units (brute force)."""
    part = sorted(problem.relevant_units(goal)) if goal in problem.derivable else []
    if not part or len(part) > limit:
        return None
    foon = Foon()
    for u in part:
        foon.add_unit(problem.units[u])
    sub = Problem(foon, problem.kitchen_items, problem.motion_rates, problem.utensils)
    return sub, sub.foon.object_ids[problem.objects[goal]]


def file_error(path: Path, text: str, read) -> InputError:
    """The InputError ``read(path)`` raises once ``path`` holds ``text``."""
    path.write_text(text)
    with pytest.raises(InputError) as err:
        read(path)
    return err.value


def one_line_error(res, code=2):
    """The one ``foon2asp: error:`` line of a CLI result that exited with ``code``."""
    assert res.exit_code == code, (res.exit_code, res.output, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, res.stderr
    assert lines[0].startswith("foon2asp: error: ")
    assert "Traceback" not in res.stderr
    return lines[0]


REPO = Path(__file__).resolve().parent.parent
DEMO = REPO / "data"

#: commands that read data: the demo data unless the test names some (there is no silent default)
_DATA_COMMANDS = {"solve", "check", "compare", "reachable", "missing", "query", "batch", "facts", "objects"}


def run_cli(*args):
    """``foon2asp ARGS`` in this process (on the demo data when a data command names none)."""
    from click.testing import CliRunner

    from foon2asp.cli.main import main

    argv = [str(a) for a in args]
    if argv and argv[0] in _DATA_COMMANDS and not {"--data", "--foon"} & set(argv):
        argv += ["--data", "demo"]
    return CliRunner().invoke(main, argv)


def demo_copy(tmp_path: Path, *leave_out: str) -> Path:
    """A copy of the demo data in ``tmp_path/data`` without the files ``leave_out`` names."""
    d = tmp_path / "data"
    d.mkdir()
    for f in DEMO.iterdir():
        if f.is_file() and f.name not in leave_out:
            (d / f.name).write_bytes(f.read_bytes())
    return d


def real_choice(problem: Problem, goal: int, units) -> bool:
    """Has ``goal`` more than one minimal tree? By the validator alone: some unit of its tree
    ``units`` can be done without (every other unit of the FOON fired, the goal is still made),
    so a minimal tree without it exists beside one with it."""
    from foon2asp.tree.validate import validate

    every = range(len(problem.units))
    for u in set(units):
        fired = validate(problem, goal, [v for v in every if v != u]).order
        if validate(problem, goal, fired).valid:
            return True
    return False


def witness_problem(problem, tree, objective: str = "units", landmarks=None, units=None):
    """``bounds_proof`` of a tree (anything with ``goal``, ``units`` and the witness fields of a
    TaskTree) with its whole witness; ``landmarks``, ``units``: claimed instead of the tree's
    (a forged witness)."""
    from foon2asp.tree.validate import bounds_proof

    return bounds_proof(
        problem,
        tree.goal,
        tree.units if units is None else units,
        tree.landmarks if landmarks is None else landmarks,
        tree.landmark_sets or [],
        objective,
        tree.landmark_cases,
        tree.derivation_level,
    )
