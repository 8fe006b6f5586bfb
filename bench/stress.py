#!/usr/bin/env python3
"""Short commands under stress (BENCHMARKS.md, "Short commands under stress").

Runs a few thousand short commands of the ``foon2asp`` script (each well under a second on the
demo data: solve, schedule, merge, check, objects, facts, reachable, --version), ``--parallel``
at a time, in a shuffled order, and reports for each command the median and the slowest wall
time. No run may take more than ten times its command's median: a slower one is a stall, and
its process is looked into once it has run ``--probe`` seconds: its Python threads' stacks
(faulthandler, on SIGUSR2) and each thread's state and kernel wait channel (/proc). A thread of
this script wakes every 50 ms meanwhile: a wake-up late by more than a second means the whole
machine stood still (the virtual machine paused, or starved by its host), and a stall during
one is the machine's, not the command's. The hypervisor's steal time is reported too.

Usage:  python bench/stress.py [--runs 3000] [--parallel 2] [--probe 5] [--seed 1] [--json runs.jsonl]
"""

from __future__ import annotations

import argparse
import json
import os
import random
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from machine import describe  # noqa: E402  (bench/machine.py)

ROOT = Path(__file__).resolve().parent.parent

#: the command line as the ``foon2asp`` script starts it, with the Python stacks dumped on SIGUSR2
START = (
    "import faulthandler, signal, sys; faulthandler.register(signal.SIGUSR2, all_threads=True);"
    " sys.argv[0] = 'foon2asp'; from foon2asp.__main__ import run; run()"
)

#: name -> arguments ({tmp}: a folder of the run's own, {tree}: a task tree of the demo data)
COMMANDS = {
    "version": ["--version"],
    "objects": ["objects", "tomato", "--data", "demo"],
    "solve": ["solve", "--data", "demo", "--goal", "tomato salad"],
    "solve-all": ["solve", "--data", "demo", "--goals", "all", "--format", "json"],
    "schedule": ["schedule", "--data", "demo", "--goal", "scrambled egg", "--agents", "arm=1,human=1"],
    "merge": ["merge", *sorted(str(p) for p in (ROOT / "data" / "llm").glob("smoothie-*.json"))]
    + ["-o", "{tmp}/merged.json", "--format", "units-json"],
    "check": ["check", "{tree}", "--data", "demo"],
    "facts": ["facts", "--data", "demo"],
    "reachable": ["reachable", "--data", "demo"],
}


def probe(pid: int) -> dict:
    """What the process ``pid`` is doing: each thread's state and wait channel, its kernel stack."""
    out: dict = {"threads": {}}
    try:
        for task in Path(f"/proc/{pid}/task").iterdir():
            stat = (task / "stat").read_text()
            name = stat[stat.index("(") + 1 : stat.rindex(")")]
            state = stat.rsplit(")", 1)[1].split()[0]
            wchan = (task / "wchan").read_text() if (task / "wchan").exists() else "?"
            out["threads"][task.name] = f"{name} {state} {wchan}"
        out["stack"] = Path(f"/proc/{pid}/stack").read_text()
    except OSError as exc:
        out["error"] = str(exc)
    return out


def steal_s() -> float:
    """Seconds the hypervisor ran others while this machine's CPUs wanted to run (/proc/stat)."""
    try:
        fields = Path("/proc/stat").read_text().splitlines()[0].split()
        return int(fields[8]) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return 0.0


class Heartbeat(threading.Thread):
    """Wakes every 50 ms and keeps each wake-up more than ``late`` seconds late: (wall time it
    woke, seconds late)."""

    def __init__(self, late: float = 1.0) -> None:
        super().__init__(daemon=True)
        self.late, self.gaps, self.stop = late, [], threading.Event()

    def run(self) -> None:
        before = time.monotonic()
        while not self.stop.wait(0.05):
            now = time.monotonic()
            if now - before - 0.05 > self.late:
                self.gaps.append((time.time(), now - before - 0.05))
            before = now


