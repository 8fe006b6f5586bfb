#!/usr/bin/env python3
"""Every answer of whole ``foon2asp batch`` commands, kept to compare two versions of foon2asp.

``run`` times one ``foon2asp batch --workers 1`` per (data set, objective) and writes, per
command, ``SET.OBJECTIVE.jsonl``: a header line (the command, its wall and CPU seconds, exit
status, the goals and how they were chosen) and one line per goal with its status, its cost
(every measure and the solver's vector), the tree's units sorted, ``proven_by`` and the bound.
``compare`` reads two such directories (old, new) and prints per (data set, objective) the
goals, the answers that differ and the time ratios new/old; it exits 1 when an answer differs.

Data sets (their inputs are made once, in ``--inputs``, and read by every later run):

* ``foon``: ../shared/foon, every made object (``--goals all-objects``);
* ``foon-111``: the files of ../shared/foon-111 merged (``foon2asp merge``), the kitchen
  its leaves (``--kitchen leaves``), motions and utensils of ../shared/foon, every made object;
* ``small``: the preset of bench/synth.py, every made object;
* ``hard-4k``: the preset, every 60th derivable object, kitchen items included (83 goals,
  the batch of BENCHMARKS.md).

Objectives: ``units``, ``success``, ``inputs``, ``depth`` and ``cost`` (with a motion-cost
table made from the data set's motion.txt: a motion costs 1.1 minus its success rate).
:data:`STEPS` samples the goals of a command that takes more than about five minutes
(every k-th goal of its list); the header and ``compare`` say so.

    python bench/answers.py run --foon2asp ../baseline/.venv/bin/foon2asp --out ../answers-baseline
    python bench/answers.py run --foon2asp .venv/bin/foon2asp --out ../answers-new --sets foon,hard-4k
    python bench/answers.py compare ../answers-baseline ../answers-new
    python bench/answers.py run --foon2asp .venv/bin/foon2asp --out ../answers-new \\
        --against ../baseline/.venv/bin/foon2asp --against-out ../answers-old --repeat 3
    python bench/answers.py show ../answers-baseline

``--against`` runs a second foon2asp in turns with the first (each command of one, then of
the other, the order swapped every run), so that both see the same load when the times are
compared; ``show`` prints one directory's goals, statuses and times as a markdown table.

``proven_by`` may turn from ``clingo`` to ``bounds`` (counted apart, not a difference). A
goal not proven within the time limit (``feasible``, ``timeout``) on both sides is counted as
such; its tree is the best found in time and is not compared. A goal proven before and not
now is a difference.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BENCH = Path(__file__).resolve().parent

OBJECTIVES = ("units", "success", "inputs", "depth", "cost")
PROVEN = ("optimal", "unreachable")
#: proven_by changes that are no difference (old, new)
ALLOWED_ROUTES = {("clingo", "bounds")}
#: (data set, objective) -> k: only every k-th goal of the set's list is asked (the command takes over ~5 min)
STEPS: dict[tuple[str, str], int] = {("foon-111", "depth"): 10, ("foon-111", "cost"): 2, ("hard-4k", "cost"): 2}
#: hard-4k: every HARD_STEP-th derivable object (kitchen items too)
HARD_STEP = 60


def nth(k: int) -> str:
    """'2nd', '3rd', '60th'."""
    return f"{k}{'th' if 10 <= k % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(k % 10, 'th')}"


@dataclass(frozen=True)
class DataSet:
    """How a data set is given to ``foon2asp batch``."""

    name: str
    #: what the goals are, in words (the header's "goals_from")
    goals_from: str

    def folder(self, inputs: Path) -> Path:
        return inputs / self.name

    def data_args(self, inputs: Path) -> list[str]:
        d = self.folder(inputs)
        if self.name == "foon-111":
            return [
                "--foon",
                str(d / "FOON.txt"),
                "--kitchen",
                "leaves",
                "--motion",
                str(d / "motion.txt"),
                "--utensils",
                str(d / "utensils.txt"),
            ]
        return ["--data", str(d)]


SETS = {
    s.name: s
    for s in (
        DataSet("foon", "every made object (--goals all-objects)"),
        DataSet("foon-111", "every made object (--goals all-objects)"),
        DataSet("small", "every made object (--goals all-objects)"),
        DataSet("hard-4k", f"every {nth(HARD_STEP)} derivable object (goals file)"),
    )
}


# ----------------------------------------------------------------------------- inputs


def _goal_lists(folder: Path, leaves: bool) -> tuple[list[dict], list[dict]]:
    """(every made object, every derivable object: kitchen items too) of a data folder, as goal objects in id order."""
    sys.path.insert(0, str(ROOT))
    from foon2asp import api
    from foon2asp.foon import goals as goals_mod

    if leaves:
        kb = api.load(
            foon=folder / "FOON.txt", kitchen="leaves", motion=folder / "motion.txt", utensils=folder / "utensils.txt"
        )
    else:
        kb = api.load(folder)
    problem = kb.problem
    made = goals_mod.all_objects(problem)
    objects = problem.objects
    return [objects[g].to_json() for g in made], [objects[g].to_json() for g in sorted(problem.derivable)]


def prepare(name: str, inputs: Path, shared: Path, foon2asp: str) -> None:
    """Make the data set's folder in ``inputs`` (once): data, motion costs, goal lists."""
    out = SETS[name].folder(inputs)
    if (out / "ready").exists():
        return
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    if name == "foon":
        for f in ("FOON.txt", "kitchen.json", "goal_nodes.json", "motion.txt", "utensils.txt"):
            shutil.copy(shared / "foon" / f, out / f)
    elif name == "foon-111":
        files = sorted(str(p) for p in (shared / "foon-111").glob("*.txt"))
        subprocess.run([foon2asp, "merge", *files, "-o", str(out / "FOON.txt")], check=True, capture_output=True)
        for f in ("motion.txt", "utensils.txt"):
            shutil.copy(shared / "foon" / f, out / f)
    else:
        sys.path.insert(0, str(BENCH))
        from synth import preset

        preset(name).write(out)
    costs = []
    for line in (out / "motion.txt").read_text(encoding="utf-8").splitlines():
        if "\t" in line:
            motion, rate = line.split("\t", 1)
            costs.append(f"{motion}\t{max(0.0, 1.1 - float(rate)):.2f}\n")
    (out / "motion-cost.txt").write_text("".join(costs), encoding="utf-8")
    made, derivable = _goal_lists(out, leaves=name == "foon-111")
    (out / "all-objects.json").write_text(json.dumps(made, indent=0), encoding="utf-8")
    (out / "derivable.json").write_text(json.dumps(derivable, indent=0), encoding="utf-8")
    (out / "ready").write_text("", encoding="utf-8")


