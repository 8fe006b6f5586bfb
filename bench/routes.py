#!/usr/bin/env python3
"""Where each goal's answer comes from: the goal runner's routes on one FOON, per objective.

For every made object (or every ``--step``-th) of a data folder and each objective, the
goal is asked alone of one :class:`GoalRunner` in one process (``foon2asp solve --goal`` for each,
without the planning ahead of many goals) and its route (foon2asp.methods.runner.PROVEN_BY) timed.  Printed as a markdown table: goals
per route, their median and slowest time, and the goals not proven within the limit
with their cost and bound.  ``--reference FILE`` (JSON lines of an earlier run of this
script, ``--raw``) also counts the answers whose status or cost differ.

    python bench/routes.py --data ../shared/foon --objectives units,success
    python bench/routes.py --data DIR --step 5 --time-limit 60 --raw new.jsonl --reference old.jsonl
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

from machine import describe  # noqa: E402  (bench/machine.py)

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from foon2asp.asp.options import AspOptions  # noqa: E402
from foon2asp.foon.loaders import Dataset  # noqa: E402
from foon2asp.foon.problem import Problem  # noqa: E402
from foon2asp.methods.runner import GoalRunner  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", required=True)
    ap.add_argument("--objectives", default="units", help="';'-separated lists, e.g. 'units;success;depth'")
    ap.add_argument("--step", type=int, default=1, help="every STEP-th made object")
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--raw", help="append one JSON line per goal here")
    ap.add_argument("--reference", help="JSON lines of an earlier --raw: count differing answers")
    args = ap.parse_args()
    data = Dataset.load(args.data)
    problem = Problem(data.foon, data.kitchen, data.motion, data.utensils)
    made = sorted({o for u in range(len(problem.units)) for o in problem.products[u]})[:: args.step]
    reference = {}
    if args.reference:
        for line in Path(args.reference).read_text().splitlines():
            r = json.loads(line)
            reference[(r["objective"], r["goal"])] = (r["status"], r["cost"])
    raw = open(args.raw, "a", encoding="utf-8") if args.raw else None
    print(f"{args.data}: {len(made)} goals, time limit {args.time_limit:g} s; {describe()}\n")
    print("| objective | route | goals | median s | max s | not proven |")
    print("|---|---|---:|---:|---:|---|")
    for objective in args.objectives.split(";"):
        names = tuple(objective.split(","))
        run = GoalRunner("asp", problem, AspOptions(objective=names, time_limit=args.time_limit))
        times: dict[str, list[float]] = {}
        open_goals: dict[str, list[str]] = {}
        differ = 0
        for goal in made:
            route = run.route(goal)
            t0 = time.perf_counter()
            tree = run(goal)
            took = time.perf_counter() - t0
            times.setdefault(route, []).append(took)
            cost = tree.asp_cost
            if tree.status not in ("optimal", "unreachable"):
                open_goals.setdefault(route, []).append(f"{goal} ({tree.status}, {cost}, bound {tree.bound})")
            if (objective, goal) in reference and reference[(objective, goal)] != (tree.status, cost):
                differ += 1
            if raw:
                record = {"objective": objective, "goal": goal, "route": route, "status": tree.status}
                raw.write(json.dumps(record | {"cost": cost, "time_s": round(took, 4)}) + "\n")
        for route, ts in sorted(times.items()):
            shown = "; ".join(open_goals.get(route, [])) or "-"
            print(f"| {objective} | {route} | {len(ts)} | {statistics.median(ts):.4f} | {max(ts):.2f} | {shown} |")
        if args.reference:
            print(f"| {objective} | differ from the reference | {differ} | | | |")
    if raw:
        raw.close()


if __name__ == "__main__":
    main()
