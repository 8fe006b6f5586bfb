#!/usr/bin/env python3
"""Benchmark of schedules (BENCHMARKS.md, "Schedules").

The reachable goals of ../shared/foon (their minimum-unit trees), on 1, 2 and 3
agents, with every unit taking 1 s and with the duration table
bench/durations.json; for each encoding (steps, dl) the fixed tree and
``--joint``: how many makespans are proven (with a person among the agents, the
fewest human units at it too), the share proven within the targets (fixed tree 1 s,
``--fixed-target``; joint 10 s), median and max time per goal (each goal the median
of ``--repeat`` runs), and the makespan against the list-scheduling baseline and
the lower bound.  Then the same with
capabilities, resources and a person: the durations, capabilities and resources files of
data/schedule on ``arm=2,human=1`` and ``arm=1,human=1``.  Every
schedule is checked by foon2asp.schedule.checker.

With ``--presets small,hard-4k,hard-10k`` it measures the hard presets of
bench/synth.py instead (bench/hard.py): each preset's goals (at most
``--preset-goals``) get their minimum-unit tree (``--tree-limit`` s each), and
the table gives the share of schedules proven within 10 s.

Usage:  python bench/schedule.py --shared ../shared [--encodings steps,dl] [--agents robot=1,arm=2,arm=3]
        [--limit 10] [--joint-limit 10] [--no-joint] [--no-shortcut] [--goals-table arm=2]
        [--fixed-target 1] [--repeat 1] [--per-goal]
        [--spec-dir data/schedule] [--spec-agents "arm=2,human=1;arm=1,human=1"]
        python bench/schedule.py --presets small,hard-4k,hard-10k [--preset-goals 10] [--encodings steps]
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

from machine import describe  # noqa: E402  (bench/machine.py)

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import foon2asp  # noqa: E402
from foon2asp.schedule import ScheduleSpec, parse_agents, schedule  # noqa: E402
from foon2asp.schedule.checker import check_schedule  # noqa: E402
from foon2asp.schedule.spec import Durations, load_durations  # noqa: E402

TABLE = ROOT / "bench" / "durations.json"
TARGET = {"fixed": 1.0, "joint": 10.0}


def run(kb, trees, spec, encoding, joint, limit, shortcut, repeat=1) -> list[dict]:
    """Each tree scheduled ``repeat`` times: the last answer, and the median time."""
    out = []
    for tree in trees:
        times = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            r = schedule(kb.problem, tree, spec, joint=joint, time_limit=limit, encoding=encoding, shortcut=shortcut)
            times.append(time.perf_counter() - t0)
        elapsed = statistics.median(times)
        d = r.to_dict()
        bad = check_schedule(kb.problem, d, spec)
        if bad:
            raise SystemExit(f"invalid schedule for {d['goal']['label']}: {bad}")
        out.append(
            {
                "goal": d["goal"]["label"],
                "units": len(r.tree.units),
                "status": r.status,
                "makespan": d["makespan"],
                "baseline": d["baseline"].get("makespan"),
                "lower": d["bounds"].get("lower"),
                "fixed": d.get("fixed_tree", {}).get("makespan"),
                "time_s": elapsed,
                "solver": "shortcut" not in r.stats,
                "human_units": d.get("human_units"),
                "human_units_proven": d.get("human_units_proven"),
                "tie_breakers": r.stats.get("tie_breakers"),
            }
        )
    return out


def _proven(r: dict) -> bool:
    """The makespan proven, and with a person the fewest human units at it too."""
    return r["status"] == "optimal" and r["human_units_proven"] is not False and r["tie_breakers"] != "time"


def row(label: str, rs: list[dict], mode: str) -> str:
    times = [r["time_s"] for r in rs]
    proven = sum(_proven(r) for r in rs)
    fast = sum(_proven(r) and r["time_s"] <= TARGET[mode] for r in rs)
    solver = sum(r["solver"] for r in rs)
    made = [r for r in rs if r["makespan"] is not None]
    gain = sum(r["baseline"] - r["makespan"] for r in made) / max(1e-9, sum(r["baseline"] for r in made))
    at_lower = sum(r["makespan"] == r["lower"] for r in made)
    shorter = sum(r["fixed"] is not None and r["makespan"] < r["fixed"] for r in made) if mode == "joint" else "-"
    return (
        f"| {label} | {proven}/{len(rs)} | {fast}/{len(rs)} | {solver} | {statistics.median(times):.3f} |"
        f" {max(times):.3f} | {100 * gain:.1f}% | {at_lower} | {shorter} |"
    )


def spec_of(agents: str, durations: Path | None) -> ScheduleSpec:
    """The spec of ``agents`` with the duration table ``durations``, less its tables of kinds the
    agents do not have (one table serves every agent set; a spec names only the agents' kinds)."""
    kinds = parse_agents(agents)
    if durations is None:
        return ScheduleSpec(kinds)
    table = load_durations(durations)
    have = {kind for kind, _ in kinds} | {"*"}
    return ScheduleSpec(kinds, Durations(table.motions, {k: v for k, v in table.kinds.items() if k in have}))


def settings(args):
    """Each measured setting of ``args``: (agents, durations label, spec, encoding, mode, time limit)."""
    for agents in [a for a in args.agents.split(";") if a]:
        for durations in (None, TABLE):
            spec = spec_of(agents, durations)
            dname = "1 s" if durations is None else "table"
            for encoding in args.encodings.split(","):
                for mode in ("fixed",) if args.no_joint else ("fixed", "joint"):
                    yield agents, dname, spec, encoding, mode, args.limit if mode == "fixed" else args.joint_limit


def presets(args) -> None:
    """The share of the hard presets' schedules proven within 10 s (fixed tree and joint)."""
    from synth import preset

    print(
        "| preset, agents, durations, mode, encoding | trees | proven | proven within 10 s | median s | max s |"
        " units (median, max) |\n|---|---|---|---|---|---|---|"
    )
    records = []
    for name in args.presets.split(","):
        with tempfile.TemporaryDirectory() as tmp:
            preset(name).write(tmp)
            kb = foon2asp.load(tmp)
            ids = kb.select_goals((), "all")
            step = max(1, len(ids) // args.preset_goals) if args.preset_goals else 1
            chosen = ids[::step][: args.preset_goals or None]
            trees = [t.raw for t in kb.solve_iter(chosen, "asp", kb.options(time_limit=args.tree_limit)) if t.has_tree]
            sizes = sorted(len(t.units) for t in trees)
            print(f"{name}: {len(chosen)} goals, {len(trees)} trees", file=sys.stderr, flush=True)
            for agents, dname, spec, encoding, mode, limit in settings(args):
                rs = run(kb, trees, spec, encoding, mode == "joint", limit, not args.no_shortcut)
                times = [r["time_s"] for r in rs] or [0.0]
                proven = sum(r["status"] == "optimal" for r in rs)
                fast = sum(r["status"] == "optimal" and r["time_s"] <= 10.0 for r in rs)
                print(
                    f"| {name}, {agents}, {dname}, {mode}, {encoding} | {len(rs)} | {proven}/{len(rs)} |"
                    f" {fast}/{len(rs)} ({100 * fast / max(1, len(rs)):.0f}%) |"
                    f" {statistics.median(times):.3f} | {max(times):.3f} |"
                    f" {sizes[len(sizes) // 2] if sizes else '-'}, {sizes[-1] if sizes else '-'} |",
                    flush=True,
                )
                for r in rs:
                    records.append(
                        {"preset": name, "agents": agents, "durations": dname, "mode": mode, "encoding": encoding, **r}
                    )
    if args.json:
        Path(args.json).write_text("".join(json.dumps(r) + "\n" for r in records), encoding="utf-8")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shared", default=str(ROOT.parent / "shared"))
    ap.add_argument("--encodings", default="steps,dl")
    ap.add_argument("--agents", default="robot=1;arm=2;arm=3", help="agent sets separated by ';'")
    ap.add_argument("--limit", type=float, default=10.0, help="time limit per goal, fixed tree (s)")
    ap.add_argument("--joint-limit", type=float, default=10.0, help="time limit per goal and solve, joint (s)")
    ap.add_argument("--no-joint", action="store_true")
    ap.add_argument("--fixed-target", type=float, default=TARGET["fixed"], help="the fixed tree's target (s)")
    ap.add_argument("--repeat", type=int, default=1, help="runs per goal; the median time is reported")
    ap.add_argument("--per-goal", action="store_true", help="also one line per goal and row")
    ap.add_argument("--no-shortcut", action="store_true", help="always run the solver")
    ap.add_argument("--goals-table", default="arm=2", help="agents of the per-goal table (duration table, steps)")
    ap.add_argument("--json", help="write every result as JSON lines here")
    ap.add_argument(
        "--spec-dir",
        default=str(ROOT / "data" / "schedule"),
        help="durations, capabilities, resources files ('': none)",
    )
    ap.add_argument("--spec-agents", default="arm=2,human=1;arm=1,human=1", help="agent sets for --spec-dir")
    ap.add_argument("--presets", help="synthetic presets (bench/synth.py), e.g. small,hard-4k,hard-10k")
    ap.add_argument("--preset-goals", type=int, default=10, help="goals per preset, spread over the list (0: all)")
    ap.add_argument("--tree-limit", type=float, default=10.0, help="time limit per tree on a preset (s)")
    args = ap.parse_args()
    TARGET["fixed"] = args.fixed_target
    print(f"machine: {describe()}")
    if args.presets:
        presets(args)
        return
    kb = foon2asp.load(Path(args.shared) / "foon")
    trees = [t.raw for t in kb.solve("all") if t.has_tree]
    print(f"{len(trees)} reachable goals of {args.shared}/foon (minimum-unit trees)")
    shortcut = not args.no_shortcut
    records = []
    header = (
        "| agents, durations, mode, encoding | proven | within target | to solver | median s | max s |"
        " gain over baseline | at lower bound | joint shorter |\n|---|---|---|---|---|---|---|---|---|"
    )
    print(header)
    per_goal: dict[str, list[dict]] = {}
    for agents, dname, spec, encoding, mode, limit in settings(args):
        rs = run(kb, trees, spec, encoding, mode == "joint", limit, shortcut, args.repeat)
        print(row(f"{agents}, {dname}, {mode}, {encoding}", rs, mode), flush=True)
        if args.per_goal:
            for r in rs:
                print(
                    f"    {r['goal']}: {r['status']} {r['makespan']:g} s (lower {r['lower']:g}),"
                    f" human {r['human_units']} (proven {r['human_units_proven']}), {r['time_s']:.3f} s",
                    flush=True,
                )
        for r in rs:
            records.append({"agents": agents, "durations": dname, "mode": mode, "encoding": encoding, **r})
        if agents == args.goals_table and dname == "table" and encoding == "steps":
            per_goal[mode] = rs
    if args.spec_dir:  # capabilities, resources and a person: the data/schedule files
        d = Path(args.spec_dir)
        files = (d / "durations.json", d / "capabilities.json", d / "resources.json")
        for agents in args.spec_agents.split(";"):
            spec = ScheduleSpec.from_files(agents, *files)
            for mode in ("fixed",) if args.no_joint else ("fixed", "joint"):
                limit = args.limit if mode == "fixed" else args.joint_limit
                rs = run(kb, trees, spec, "steps", mode == "joint", limit, shortcut)
                print(row(f"{agents}, {d.name} files, {mode}, steps", rs, mode), flush=True)
                for r in rs:
                    records.append(
                        {"agents": agents, "durations": f"{d.name} files", "mode": mode, "encoding": "steps", **r}
                    )
    if per_goal.get("fixed"):
        print(f"\nper goal, {args.goals_table}, duration table, steps (makespan / baseline / lower bound, s):")
        print("| goal | units | makespan | baseline | lower bound | time s | joint | joint time s |")
        print("|---|---|---|---|---|---|---|---|")
        joint = {r["goal"]: r for r in per_goal.get("joint", [])}
        for r in per_goal["fixed"]:
            j = joint.get(r["goal"], {})
            jm = f"{j['makespan']:g} ({j['status']})" if j else "-"
            jt = f"{j['time_s']:.2f}" if j else "-"
            status = "" if r["status"] == "optimal" else f" ({r['status']})"
            print(
                f"| {r['goal']} | {r['units']} | {r['makespan']:g}{status} | {r['baseline']:g} | {r['lower']:g} |"
                f" {r['time_s']:.2f} | {jm} | {jt} |"
            )
    if args.json:
        Path(args.json).write_text("".join(json.dumps(r) + "\n" for r in records), encoding="utf-8")


if __name__ == "__main__":
    main()