def goals_args(name: str, objective: str, inputs: Path, work: Path) -> tuple[list[str], str, int | None]:
    """The --goals option of a command, the words saying which goals, the sampling step (None: all)."""
    folder = SETS[name].folder(inputs)
    step = STEPS.get((name, objective))
    if name == "hard-4k":
        goals = json.loads((folder / "derivable.json").read_text(encoding="utf-8"))[::HARD_STEP]
        words = SETS[name].goals_from
        if step:
            goals, words = goals[::step], f"{words}, every {nth(step)} of those (sampled)"
    elif step:
        goals = json.loads((folder / "all-objects.json").read_text(encoding="utf-8"))[::step]
        words = f"every {nth(step)} made object (sampled; goals file)"
    else:
        return ["--goals", "all-objects"], SETS[name].goals_from, None
    path = work / f"{name}.{objective}.goals.json"
    path.write_text(json.dumps(goals, indent=0), encoding="utf-8")
    return ["--goals", str(path)], words, step


# ----------------------------------------------------------------------------- run


def machine() -> str:
    try:
        sys.path.insert(0, str(BENCH))
        from machine import describe

        return describe()
    except ImportError:
        load = os.getloadavg()
        return f"nproc {os.cpu_count()}, load average {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}"


def answer(rec: dict) -> dict:
    """The parts of a batch result line that are compared (and a few kept to read)."""
    return {
        "goal": rec["goal"],
        "status": rec["status"],
        "cost": rec.get("cost"),
        "asp_cost": rec.get("asp_cost"),
        "units": sorted(json.dumps(u, sort_keys=True) for u in rec.get("units") or []),
        "proven_by": rec.get("proven_by"),
        "bound": rec.get("bound"),
        "valid": rec.get("valid"),
        "time_s": rec.get("time_s"),
    }


