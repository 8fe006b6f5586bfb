#!/usr/bin/env python3
"""Benchmark of the explorer page (BENCHMARKS.md, "The explorer").

Starts ``foon2asp explore --data SHARED/foon`` and drives the page in the system Chromium
(Playwright) over the 25 reference goals: the first tree on screen (from asking the page's
address to its answer drawn; target 1 s) and a toggle (a motion of the goal's relevant part
unticked, else a kitchen item, else the objective changed, to its answer drawn; target median
0.3 s).  Then ``--requests`` requests as a page sends them (each goal's tree, baselines and
schedule with random toggles, one in ten a bad goal or rule) and the resident memory of the
server and its workers after 10 of them and after all (target: within 10 %).

Usage:  python bench/explore.py --shared ../shared [--requests 1000] [--chromium /usr/bin/chromium]
"""

from __future__ import annotations

import argparse
import json
import random
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path
from urllib.parse import urlencode

from machine import describe  # noqa: E402  (bench/machine.py)

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run"]
ARGS += ["--disable-background-networking", "--disable-component-update", "--disable-sync"]
SHOWN = "document.body.dataset.shown === location.search.replace(/^\\?/, '')"
COMPLETE = "document.body.dataset.complete === location.search.replace(/^\\?/, '')"


def start(data: Path) -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen(
        [sys.executable, "-m", "foon2asp", "explore", "--data", str(data)], stdout=subprocess.PIPE, text=True
    )
    line = proc.stdout.readline() if proc.stdout else ""
    found = re.search(r"http://\S+/", line)
    if found is None:
        proc.kill()
        raise SystemExit(f"the explorer did not start: {line!r}")
    return proc, found.group(0)


def memory(pid: int) -> int:
    """Resident kB of ``pid`` and its children."""
    pids = {pid}
    for task in Path(f"/proc/{pid}/task").iterdir():
        pids |= {int(p) for p in (task / "children").read_text().split()}
    total = 0
    for p in pids:
        status = Path(f"/proc/{p}/status").read_text()
        total += int(status.split("VmRSS:")[1].split()[0])
    return total


def settle(client, url: str) -> None:
    """Wait until every worker is ready and none is busy."""
    for _ in range(600):
        found = client.get(url + "api/status").json()
        if found["ready"] == found["workers"] and found["busy"] == 0:
            return
        time.sleep(0.05)


def page_times(url: str, goals: list[str], chromium: str) -> tuple[list[float], list[float], list[str]]:
    """Per goal: seconds to the first tree on screen, and to the answer of one toggle (and which)."""
    from playwright.sync_api import sync_playwright

    first, toggle, kinds = [], [], []
    with sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path=chromium, args=ARGS)
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        page.goto(url)  # the page's own files once, as a reader has them
        for goal in goals:
            t0 = time.perf_counter()
            page.goto(url + "?" + urlencode({"goal": goal}))
            page.wait_for_function(SHOWN, timeout=60_000)
            first.append(time.perf_counter() - t0)
            page.wait_for_function(COMPLETE, timeout=60_000)  # a reader toggles once the page is complete
            boxes = [s for s in ("#motions input", "#kitchen input") if page.locator(s).count()]
            kinds.append("motion" if "#motions input" in boxes else "kitchen item" if boxes else "objective")
            t0 = time.perf_counter()
            if boxes:
                page.locator(boxes[0]).first.uncheck()
            else:
                page.select_option("#objective-1", "success")
            page.wait_for_function(SHOWN, timeout=60_000)
            toggle.append(time.perf_counter() - t0)
            page.wait_for_function(COMPLETE, timeout=60_000)  # the next goal is asked of idle workers
        browser.close()
    return first, toggle, kinds


def page_request(rng: random.Random, goals: list[str], parts: dict[str, dict]) -> str:
    """A request as the page sends it, with random toggles; one in ten a bad goal or rule."""
    goal = rng.choice(goals)
    if rng.random() < 0.1:
        bad = rng.choice([{"goal": goal + "x"}, {"goal": goal, "rule": ":- use(U), motoin(U,"}])
        return "api/tree?" + urlencode(bad)
    part = parts.get(goal, {"motions": [], "kitchen": []})
    params = [("goal", goal), ("objective", rng.choice(["units", "success,units", "depth"]))]
    params += [("forbid-motion", m) for m in rng.sample(part["motions"], min(len(part["motions"]), rng.randint(0, 2)))]
    items = [k["text"] for k in part["kitchen"]]
    params += [("without", k) for k in rng.sample(items, min(len(items), rng.randint(0, 1)))]
    return f"api/{rng.choice(['tree', 'tree', 'baselines', 'schedule'])}?" + urlencode(params)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shared", default="../shared")
    ap.add_argument("--requests", type=int, default=1000)
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--per-goal", action="store_true", help="also print each goal's two times")
    args = ap.parse_args()
    import httpx2 as httpx

    proc, url = start(Path(args.shared) / "foon")
    try:
        with httpx.Client(timeout=120) as client:
            page = client.get(url).text
            offer = json.loads(re.search(r'type="application/json">(.*?)</script>', page).group(1))
            goals = [g["text"] for g in offer["goals"]]
            first, toggle, kinds = page_times(url, goals, args.chromium)
            if args.per_goal:
                for goal, a, b in zip(goals, first, toggle):
                    print(f"{a:.3f} {b:.3f} {goal[:70]}")
            parts = {}
            for goal in goals:
                found = client.get(url + "api/tree", params={"goal": goal})
                parts[goal] = found.json()["part"]
            rng = random.Random(50)
            before = after = memory(proc.pid)
            t0 = time.perf_counter()
            for k in range(args.requests):
                if k == 10:
                    settle(client, url)
                    before = memory(proc.pid)
                client.get(url + page_request(rng, goals, parts))
            settle(client, url)
            after = memory(proc.pid)
            elapsed = time.perf_counter() - t0
    finally:
        proc.terminate()
        proc.wait(timeout=30)
    print(f"machine: {describe()}")
    print(f"first tree on screen, 25 goals: median {statistics.median(first):.3f} s, max {max(first):.3f} s")
    counts = {k: kinds.count(k) for k in dict.fromkeys(kinds)}
    print(f"toggle ({counts}): median {statistics.median(toggle):.3f} s, max {max(toggle):.3f} s")
    print(
        f"memory (server and workers): after 10 requests {before / 1024:.1f} MB, after {args.requests}"
        f" {after / 1024:.1f} MB ({100 * (after - before) / before:+.1f} %); {args.requests} requests in {elapsed:.0f} s"
    )


if __name__ == "__main__":
    main()
