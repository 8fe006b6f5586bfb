"""Where the time of answering goals goes: planning (preparation), writing facts, clingo parsing
(``Control.add``/``load``), grounding and solving, summed over every goal of a data set.

    python bench/calls.py --shared ../shared [--data foon] [--preset hard-4k] [--objective units]

Prints one markdown row per data set: goals, the routes taken, and the seconds of each phase.
The phases are timed by wrapping the functions that do them, so the whole run is what
``batch --workers 1`` does in one process, minus the results file.
"""

from __future__ import annotations

import argparse
import collections
import importlib
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import foon2asp  # noqa: E402
from foon2asp.asp import control, grounding, session  # noqa: E402
from foon2asp.asp.options import AspOptions  # noqa: E402

plan_mod = importlib.import_module("foon2asp.methods.plan")
runner_mod = importlib.import_module("foon2asp.methods.runner")

PHASES = ("plan", "facts", "parse", "ground", "solve")


def timed(spent: dict[str, float], phase: str, fn):
    """``fn`` whose time is added to ``spent[phase]`` (not twice when it calls itself)."""
    depth = [0]

    def wrapper(*args, **kwargs):
        depth[0] += 1
        t0 = time.perf_counter()
        try:
            return fn(*args, **kwargs)
        finally:
            depth[0] -= 1
            if depth[0] == 0:
                spent[phase] += time.perf_counter() - t0

    return wrapper


def measure(problem, goals, objective: tuple[str, ...]) -> tuple[dict[str, float], dict[str, int], float]:
    spent: dict[str, float] = collections.defaultdict(float)
    patches = [
        (runner_mod, "plan", plan_mod.plan, "plan"),
        (session, "fact_programs", grounding.fact_programs, "facts"),
        (control.Control, "add", control.Control.add, "parse"),
        (control.Control, "load", control.Control.load, "parse"),
        (control.Control, "ground", control.Control.ground, "ground"),
        (control.Control, "solve", control.Control.solve, "solve"),
    ]
    for owner, name, fn, phase in patches:
        setattr(owner, name, timed(spent, phase, fn))
    try:
        run = runner_mod.GoalRunner("asp", problem, AspOptions(objective=objective))
        t0 = time.perf_counter()
        for g in goals:
            run(g)
        wall = time.perf_counter() - t0
    finally:
        for owner, name, fn, _ in patches:
            setattr(owner, name, fn)
    return spent, dict(run.counts), wall


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
    print(f"objective {args.objective}; seconds summed over the goals")
    print()
    print("| data | goals | routes | " + " | ".join(PHASES) + " | wall |")
    print("|---|---:|---|" + "---:|" * (len(PHASES) + 1))
    for name, problem, goals in cases:
        spent, counts, wall = measure(problem, goals, objective)
        routes = ", ".join(f"{k} {v}" for k, v in counts.items() if v)
        cells = " | ".join(f"{spent[p]:.2f}" for p in PHASES)
        print(f"| {name} | {len(goals)} | {routes} | {cells} | {wall:.2f} |")


if __name__ == "__main__":
    main()