def timed(cmd: list[str], cwd: Path) -> tuple[float, float, int, str]:
    """Run ``cmd``: (wall s, user+system CPU s of it and its children, exit status, stderr)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=cwd, stdin=subprocess.DEVNULL, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, proc.returncode, proc.stderr + proc.stdout


@dataclass
class Side:
    """One foon2asp whose commands are run, and what its runs of one command gave."""

    foon2asp: str
    out: Path
    walls: list[float] = field(default_factory=list)
    cpus: list[float] = field(default_factory=list)
    exits: list[int] = field(default_factory=list)
    loads: list[float] = field(default_factory=list)
    answers: list[list[dict]] = field(default_factory=list)
    batch_header: dict = field(default_factory=dict)
    log: str = ""


def batch_command(
    foon2asp: str, name: str, objective: str, goals: list[str], inputs: Path, a: argparse.Namespace, raw: Path
) -> list[str]:
    """The timed command: one batch of one objective, one worker, the asp method."""
    folder = SETS[name].folder(inputs)
    extra = ["--motion-cost", str(folder / "motion-cost.txt")] if objective == "cost" else []
    return [
        foon2asp,
        "batch",
        *SETS[name].data_args(inputs),
        *goals,
        "--methods",
        "asp",
        "--objective",
        objective,
        *extra,
        "--workers",
        "1",
        "--time-limit",
        str(a.time_limit),
        "--no-progress",
        "--no-fsync",
        "--summary",
        "text",
        "-o",
        str(raw),
    ]


def run_one(
    a: argparse.Namespace, name: str, objective: str, inputs: Path, sides: list[Side], machine_line: str
) -> None:
    """Run one (data set, objective) ``--repeat`` times on every side, taking turns, and write its results files."""
    goals: list[str] = []
    for side in sides:
        work = side.out / "raw"
        work.mkdir(parents=True, exist_ok=True)
        goals, goals_from, step = goals_args(name, objective, inputs, work)
    for i in range(a.repeat):
        # taking turns, the first side first in odd runs and last in even ones
        for side in sides if i % 2 == 0 else sides[::-1]:
            raw = side.out / "raw" / f"{name}.{objective}.{i}.jsonl"
            raw.unlink(missing_ok=True)
            cmd = batch_command(side.foon2asp, name, objective, goals, inputs, a, raw)
            load = os.getloadavg()[0]
            wall, cpu, code, side.log = timed(cmd, raw.parent)
            if code not in (0, 1) or not raw.exists():
                sys.exit(f"answers: {name} {objective}: {side.foon2asp} exited {code}:\n{side.log}")
            lines = [json.loads(x) for x in raw.read_text(encoding="utf-8").splitlines() if x.strip()]
            side.batch_header = side.batch_header or lines[0]
            side.answers.append([answer(r) for r in lines[1:]])
            side.walls.append(wall)
            side.cpus.append(cpu)
            side.exits.append(code)
            side.loads.append(round(load, 2))
            who = f" [{side.foon2asp}]" if len(sides) > 1 else ""
            print(
                f"  {name:9} {objective:8} run {i + 1}/{a.repeat}{who}: {len(lines) - 1} goals, wall {wall:.2f} s,"
                f" cpu {cpu:.2f} s, exit {code}, load {load:.2f}{f' ({goals_from})' if step else ''}",
                flush=True,
            )
    for side in sides:
        # the answers of the first run; runs that disagree on a proven answer are noted
        first = {json.dumps(r["goal"], sort_keys=True): r for r in side.answers[0]}
        unstable = sorted(
            {
                k
                for other in side.answers[1:]
                for r in other
                if (k := json.dumps(r["goal"], sort_keys=True)) in first
                and r["status"] in PROVEN
                and differs(first[k], r)
            }
        )
        header = {
            "answers": 1,
            "inputs_sha256": inputs_sha256(SETS[name].folder(inputs), goals),
            "set": name,
            "objective": objective,
            "command": batch_command(
                side.foon2asp, name, objective, goals, inputs, a, side.out / "raw" / f"{name}.{objective}.0.jsonl"
            ),
            "foon2asp": side.foon2asp,
            "version": version(side.foon2asp),
            "goals": len(side.answers[0]),
            "goals_from": goals_from,
            "sampled_step": step,
            "time_limit": a.time_limit,
            "wall_s": side.walls,
            "cpu_s": side.cpus,
            "wall_median_s": statistics.median(side.walls),
            "cpu_median_s": statistics.median(side.cpus),
            "exit": side.exits,
            "batch_header": side.batch_header,
            "unstable_between_runs": unstable,
            "summary": side.log.strip().splitlines()[-3:],
            "machine": machine_line,
            "load": side.loads,
            "when": time.strftime("%Y-%m-%d %H:%M:%S"),
        }
        with open(side.out / f"{name}.{objective}.jsonl", "w", encoding="utf-8") as fh:
            fh.write(json.dumps(header) + "\n")
            fh.writelines(json.dumps(r) + "\n" for r in side.answers[0])


def inputs_sha256(folder: Path, goals: list[str]) -> str:
    """One hash of the data set's files and the goals asked (a goals file by its content)."""
    h = hashlib.sha256()
    for path in sorted(p for p in folder.iterdir() if p.is_file() and p.name != "ready"):
        h.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    h.update(Path(goals[1]).read_bytes() if goals[1] != "all-objects" else b"all-objects")
    return h.hexdigest()


