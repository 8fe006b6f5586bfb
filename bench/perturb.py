#!/usr/bin/env python3
"""How many fixed trees randomised list scheduling proves optimal, by number of tries.

For the minimum-unit trees of the reachable goals of ../shared/foon and of the hard presets
(bench/synth.py, 10 goals each), on 2 and 3 arms with unit durations and with
bench/durations.json: the trees whose plain list schedule misses the lower bound, and how many
of them a list schedule with perturbed priorities (foon2asp.schedule.baseline.known_schedule)
brings to the lower bound within N tries, with the time it takes (BENCHMARKS.md, "Schedules").

Usage:  python bench/perturb.py [--shared ../shared] [--presets hard-4k,hard-10k] [--tries 0,8,16,48,128]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

from machine import describe  # noqa: E402  (bench/machine.py)

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import foon2asp  # noqa: E402
from foon2asp.asp.options import AspOptions  # noqa: E402
from foon2asp.methods.runner import GoalRunner  # noqa: E402
from foon2asp.schedule.baseline import known_schedule, list_schedule  # noqa: E402
from foon2asp.schedule.instances import instance, makespan  # noqa: E402
from foon2asp.schedule.lower_bounds import bounds  # noqa: E402
from schedule import spec_of  # noqa: E402  (bench/schedule.py)
from synth import preset  # noqa: E402

TABLE = ROOT / "bench" / "durations.json"


def trees(args) -> list[tuple[str, object, list[int]]]:
    out = []
    kb = foon2asp.load(Path(args.shared) / "foon")
    for t in kb.solve("all"):
        if t.raw.has_tree and t.raw.units:
            out.append(("foon", kb.problem, list(t.raw.units)))
    for name in [p for p in args.presets.split(",") if p]:
        syn = preset(name)
        problem = syn.problem()
        goals = [problem.foon.object_ids[g] for g in syn.goals]
        goals = goals[:: max(1, len(goals) // 10)][:10]
        runner = GoalRunner("asp", problem, AspOptions(time_limit=10), "whole", True, goals=goals)
        for g in goals:
            t = runner(g)
            if t.has_tree and t.units:
                out.append((name, problem, list(t.units)))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--shared", default=str(ROOT.parent / "shared"))
    ap.add_argument("--presets", default="hard-4k,hard-10k")
    ap.add_argument("--tries", default="0,8,16,48,128")
    args = ap.parse_args()
    tries = [int(x) for x in args.tries.split(",")]
    found = trees(args)
    print(describe())
    print(f"{len(found)} trees\n")
    print(
        "| FOON, agents, durations | trees | baseline misses the bound | "
        + " | ".join(f"{n} tries: met, median ms, max ms" for n in tries)
        + " |"
    )
    print("|---" * (3 + len(tries)) + "|")
    for agents in ("arm=2", "arm=3"):
        for label, durations in (("1 s", None), ("table", TABLE)):
            spec = spec_of(agents, durations)
            for source in dict.fromkeys(s for s, _, _ in found):
                insts = [instance(p, u, spec) for s, p, u in found if s == source]
                missed = [(i, bounds(i).lower) for i in insts if makespan(list_schedule(i)) > bounds(i).lower]
                cells = []
                for n in tries:
                    met, times = 0, []
                    for inst, low in missed:
                        t0 = time.perf_counter()
                        run, _ = known_schedule(inst, low, tries=n)
                        times.append(1000 * (time.perf_counter() - t0))
                        met += makespan(run) <= low
                    cells.append(
                        f"{met}/{len(missed)}, {statistics.median(times):.1f}, {max(times):.1f}" if times else "-"
                    )
                print(f"| {source}, {agents}, {label} | {len(insts)} | {len(missed)} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
