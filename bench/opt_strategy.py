"""Solver settings on the 25 goals of ../shared/foon: objectives x optimisation strategy.

For every configuration one Session grounds the whole FOON once and solves
the 25 goals in turn (as ``foon2asp solve --goals all`` does).  Printed per
configuration: grounding time, median / max / total per-goal solve time,
the number of goals proven optimal, and whether the optimal costs agree with
the first strategy (they must: every strategy proves the same optimum).

    .venv/bin/python bench/opt_strategy.py [--shared ../shared] [--repeat 3]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from foon2asp.asp.options import AspOptions  # noqa: E402
from foon2asp.foon.loaders import Dataset  # noqa: E402
from foon2asp.foon.problem import Problem  # noqa: E402
from foon2asp.methods.plan import session_of as Session  # noqa: E402

STRATEGIES = ("bb", "bb,hier", "usc", "usc,oll")
#: each objective alone, then depth beside success and units
OBJECTIVES = (
    *((name,) for name in ("units", "success", "inputs", "depth")),
    *(("depth", "success"), ("success", "depth"), ("units", "depth")),
)
EXTRA = (
    ("units, --max-depth 12", dict(objective=("units",), max_depth=12)),
    ("success, --human-steps 2", dict(objective=("success",), human_steps=2)),
    ("units, --models 3", dict(objective=("units",), models=3)),
    ("units, --all-optimal", dict(objective=("units",), all_optimal=True)),
    ("asp-greedy-h1", dict(heuristic="h1")),
    ("asp-greedy-h2", dict(heuristic="h2")),
    ("units, 2 threads", dict(objective=("units",), threads=2)),
    ("success, 2 threads", dict(objective=("success",), threads=2)),
)


def run(problem: Problem, goals: list[int], options: AspOptions) -> dict:
    t0 = time.perf_counter()
    session = Session(problem, options)
    ground = time.perf_counter() - t0
    times, costs, proven = [], [], 0
    for g in goals:
        t = time.perf_counter()
        tree = session.solve(g)
        times.append(time.perf_counter() - t)
        costs.append(tuple(tree.asp_cost or ()))
        proven += tree.status in ("optimal", "unreachable", "found")
    return {
        "ground": ground,
        "median": statistics.median(times),
        "max": max(times),
        "total": time.perf_counter() - t0,
        "proven": proven,
        "costs": costs,
    }


def best_of(problem, goals, options, repeat: int) -> dict:
    runs = [run(problem, goals, options) for _ in range(repeat)]
    return min(runs, key=lambda r: r["total"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shared", default=str(ROOT.parent / "shared"), help="directory holding foon/")
    parser.add_argument("--repeat", type=int, default=3, help="runs per configuration (the fastest is shown)")
    args = parser.parse_args()
    data = Dataset.load(Path(args.shared) / "foon")
    problem = Problem.from_dataset(data)
    goals = [problem.foon.object_ids[o] for o, _ in data.goals]
    print(f"{len(goals)} goals, {len(problem.units)} units; best of {args.repeat} runs; times in seconds")
    print()
    print("| objective | strategy | ground | median/goal | max/goal | total | proven | same optimum |")
    print("|---|---|---:|---:|---:|---:|---:|---|")
    for objective in OBJECTIVES:
        reference = None
        for strategy in STRATEGIES:
            r = best_of(problem, goals, AspOptions(objective=objective, opt_strategy=strategy), args.repeat)
            reference = reference or r["costs"]
            same = "yes" if r["costs"] == reference else "NO"
            print(
                f"| {','.join(objective)} | {strategy} | {r['ground']:.2f} | {r['median'] * 1000:.0f} ms "
                f"| {r['max']:.2f} | {r['total']:.2f} | {r['proven']}/{len(goals)} | {same} |"
            )
    print()
    print("| configuration (default strategy) | ground | median/goal | max/goal | total | proven |")
    print("|---|---:|---:|---:|---:|---:|")
    for name, kw in EXTRA:
        r = best_of(problem, goals, AspOptions(**kw), args.repeat)
        print(
            f"| {name} | {r['ground']:.2f} | {r['median'] * 1000:.0f} ms | {r['max']:.2f} "
            f"| {r['total']:.2f} | {r['proven']}/{len(goals)} |"
        )


if __name__ == "__main__":
    main()