def version(foon2asp: str) -> str:
    proc = subprocess.run([foon2asp, "--version"], capture_output=True, text=True)
    return proc.stdout.strip()


def executable(path: str | None, option: str) -> str:
    if not path:
        path = shutil.which("foon2asp") or str(Path(sys.executable).parent / "foon2asp")
    full = str(Path(path).absolute())
    if not Path(full).is_file():
        sys.exit(f"answers: {option}: {full} not found")
    return full


def cmd_run(a: argparse.Namespace) -> None:
    sets = a.sets.split(",")
    objectives = a.objectives.split(",")
    for s in sets:
        if s not in SETS:
            sys.exit(f"answers: --sets: unknown data set {s!r} (have {', '.join(SETS)})")
    for o in objectives:
        if o not in OBJECTIVES:
            sys.exit(f"answers: --objectives: unknown objective {o!r} (have {', '.join(OBJECTIVES)})")
    if bool(a.against) != bool(a.against_out):
        sys.exit("answers: --against and --against-out go together")
    inputs = Path(a.inputs).absolute()
    main_side = Side(executable(a.foon2asp, "--foon2asp"), Path(a.out).absolute())
    sides = [Side(executable(a.against, "--against"), Path(a.against_out).absolute())] if a.against else []
    sides.append(main_side)
    machine_line = machine()
    print(f"Machine: {machine_line}", flush=True)
    for side in sides:
        side.out.mkdir(parents=True, exist_ok=True)
        print(f"foon2asp: {side.foon2asp} ({version(side.foon2asp)}) -> {side.out}", flush=True)
    t0 = time.perf_counter()
    for s in sets:
        prepare(s, inputs, Path(a.shared), sides[0].foon2asp)
        for o in objectives:
            run_one(a, s, o, inputs, [Side(x.foon2asp, x.out) for x in sides], machine_line)
    print(f"Wall time {time.perf_counter() - t0:.0f} s")


# ----------------------------------------------------------------------------- compare


def read(path: Path) -> tuple[dict, dict[str, dict]]:
    with open(path, encoding="utf-8") as fh:
        header = json.loads(fh.readline())
        return header, {json.dumps(r["goal"], sort_keys=True): r for r in map(json.loads, fh) if r}


def differs(old: dict, new: dict) -> list[str]:
    """What differs between two answers of one goal: status, cost, units, proven_by."""
    out = []
    if old["status"] != new["status"]:
        out.append("status")
    if old["cost"] != new["cost"] or old["asp_cost"] != new["asp_cost"]:
        out.append("cost")
    if old["units"] != new["units"]:
        out.append("units")
    if old["proven_by"] != new["proven_by"] and (old["proven_by"], new["proven_by"]) not in ALLOWED_ROUTES:
        out.append("proven_by")
    return out


def short(r: dict) -> str:
    return f"{r['status']} {r['asp_cost']} {len(r['units'])} units by {r['proven_by']}"


