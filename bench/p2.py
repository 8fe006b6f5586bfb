#!/usr/bin/env python3
"""P2 as a user runs it: the whole ``batch`` commands side by side, wall time.

    foon2asp batch --data FOON --goals all-objects                    (asp, the defaults)
    foon2asp batch --data FOON --goals all-objects --methods gbfs-h1  (the greedy baseline)

each with ``--fsync`` (the default) and with ``--no-fsync``, run as subprocesses one after
the other, alternating (asp, gbfs, asp, gbfs, ...), ``--runs`` times each (default 3); the
median wall time of each and the ratio asp / gbfs-h1 are printed (target: <= 3x). Every asp
result line must be ``optimal`` or ``unreachable``; the run checks that.

Usage:  python bench/p2.py --shared ../shared [--runs 3]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from machine import describe  # noqa: E402  (bench/machine.py)

ROOT = Path(__file__).resolve().parent.parent


def machine() -> str:
    return describe()


def load() -> str:
    try:
        return open("/proc/loadavg").read().split()[0]
    except OSError:
        return "?"


def run(foon: Path, methods: str | None, fsync: bool, out: Path) -> float:
    cmd = [sys.executable, "-m", "foon2asp", "batch", "--data", str(foon), "--goals", "all-objects"]
    cmd += ["--no-progress", "--output", str(out)]
    if methods:
        cmd += ["--methods", methods]
    if not fsync:
        cmd.append("--no-fsync")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    t0 = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    if done.returncode not in (0, 1):  # 1: some goal has no tree (unreachable / not found)
        raise SystemExit(f"failed: {' '.join(cmd)}\n{done.stderr}")
    return wall


def check(out: Path) -> tuple[dict, dict]:
    """Counts of the statuses and of how the goals were answered (the shortcut, else the solver)."""
    statuses: dict[str, int] = {}
    answered: dict[str, int] = {}
    for line in out.read_text().splitlines():
        record = json.loads(line)
        if "status" in record:
            statuses[record["status"]] = statuses.get(record["status"], 0) + 1
            how = record.get("stats", {}).get("shortcut", "solver")
            answered[how] = answered.get(how, 0) + 1
    return statuses, answered


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--shared", default=str(ROOT.parent / "shared"), help="folder holding foon/ (default: ../shared)")
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    foon = Path(args.shared) / "foon"
    print(f"machine: {machine()}; load average at start {load()}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for fsync in (True, False):
            walls: dict[str, list[float]] = {"asp": [], "gbfs-h1": []}
            for i in range(args.runs):
                for label, methods in (("asp", None), ("gbfs-h1", "gbfs-h1")):
                    out = Path(tmp) / f"{label}-{fsync}-{i}.jsonl"
                    walls[label].append(run(foon, methods, fsync, out))
                    if label == "asp":
                        statuses, answered = check(out)
                        bad = {s: n for s, n in statuses.items() if s not in ("optimal", "unreachable")}
                        if bad:
                            raise SystemExit(f"asp results not all proven: {statuses}")
                    out.unlink()
            asp, gbfs = statistics.median(walls["asp"]), statistics.median(walls["gbfs-h1"])
            flag = "--fsync (default)" if fsync else "--no-fsync"
            rows.append((flag, asp, gbfs, walls))
            print(
                f"P2 {flag:18} asp {asp:6.2f} s  gbfs-h1 {gbfs:6.2f} s  ratio {asp / gbfs:.2f}x"
                f"  (runs asp {', '.join(f'{w:.2f}' for w in walls['asp'])};"
                f" gbfs-h1 {', '.join(f'{w:.2f}' for w in walls['gbfs-h1'])}; statuses {statuses}; load {load()})"
            )
            print(f"   asp goals answered by: {', '.join(f'{k} {v}' for k, v in sorted(answered.items()))}")
    print("target: asp <= 3x gbfs-h1")


if __name__ == "__main__":
    main()