def run_one(name: str, args: list[str], probe_s: float) -> dict:
    """Run one command; past ``probe_s`` seconds, look into it once."""
    started = time.time()
    t0 = time.perf_counter()
    proc = subprocess.Popen(
        [sys.executable, "-c", START, *args], cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )
    looked: dict | None = None
    try:
        proc.wait(timeout=probe_s)
    except subprocess.TimeoutExpired:
        looked = probe(proc.pid)
        proc.send_signal(signal.SIGUSR2)
    err = proc.communicate()[1].decode(errors="replace")
    seconds = time.perf_counter() - t0
    record = {"name": name, "started": started, "seconds": seconds, "code": proc.returncode}
    if looked is not None:
        record["probe"] = looked
        record["stderr"] = err[-4000:]
    return record


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=3000)
    ap.add_argument("--parallel", type=int, default=2)
    ap.add_argument("--probe", type=float, default=5.0, help="look into a run once it has taken this long")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", help="append every run's record to this file (a JSON line each, as it ends)")
    args = ap.parse_args()

    rng = random.Random(args.seed)
    names = [rng.choice(sorted(COMMANDS)) for _ in range(args.runs)]
    print(f"machine: {describe()}")
    with tempfile.TemporaryDirectory(prefix="foon2asp-stress-") as tmp:
        tree = Path(tmp) / "egg.txt"
        egg = [sys.executable, "-m", "foon2asp", "solve", "--data", "demo", "--goal", "scrambled egg", "--format"]
        tree.write_bytes(subprocess.run([*egg, "foon"], cwd=ROOT, check=True, capture_output=True).stdout)
        todo = iter(enumerate(names))
        lock = threading.Lock()
        records: list[dict] = []

        def worker() -> None:
            while True:
                with lock:
                    item = next(todo, None)
                if item is None:
                    return
                i, name = item
                own = Path(tmp) / f"run{i}"
                own.mkdir()
                argv = [a.format(tmp=own, tree=tree) for a in COMMANDS[name]]
                record = run_one(name, argv, args.probe)
                with lock:
                    records.append(record)
                    if args.json:
                        with open(args.json, "a", encoding="utf-8") as fh:
                            fh.write(json.dumps(record) + "\n")
                    if len(records) % 250 == 0:
                        print(f"{len(records)} runs, load {os.getloadavg()[0]:.2f}", flush=True)

        t0, stolen = time.perf_counter(), steal_s()
        beat = Heartbeat()
        beat.start()
        threads = [threading.Thread(target=worker) for _ in range(args.parallel)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        beat.stop.set()
        elapsed, stolen = time.perf_counter() - t0, steal_s() - stolen

    print(f"{len(records)} runs, {args.parallel} at a time, {elapsed:.0f} s; machine after: {describe()}")
    print(f"steal time {stolen:.1f} s; the machine stood still {len(beat.gaps)} time(s) for more than 1 s")
    for at, late in beat.gaps:
        print(f"- at {time.strftime('%H:%M:%S', time.localtime(at))}: {late:.1f} s")
    print("| command | runs | median s | slowest s | slowest / median | exit statuses |")
    print("|---|---:|---:|---:|---:|---|")
    stalls = []
    for name in sorted(COMMANDS):
        mine = [r for r in records if r["name"] == name]
        if not mine:
            continue
        times = [r["seconds"] for r in mine]
        median = statistics.median(times)
        codes = ", ".join(f"{c} x{sum(r['code'] == c for r in mine)}" for c in sorted({r["code"] for r in mine}))
        print(f"| `{name}` | {len(mine)} | {median:.3f} | {max(times):.3f} | {max(times) / median:.1f} | {codes} |")
        stalls += [r | {"median": median} for r in mine if r["seconds"] > 10 * median]
    print(f"stalls (slower than ten times their command's median): {len(stalls)}")
    for r in stalls:
        when = time.strftime("%H:%M:%S", time.localtime(r["started"]))
        still = [late for at, late in beat.gaps if r["started"] <= at <= r["started"] + r["seconds"] + 1]
        machine = f"; the machine stood still {sum(still):.1f} s meanwhile" if still else ""
        print(f"- {r['name']} at {when}: {r['seconds']:.2f} s (median {r['median']:.3f} s){machine}")
        if "probe" in r:
            print(json.dumps(r["probe"], indent=2))
            print(r["stderr"])
    sys.exit(1 if stalls else 0)


if __name__ == "__main__":
    main()