def compare_cell(old_h: dict, old: dict, new_h: dict, new: dict) -> tuple[dict, list[str]]:
    """Counts of one (data set, objective) and lines describing each difference."""
    c = {k: 0 for k in ("status", "cost", "units", "proven_by", "to_bounds", "newly_proven", "unproven_both")}
    notes: list[str] = []
    if old_h.get("inputs_sha256") != new_h.get("inputs_sha256"):
        notes.append("the inputs differ (another inputs folder or goals): the answers are not comparable")
    old_config, new_config = old_h["batch_header"]["config"], new_h["batch_header"]["config"]
    if old_config.get("input_sha256") != new_config.get("input_sha256"):
        notes.append("note: the batch headers' input_sha256 differ (the same files, the facts hashed differently)")
    keys = sorted(k for k in old_config.keys() | new_config.keys() if k != "input_sha256")
    if changed := [k for k in keys if old_config.get(k) != new_config.get(k)]:
        notes.append(f"the configurations differ in: {', '.join(changed)}")
    missing, added = old.keys() - new.keys(), new.keys() - old.keys()
    if missing or added:
        notes.append(f"goals only before: {len(missing)}, only now: {len(added)}")
    for k in sorted(old.keys() & new.keys()):
        o, n = old[k], new[k]
        if (o["proven_by"], n["proven_by"]) in ALLOWED_ROUTES:
            c["to_bounds"] += 1
        if o["status"] not in PROVEN:
            if n["status"] in PROVEN:
                c["newly_proven"] += 1
                notes.append(f"newly proven {k}: {short(o)} -> {short(n)}")
            else:
                c["unproven_both"] += 1
            continue
        what = differs(o, n)
        for w in what:
            c[w] += 1
        if what:
            notes.append(f"{'/'.join(what)} {k}: {short(o)} -> {short(n)}")
    c["goals_only_one_side"] = len(missing) + len(added)
    return c, notes


