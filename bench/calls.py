"""Where the time of answering goals goes: each clingo call by kind (creating a control,
parsing programs, grounding, solving) and the Python around them, summed over every goal of a
data set and per call.

    python bench/calls.py --shared ../shared [--data foon] [--preset hard-4k] [--objective units]

The calls are timed at clingo's own Python API (``clingo.Control`` and the program builder),
so the script measures whichever foon2asp the interpreter running it imports: run it with
another version's Python to compare two versions on the same machine, e.g.
``../baseline/.venv/bin/python bench/calls.py``.  The goals are answered as ``batch
--workers 1`` answers them, in one process, without the results file.

Prints one markdown row per data set: the goals, the routes taken, then for each kind of call
the seconds summed, the calls and the milliseconds per call, and the Python rest.
"""

from __future__ import annotations

import argparse
import collections
import importlib
import sys
import time
from collections.abc import Callable
from pathlib import Path

import clingo
import clingo.ast

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import foon2asp  # noqa: E402
from foon2asp.asp.options import AspOptions  # noqa: E402

#: kind of call -> the clingo API functions it is made of (the statements a program builder adds
#: count as part of parsing, and a solve handle's waiting as part of its solve call)
CALLS: dict[str, list[tuple[type, str]]] = {
    "create": [(clingo.Control, "__init__")],
    "parse": [(clingo.Control, "add"), (clingo.Control, "load"), (clingo.ast.ProgramBuilder, "add")],
    "ground": [(clingo.Control, "ground")],
    "solve": [(clingo.Control, "solve"), (clingo.SolveHandle, "wait"), (clingo.SolveHandle, "get")],
}


def timed(spent: dict[str, float], count: collections.Counter, kind: str, fn: Callable, counted: bool) -> Callable:
    """``fn`` whose time is added to ``spent[kind]`` and, when ``counted``, whose calls are counted."""

    def wrapper(*args, **kwargs):
        t0 = time.perf_counter()
        try:
            return fn(*args, **kwargs)
        finally:
            spent[kind] += time.perf_counter() - t0
            count[kind] += counted

    return wrapper


def measure(
    problem, goals, objective: tuple[str, ...]
) -> tuple[dict[str, float], collections.Counter, dict, float, int]:
    """Answer ``goals``; the seconds and calls of each kind, the routes, the wall seconds and the
    goals clingo decided together (one call for many)."""
    spent: dict[str, float] = collections.defaultdict(float)
    count: collections.Counter = collections.Counter()
    originals = [(owner, name, getattr(owner, name)) for kinds in CALLS.values() for owner, name in kinds]
    for kind, functions in CALLS.items():
        for owner, name in functions:
            # a statement handed to the program builder is part of one parse, and waiting on a
            # solve handle part of its solve call, not calls of their own
            counted = owner not in (clingo.ast.ProgramBuilder, clingo.SolveHandle)
            setattr(owner, name, timed(spent, count, kind, getattr(owner, name), counted))
    runner_mod = importlib.import_module("foon2asp.methods.runner")
    try:
        run = runner_mod.GoalRunner("asp", problem, AspOptions(objective=objective))
        t0 = time.perf_counter()
        each = getattr(run, "each", None)  # planned ahead, as batch plans them (where the version does)
        trees = list(each(goals) if each is not None else map(run, goals))
        wall = time.perf_counter() - t0
    finally:
        for owner, name, fn in originals:
            setattr(owner, name, fn)
    together = sum(bool(t.stats.get("plan", {}).get("decided_with")) for t in trees)
    return spent, count, dict(run.counts), wall, together


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--shared", default=str(HERE.parent.parent / "shared"))
    ap.add_argument("--data", action="append", default=[], help="a folder under --shared (default: foon)")
    ap.add_argument("--preset", action="append", default=[], help="a synthetic preset (bench/synth.py)")
    ap.add_argument("--objective", default="units")
    args = ap.parse_args()
    objective = tuple(args.objective.split(","))
    cases = []
    for name in args.data or ([] if args.preset else ["foon"]):
        kb = foon2asp.load(str(Path(args.shared) / name))
        cases.append((name, kb.problem, kb.goal_ids("all-objects")))
    for name in args.preset:
        from synth import preset

        syn = preset(name)
        problem = syn.problem()
        cases.append((name, problem, [problem.foon.object_ids[g] for g in syn.goals]))
    version = Path(foon2asp.__file__).resolve().parent.parent
    print(f"foon2asp from {version}; objective {args.objective}; s summed (calls, ms per call)")
    print()
    print("| data | goals | routes | " + " | ".join(CALLS) + " | Python | wall s |")
    print("|---|---:|---|" + "---:|" * (len(CALLS) + 2))
    for name, problem, goals in cases:
        spent, count, routes, wall, _ = measure(problem, goals, objective)
        taken = ", ".join(f"{k} {v}" for k, v in routes.items() if v)
        cells = " | ".join(
            f"{spent[k]:.2f} ({count[k]}, {1000 * spent[k] / count[k]:.2f})" if count[k] else "0" for k in CALLS
        )
        rest = wall - sum(spent.values())
        print(f"| {name} | {len(goals)} | {taken} | {cells} | {rest:.2f} | {wall:.2f} |")


if __name__ == "__main__":
    main()
