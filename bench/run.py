#!/usr/bin/env python3
"""Benchmarks P1-P3 of batch solving (figures printed; not timed tests).

P1  the 25 goals of goal_nodes.json with ids, gbfs-h1, gbfs-h2 and asp, every
    tree checked by the validator, end to end (load, build, solve, check).
P2  every derivable object that some unit makes (not in the kitchen) with a
    proven-optimal min-unit tree, against gbfs-h1 over the same goals, in one run.
P3  synthetic FOONs 10x and 100x the size (bench/synth.py, seed 1): parse,
    facts, ground, per-goal queries (median, max), the same goals planned ahead as batch
    plans them (mean), and peak memory, each factor in its own process.

Usage:  python bench/run.py --shared ../shared [--parts P1,P2,P3] [--factors 10,100]
"""

from __future__ import annotations

import argparse
import json
import random
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from machine import describe  # noqa: E402  (bench/machine.py)

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from foon2asp import methods  # noqa: E402
from foon2asp.asp.facts import facts  # noqa: E402
from foon2asp.asp.options import AspOptions  # noqa: E402
from foon2asp.foon import goals as goals_mod  # noqa: E402
from foon2asp.foon.loaders import Dataset  # noqa: E402
from foon2asp.foon.problem import Problem  # noqa: E402
from foon2asp.methods.runner import GoalRunner, Parts  # noqa: E402
from foon2asp.tree.validate import validate  # noqa: E402


def peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def machine() -> str:
    return describe()


def ms(x: float) -> str:
    return f"{1000 * x:.2f} ms"


def p1(foon_dir: Path) -> dict:
    t0 = time.perf_counter()
    data = Dataset.load(foon_dir)
    problem = Problem.from_dataset(data)
    goal_ids = goals_mod.resolve(data, problem, None, "all")
    counts = {}
    valid = 0
    split = {"load": time.perf_counter() - t0}
    parts = Parts(problem)
    for name in ("ids", "gbfs-h1", "gbfs-h2", "asp"):
        t = time.perf_counter()
        run = GoalRunner(name, problem, AspOptions(opt_strategy="usc"), "per-goal", True, parts)
        for g in goal_ids:
            tree = run(g)
            counts[(name, tree.status)] = counts.get((name, tree.status), 0) + 1
            if tree.has_tree and validate(problem, g, tree.units).valid:
                valid += 1
        split[name] = time.perf_counter() - t
    total = time.perf_counter() - t0
    print(f"P1  {len(goal_ids)} goals x 4 methods, end to end: {total:.3f} s (target <= 1 s)")
    print("    split: " + ", ".join(f"{k} {v:.3f} s" for k, v in split.items()))
    print(f"    statuses: {dict(sorted((f'{m}:{s}', n) for (m, s), n in counts.items()))}; valid trees: {valid}")
    return {"total_s": total, "goals": len(goal_ids)}


def _time_runner(run, goal_ids):
    times = []
    results = {}
    t0 = time.perf_counter()
    for g in goal_ids:
        t = time.perf_counter()
        tree = run(g)
        times.append(time.perf_counter() - t)
        results[g] = tree
    return time.perf_counter() - t0, times, results


def p2(foon_dir: Path) -> dict:
    data = Dataset.load(foon_dir)
    problem = Problem.from_dataset(data)
    everything = goals_mod.all_objects(problem)
    goal_ids = [g for g in everything if g in problem.derivable]
    print(f"P2  all-objects: {len(everything)} objects, {len(goal_ids)} derivable (the goals measured)")
    parts = Parts(problem)
    out = {}
    t0 = time.perf_counter()
    gbfs = methods.runner("gbfs-h1", problem, AspOptions())
    total, times, _ = _time_runner(gbfs, goal_ids)
    out["gbfs-h1"] = (total, times)
    print(f"    gbfs-h1                         total {total:7.3f} s  median {ms(statistics.median(times))}")
    variants = [
        ("asp whole, bb", AspOptions(), "whole"),
        ("asp whole, usc", AspOptions(opt_strategy="usc"), "whole"),
        ("asp per-goal, usc", AspOptions(opt_strategy="usc"), "per-goal"),
    ]
    for label, options, grounding in variants:
        t = time.perf_counter()
        runner = GoalRunner("asp", problem, options, grounding, True, parts)
        build = time.perf_counter() - t
        total, times, results = _time_runner(runner, goal_ids)
        optimal = sum(1 for r in results.values() if r.status == "optimal")
        ratio = (build + total) / out["gbfs-h1"][0]
        out[label] = (build + total, times)
        print(
            f"    {label:30}  total {build + total:7.3f} s  (ground {build:.3f} s)  median {ms(statistics.median(times))}"
            f"  max {ms(max(times))}  optimal {optimal}/{len(goal_ids)}  {runner.counts}  ratio to gbfs-h1 {ratio:.1f}x"
        )
    print(f"    P2 wall time {time.perf_counter() - t0:.1f} s; target: ASP <= 3x gbfs-h1")
    return out