def cmd_compare(a: argparse.Namespace) -> int:
    old_dir, new_dir = Path(a.old), Path(a.new)
    names = [p.name for p in cells(old_dir)]
    if not names:
        sys.exit(f"answers: {old_dir}: no results (SET.OBJECTIVE.jsonl)")
    rows = [
        "| set | objective | goals | status | cost | units | proven_by | clingo→bounds | newly proven"
        " | unproven both | wall old s | wall new s | wall new/old | cpu new/old |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    failed, slow, details, not_run = False, [], [], []

    def mark(ratio: float, judged: bool) -> str:
        return f"{ratio:.2f}{' !' if judged and ratio > a.max_ratio else ''}"

    for cell in names:
        old_h, old = read(old_dir / cell)
        name = f"{old_h['set']} {old_h['objective']}"
        if not (new_dir / cell).exists():
            not_run.append(name)
            continue
        new_h, new = read(new_dir / cell)
        c, notes = compare_cell(old_h, old, new_h, new)
        wall = new_h["wall_median_s"] / old_h["wall_median_s"]
        cpu = new_h["cpu_median_s"] / old_h["cpu_median_s"]
        sampled = f" (every {nth(old_h['sampled_step'])})" if old_h.get("sampled_step") else ""
        bad = any(c[k] for k in ("status", "cost", "units", "proven_by", "goals_only_one_side")) or any(
            n.startswith(("the inputs differ", "the configurations differ")) for n in notes
        )
        failed |= bad
        ratio = wall if a.time == "wall" else cpu
        if ratio > a.max_ratio:
            slow.append(f"{name}: {a.time} {ratio:.2f}× (> {a.max_ratio:.2f}×)")
        rows.append(
            f"| {old_h['set']} | {old_h['objective']} | {len(old)}{sampled} | {c['status']} | {c['cost']} | {c['units']}"
            f" | {c['proven_by']} | {c['to_bounds']} | {c['newly_proven']} | {c['unproven_both']}"
            f" | {old_h['wall_median_s']:.2f} | {new_h['wall_median_s']:.2f} | {mark(wall, a.time == 'wall')}"
            f" | {mark(cpu, a.time == 'cpu')} |"
        )
        for unstable, h in (("before", old_h), ("now", new_h)):
            if h.get("unstable_between_runs"):
                notes.append(f"{len(h['unstable_between_runs'])} proven answers differ between the runs {unstable}")
        details += [f"{name}: {n}" for n in notes[: a.details]]
        if len(notes) > a.details:
            details.append(f"{name}: ... {len(notes) - a.details} more")
    print("\n".join(rows))
    for line in details:
        print(line)
    for line in slow:
        print(f"slower: {line}")
    if not_run:
        print(f"not run in {new_dir} (not compared): {', '.join(not_run)}")
    compared = len(names) - len(not_run)
    print(
        f"answers of {compared} command(s): "
        + ("DIFFERENT" if failed else "the same")
        + f"; {len(slow)} command(s) over {a.max_ratio:.2f}× ({a.time} time)"
    )
    return 1 if failed else 0


def cells(directory: Path) -> list[Path]:
    """The results files of a directory, in the order of SETS and OBJECTIVES."""
    order = {s: i for i, s in enumerate(SETS)}

    def key(p: Path) -> tuple[int, int]:
        name, objective = p.name.split(".")[:2]
        return order.get(name, len(order)), OBJECTIVES.index(objective) if objective in OBJECTIVES else 99

    return sorted(directory.glob("*.*.jsonl"), key=key)


def cmd_show(a: argparse.Namespace) -> None:
    """Per command of one results directory: goals, statuses and routes, wall and CPU seconds."""
    rows = [
        "| set | objective | goals | statuses (proven_by) | wall s | CPU s | load at start |",
        "|---|---|---|---|---:|---:|---:|",
    ]
    for path in cells(Path(a.dir)):
        header, answers = read(path)
        counts: dict[str, int] = {}
        for r in answers.values():
            k = f"{r['status']} ({r['proven_by']})" if r["proven_by"] else r["status"]
            counts[k] = counts.get(k, 0) + 1
        statuses = ", ".join(f"{k} {v}" for k, v in sorted(counts.items(), key=lambda kv: -kv[1]))
        goals = f"{len(answers)}, {header['goals_from']}"
        rows.append(
            f"| {header['set']} | {header['objective']} | {goals} | {statuses} | {header['wall_median_s']:.1f}"
            f" | {header['cpu_median_s']:.1f} | {', '.join(map(str, header.get('load', []))) or '-'} |"
        )
    print("\n".join(rows))


# ----------------------------------------------------------------------------- main


def main(argv: Iterable[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="mode", required=True)
    r = sub.add_parser("run", help="run the batches, one results file per (data set, objective)")
    r.add_argument("--foon2asp", help="the foon2asp executable (default: on PATH, else beside this Python)")
    r.add_argument("--out", required=True, help="directory for the results")
    r.add_argument("--sets", default=",".join(SETS), help=f"comma-separated of: {', '.join(SETS)}")
    r.add_argument("--objectives", default=",".join(OBJECTIVES), help="comma-separated, each run on its own")
    r.add_argument("--time-limit", type=float, default=60.0, help="seconds per goal (default 60)")
    r.add_argument("--repeat", type=int, default=1, help="runs per command; times are their median")
    r.add_argument(
        "--against",
        metavar="FOON2ASP",
        help="a second foon2asp (e.g. the baseline's) run in turns with the first, so both see the same load",
    )
    r.add_argument("--against-out", metavar="DIR", help="directory for the results of --against")
    r.add_argument("--shared", default=str(ROOT.parent / "shared"), help="the shared data folder")
    r.add_argument(
        "--inputs",
        default=str(ROOT.parent / "answers-inputs"),
        help="where the data sets' folders are made once and then read (default: ../answers-inputs)",
    )
    c = sub.add_parser("compare", help="compare two results directories; exit 1 when an answer differs")
    c.add_argument("old")
    c.add_argument("new")
    c.add_argument("--max-ratio", type=float, default=1.10, help="flag commands slower than this (new/old)")
    c.add_argument(
        "--time",
        choices=("wall", "cpu"),
        default="wall",
        help="the time judged against --max-ratio: wall seconds, or CPU seconds (steadier on a busy machine)",
    )
    c.add_argument("--details", type=int, default=10, help="difference lines shown per command")
    w = sub.add_parser("show", help="the goals, statuses and times of one results directory (markdown)")
    w.add_argument("dir")
    a = ap.parse_args(list(argv) if argv is not None else None)
    if a.mode == "show":
        cmd_show(a)
        return 0
    if a.mode == "run":
        if a.repeat < 1:
            ap.error("--repeat must be at least 1")
        cmd_run(a)
        return 0
    return cmd_compare(a)


if __name__ == "__main__":
    sys.exit(main())
