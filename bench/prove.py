#!/usr/bin/env python3
"""How many goals of the hard presets are proven, and how far the rest are from it.

Every goal of each preset (bench/synth.py.PRESETS) for each objective, solved as
``foon2asp solve --data PRESET --goals all --time-limit LIMIT`` solves it (the goal runner
with the defaults: shortcuts, bounds, pruning, the solver), one goal after another in one
process.  Per preset and objective: proven within 10 s and within LIMIT, median and max
time per goal, and for every unproven goal its tree, lower bound and gap.

Usage:  python bench/prove.py [--presets hard-4k,hard-10k] [--objectives units,success,...]
                              [--time-limit 60] [--raw FILE]
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
from foon2asp.methods.runner import GoalRunner  # noqa: E402
from synth import preset  # noqa: E402

OBJECTIVES = ("units", "success", "inputs", "depth", "depth,success")


def run(name: str, objective: str, limit: float, raw) -> dict:
    syn = preset(name)
    problem = syn.problem()
    goals = [problem.foon.object_ids[g] for g in syn.goals]
    options = AspOptions(objective=tuple(objective.split(",")), time_limit=limit)
    runner = GoalRunner("asp", problem, options, "whole", True, goals=goals)
    rows = []
    for goal in goals:
        t0 = time.perf_counter()
        tree = runner(goal)
        wall = time.perf_counter() - t0
        row = {
            "preset": name,
            "objective": objective,
            "goal": goal,
            "status": tree.status,
            "wall_s": round(wall, 3),
            "units": len(tree.units),
            "bound": tree.bound,
            "gap": tree.gap,
            "how": tree.stats.get("shortcut") or tree.stats.get("proof") or "solver",
            "proven_by": tree.stats.get("proven_by"),
        }
        rows.append(row)
        if raw is not None:
            raw.write(json.dumps(row) + "\n")
            raw.flush()
    proven = [r for r in rows if r["status"] in ("optimal", "unreachable")]
    times = [r["wall_s"] for r in rows]
    return {
        "preset": name,
        "objective": objective,
        "goals": len(rows),
        "within_10": sum(1 for r in proven if r["wall_s"] <= 10),
        "within_limit": len(proven),
        "median_s": statistics.median(times),
        "max_s": max(times),
        "open": [(r["goal"], r["units"], r["bound"], r["gap"]) for r in rows if r not in proven],
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--presets", default="hard-4k,hard-10k")
    ap.add_argument("--objectives", default=",".join(o.replace(",", "+") for o in OBJECTIVES))
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--raw", help="write one JSON line per goal here")
    a = ap.parse_args()
    print(f"machine: {describe()}")
    raw = open(a.raw, "a", encoding="utf-8") if a.raw else None
    print(
        "| preset · objective | proven ≤ 10 s | proven ≤ limit | median s | max s | not proven: goal (units, bound, gap) |"
    )
    print("|---|---|---|---|---|---|")
    for name in a.presets.split(","):
        for objective in a.objectives.split(","):
            objective = objective.replace("+", ",")
            r = run(name, objective, a.time_limit, raw)
            rest = "; ".join(f"{g} ({u}, {b}, {100 * (gap or 0):.0f}%)" for g, u, b, gap in r["open"]) or "–"
            print(
                f"| {name} · {objective} | {r['within_10']}/{r['goals']} | {r['within_limit']}/{r['goals']} "
                f"| {r['median_s']:.2f} | {r['max_s']:.1f} | {rest} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
