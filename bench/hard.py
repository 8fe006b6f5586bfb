#!/usr/bin/env python3
"""The hard benchmark: objectives x solver settings on FOONs with real choice.

For each preset (bench/synth.py.PRESETS, and ``foon`` = the 25 goals of
../shared/foon), objective and solver setting, every goal is solved as
``foon2asp solve`` does it: one Session grounded on the goal's units
(``problem.units_for([goal])``), then ``solve(goal)`` with a time limit.  The
time counted is grounding plus solving.  Printed (and with ``--table``
written as markdown): the share of goals proven (``optimal`` or
``unreachable``) within the limit, the median and max time per goal, and the
goals not proven with their status and best cost.

    python bench/hard.py                                  # the table of BENCHMARKS.md
    python bench/hard.py --presets small --objectives "units;depth,success" --settings "bb/usc,one" --limit 5
    python bench/hard.py --write-preset hard-4k DIR       # the preset as a data folder (foon2asp --data DIR)
    python bench/hard.py --table-only raw.jsonl           # the markdown table of earlier raw lines

Raw records (one JSON line per goal) are appended to ``--raw`` when given.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
from collections.abc import Iterable
from pathlib import Path

from machine import describe  # noqa: E402  (bench/machine.py)

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


from foon2asp.asp.canonical import canonical_problem  # noqa: E402
from foon2asp.asp.options import AspOptions  # noqa: E402
from foon2asp.foon import goals as goals_mod  # noqa: E402
from foon2asp.foon.loaders import Dataset  # noqa: E402
from foon2asp.foon.problem import Problem  # noqa: E402
from foon2asp.methods.plan import session_of as Session  # noqa: E402
from synth import PRESETS, preset, shape  # noqa: E402

#: a redundant constraint: a used unit must make something needed (the goal, or an input of a used unit)
NEED = (
    "need",
    "needed(O) :- goal(O).\nneeded(I) :- use(U), required(U,I).\n:- use(U), not needed(O) : product(U,O).\n",
)
#: the domain heuristic: try leaving candidates out first
DOM_FALSE = ("dom-false", "#heuristic use(U) : candidate(U). [1,false]\n")

#: a user program that changes nothing: it switches off what only plain optimisation may use
#: (dominated units, foon2asp.asp.dominance), to measure without it
NO_DOMINANCE = ("no-dominance", "% a user program: no dominated units are forbidden\n")

#: setting name -> AspOptions keyword arguments ("default": what a user who sets nothing gets)
SETTINGS: dict[str, dict] = {
    "default": {},
    # the default, the proof alone
    "default-nocanon": {"canonical": False},
    "bb": {"opt_strategy": "bb"},
    "bb+dom-false+need": {"opt_strategy": "bb", "clingo_args": ["--heuristic=Domain"], "programs": [NEED, DOM_FALSE]},
    "usc": {"opt_strategy": "usc"},
    "usc,one": {"opt_strategy": "usc,one"},
    "usc,k": {"opt_strategy": "usc,k"},
    "usc,pmres": {"opt_strategy": "usc,pmres"},
    "usc+shrink": {"opt_strategy": "usc", "clingo_args": ["--opt-usc-shrink=rgs"]},
    # the proof alone: no canonical tree afterwards (foon2asp.asp.canonical)
    "usc-nocanon": {"opt_strategy": "usc", "canonical": False},
    "usc-nodom": {"opt_strategy": "usc", "programs": [NO_DOMINANCE]},
    "usc-nodom-nocanon": {"opt_strategy": "usc", "canonical": False, "programs": [NO_DOMINANCE]},
    # OLL without its redundant (symmetry) constraints on the cardinality outputs
    "usc,succinct": {"opt_strategy": "usc,oll,succinct"},
    "usc,succinct-nocanon": {"opt_strategy": "usc,oll,succinct", "canonical": False},
    "pf2(bb|usc)": {"threads": 2, "portfolio": "[bb]: --opt-strategy=bb\n[usc]: --opt-strategy=usc\n"},
    "pf2(bbsign|usc)": {
        "threads": 2,
        "portfolio": "[bbsign]: --opt-strategy=bb --opt-heuristic=sign,model\n[usc]: --opt-strategy=usc\n",
    },
}
OBJECTIVES = ("units", "success", "inputs", "depth", "depth,success")
ALL = ";".join(OBJECTIVES)
#: settings that measure one change each, left out of the comparison ("default" is its usc line)
SINGLE = ("default", "default-nocanon", "usc-nocanon", "usc-nodom", "usc-nodom-nocanon", "usc,succinct")
EVERY = "/".join(s for s in SETTINGS if s not in SINGLE and s != "usc,succinct-nocanon")

#: the table of BENCHMARKS.md: (preset, objectives, settings, at most N goals)
DEFAULT_PLAN = [
    ("tiny", ALL, EVERY, None),
    ("small", ALL, EVERY, None),
    ("foon", ALL, EVERY, None),
    ("hard-4k", "units", "bb", 10),
    ("hard-4k", ALL, "default/usc/usc+shrink/pf2(bbsign|usc)", 10),
    ("hard-4k", "units;success", "default-nocanon/usc-nocanon/usc-nodom-nocanon", 10),
    ("hard-10k", "units;success", "default/usc", 10),
]


def load(name: str, shared: Path) -> tuple[Problem, list[int]]:
    """The problem and goal ids of a preset or of ``foon`` (shared/foon and its goals file)."""
    if name == "foon":
        data = Dataset.load(shared / "foon")
    elif name == "foon-111":
        from foon111 import build  # bench/foon111.py: the 111 recipe files merged

        data = build(shared, Path(tempfile.mkdtemp(prefix="foon111-")))
    else:
        data = preset(name).dataset()
    problem = Problem.from_dataset(data)
    return problem, [goals_mod.goal_id(problem, obj) for obj, _ in data.goals]


def pick(goals: list[int], limit: int | None) -> list[int]:
    """At most ``limit`` goals, spread evenly over the list (the presets mix depths round-robin)."""
    if not limit or limit >= len(goals):
        return goals
    step = len(goals) / limit
    return [goals[int(i * step)] for i in range(limit)]


def run(
    problem: Problem, name: str, goals: list[int], objective: str, setting: str, time_limit: float
) -> Iterable[dict]:
    for g in goals:
        t0 = time.perf_counter()
        # the goal's canonical session, as solve builds it when nothing is pruned
        view, units = canonical_problem(problem, [g])
        options = AspOptions(
            objective=tuple(objective.split(",")),
            time_limit=time_limit,
            units=units,
            **SETTINGS[setting],
        )
        grounding = time.perf_counter()
        session = Session(view, options, goal=g)
        ground_s = time.perf_counter() - grounding
        tree = session.solve(g)
        elapsed = time.perf_counter() - t0
        yield {
            "preset": name,
            "objective": objective,
            "setting": setting,
            "goal": g,
            "status": tree.status,
            "units": len(tree.units),
            "asp_cost": tree.asp_cost,
            "fallback": tree.fallback is not None,
            "canonical_search": tree.stats.get("canonical_search"),
            "time_s": round(elapsed, 4),
            "ground_s": round(ground_s, 4),
            "limit": time_limit,
            "load": round(os.getloadavg()[0], 2),
        }


def table(records: list[dict]) -> str:
    """Markdown: per (preset, objective, setting) the proven share, median and max time, the misses."""
    cells: dict[tuple, dict[int, dict]] = {}
    for r in records:
        cells.setdefault((r["preset"], r["objective"], r["setting"]), {})[r["goal"]] = r  # the last run wins
    lines = [
        "| preset | objective | setting | proven | median s | max s | not proven (goal:status:best units) |",
        "|---|---|---|---:|---:|---:|---|",
    ]
    for (pr, ob, se), by_goal in cells.items():
        rs = list(by_goal.values())
        proven = [r for r in rs if r["status"] in ("optimal", "unreachable")]
        times = [r["time_s"] for r in rs]
        misses = [f"{r['goal']}:{r['status'][:4]}:{r['units'] or '-'}" for r in rs if r not in proven]
        more = " …" if len(misses) > 5 else ""
        lines.append(
            f"| {pr} | {ob} | {se} | {len(proven)}/{len(rs)} | {statistics.median(times):.2f} | {max(times):.2f}"
            f" | {' '.join(misses[:5])}{more} |"
        )
    return "\n".join(lines) + "\n"


def machine() -> str:
    return describe()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--presets", help="comma-separated of: foon (../shared/foon), " + ", ".join(PRESETS))
    ap.add_argument("--objectives", help=f"';'-separated, each a comma list (default {ALL})")
    ap.add_argument("--settings", help=f"'/'-separated of: {' '.join(SETTINGS)} (default: all but default)")
    ap.add_argument("--limit", type=int, default=None, help="at most N goals per preset (spread over the list)")
    ap.add_argument(
        "--plan",
        action="append",
        default=[],
        metavar="PRESET:OBJECTIVES:SETTINGS[:LIMIT]",
        help="a cell block of its own (repeatable; replaces --presets/--objectives/--settings/--limit)",
    )
    ap.add_argument("--time-limit", type=float, default=10.0, help="seconds per goal")
    ap.add_argument("--shared", default=str(ROOT.parent / "shared"), help="the shared data folder (holds foon/)")
    ap.add_argument("--raw", help="append one JSON line per goal to this file")
    ap.add_argument("--table", help="write the markdown table (with the machine line) to this file")
    ap.add_argument("--table-only", metavar="RAW", help="print the table of the raw lines in RAW and stop")
    ap.add_argument("--write-preset", nargs=2, metavar=("NAME", "DIR"), help="write a preset as a data folder")
    a = ap.parse_args()

    if a.write_preset:
        name, directory = a.write_preset
        syn = preset(name)
        syn.write(directory)
        print(f"{name}: {shape(syn.problem())}, {len(syn.goals)} goals -> {directory}")
        return
    if a.table_only:
        with open(a.table_only, encoding="utf-8") as fh:
            print(table([json.loads(line) for line in fh if line.strip()]), end="")
        return

    plan = []
    for block in a.plan:
        parts = block.split(":")
        plan.append((parts[0], parts[1], parts[2], int(parts[3]) if len(parts) > 3 else None))
    if not plan and (a.presets or a.objectives or a.settings or a.limit):
        presets = (a.presets or "tiny,small,foon,hard-4k,hard-10k").split(",")
        plan = [(p, a.objectives or ALL, a.settings or EVERY, a.limit) for p in presets]
    plan = plan or DEFAULT_PLAN
    for p, _, settings, _ in plan:
        if p not in ("foon", "foon-111") and p not in PRESETS:
            ap.error(f"unknown preset {p!r} (have foon, foon-111, {', '.join(PRESETS)})")
        for s in settings.split("/"):
            if s not in SETTINGS:
                ap.error(f"unknown setting {s!r} (have {', '.join(SETTINGS)})")

    header = f"Machine: {machine()}. Limit {a.time_limit:g} s per goal."
    print(header, flush=True)
    raw = open(a.raw, "a", encoding="utf-8") if a.raw else None  # noqa: SIM115
    records: list[dict] = []
    t_start = time.perf_counter()
    loaded: dict[str, tuple[Problem, list[int]]] = {}
    for name, objectives, settings, limit in plan:
        if name not in loaded:
            loaded[name] = load(name, Path(a.shared))
        problem, goals = loaded[name]
        goals = pick(goals, limit)
        for objective in objectives.split(";"):
            for setting in settings.split("/"):
                cell = list(run(problem, name, goals, objective, setting, a.time_limit))
                records += cell
                if raw:
                    raw.writelines(json.dumps(r) + "\n" for r in cell)
                    raw.flush()
                print(table(cell).splitlines()[-1], flush=True)
    if raw:
        raw.close()
    footer = f"Wall time {time.perf_counter() - t_start:.0f} s; load average at the end {os.getloadavg()[0]:.2f}."
    print(footer)
    if a.table:
        Path(a.table).write_text(f"{header}\n\n{table(records)}\n{footer}\n", encoding="utf-8")


if __name__ == "__main__":
    main()