def p3_one(foon_dir: Path, factor: int, sample: int, seed: int) -> dict:
    """One factor, in this process (run by p3 in a subprocess for a clean peak RSS)."""
    from synth import synthesize

    data = Dataset.load(foon_dir)
    t = time.perf_counter()
    syn = synthesize(data, factor, seed=seed)
    gen = time.perf_counter() - t
    with tempfile.TemporaryDirectory() as tmp:
        syn.write(tmp)
        t = time.perf_counter()
        data2 = Dataset.load(tmp)
        parse = time.perf_counter() - t
    del syn
    t = time.perf_counter()
    problem = Problem.from_dataset(data2)
    build = time.perf_counter() - t
    t = time.perf_counter()
    text = facts(problem)
    facts_s = time.perf_counter() - t
    del text
    rng = random.Random(seed)
    parts = Parts(problem)
    candidates = [g for g in goals_mod.all_objects(problem) if g in problem.derivable]
    goal_ids = rng.sample(candidates, min(sample, len(candidates)))
    row = {
        "factor": factor,
        "units": len(problem.units),
        "objects": len(problem.objects),
        "generate_s": gen,
        "parse_s": parse,
        "problem_s": build,
        "facts_s": facts_s,
    }
    # per-goal groundings: query time includes the goal's own grounding
    runner = GoalRunner("asp", problem, AspOptions(opt_strategy="usc"), "per-goal", True, parts)
    _, times, res = _time_runner(runner, goal_ids)
    row["per_goal"] = {
        "median_s": statistics.median(times),
        "mean_s": statistics.mean(times),
        "max_s": max(times),
        "counts": dict(runner.counts),
        "optimal": sum(r.status == "optimal" for r in res.values()),
    }
    row["rss_after_per_goal_mb"] = peak_mb()
    # the same goals asked together, planned ahead as batch plans them (the bounded decisions in
    # one clingo call per window), on fresh parts: the mean time per goal, planning included
    ahead = GoalRunner("asp", problem, AspOptions(opt_strategy="usc"), "per-goal", True, Parts(problem))
    t = time.perf_counter()
    trees = list(ahead.each(goal_ids))
    row["ahead"] = {
        "mean_s": (time.perf_counter() - t) / len(goal_ids),
        "same": sum(tr.status == res[g].status and tr.units == res[g].units for g, tr in zip(goal_ids, trees)),
        "goals": len(goal_ids),
    }
    # the whole grounding (viable units), then the same goals on it
    t = time.perf_counter()
    whole = GoalRunner("asp", problem, AspOptions(opt_strategy="usc"), "whole", True, parts)
    row["ground_whole_s"] = time.perf_counter() - t
    few = goal_ids[: max(10, sample // 10)]
    _, times, res2 = _time_runner(whole, few)
    row["whole"] = {"median_s": statistics.median(times), "max_s": max(times), "goals": len(few)}
    agree = sum(res[g].status == res2[g].status and len(res[g].units) == len(res2[g].units) for g in few)
    row["agree"] = f"{agree}/{len(few)}"
    row["peak_rss_mb"] = peak_mb()
    return row


def p3(foon_dir: Path, factors: list[int], sample: int) -> list[dict]:
    rows = []
    for factor in factors:
        cmd = [
            sys.executable,
            __file__,
            "--shared",
            str(foon_dir.parent),
            "--p3-factor",
            str(factor),
            "--sample",
            str(sample),
        ]
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:
            print(f"P3  {factor}x failed: {done.stderr.strip().splitlines()[-1:]}")
            continue
        row = json.loads(done.stdout.strip().splitlines()[-1])
        rows.append(row)
        pg, wh = row["per_goal"], row["whole"]
        print(
            f"P3  {factor}x: {row['units']} units, {row['objects']} objects; generate {row['generate_s']:.1f} s, "
            f"parse {row['parse_s']:.2f} s, problem {row['problem_s']:.2f} s, facts {row['facts_s']:.2f} s, "
            f"whole ground {row['ground_whole_s']:.2f} s"
        )
        print(
            f"    per-goal queries ({sum(pg['counts'].values())} goals): median {ms(pg['median_s'])}, "
            f"mean {ms(pg['mean_s'])}, max {ms(pg['max_s'])}, "
            f"{pg['counts']}, optimal {pg['optimal']}; rss after them {row['rss_after_per_goal_mb']:.0f} MB"
        )
        ah = row["ahead"]
        print(
            f"    the same goals planned ahead (as batch): mean {ms(ah['mean_s'])} a goal; "
            f"the same answers {ah['same']}/{ah['goals']}"
        )
        print(
            f"    whole-grounding queries ({wh['goals']} goals): median {ms(wh['median_s'])}, max {ms(wh['max_s'])}; "
            f"same sizes as per-goal {row['agree']}; peak RSS {row['peak_rss_mb']:.0f} MB"
        )
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--shared", default=str(ROOT.parent / "shared"), help="folder holding foon/ (default: ../shared)")
    ap.add_argument("--parts", default="P1,P2,P3")
    ap.add_argument("--factors", default="10,100")
    ap.add_argument("--sample", type=int, default=300, help="goals per synthetic FOON in P3")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--p3-factor", type=int, help=argparse.SUPPRESS)
    args = ap.parse_args()
    foon_dir = Path(args.shared) / "foon"
    if args.p3_factor:
        print(json.dumps(p3_one(foon_dir, args.p3_factor, args.sample, args.seed)))
        return
    print(f"machine: {machine()}")
    parts = {p.strip().upper() for p in args.parts.split(",")}
    if "P1" in parts:
        p1(foon_dir)
    if "P2" in parts:
        p2(foon_dir)
    if "P3" in parts:
        p3(foon_dir, [int(f) for f in args.factors.split(",")], args.sample)


if __name__ == "__main__":
    main()
