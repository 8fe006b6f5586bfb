"""Signals (foon2asp.asp.interrupts): SIGINT and SIGTERM end a command with one line, and a batch leaves no workers."""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from foon2asp.batch.results_file import read_results
from helpers import REPO


def _cli(*args) -> list[str]:
    return [sys.executable, "-m", "foon2asp", *map(str, args)]


def _env():
    return dict(os.environ, PYTHONPATH=str(REPO))


@pytest.mark.parametrize("sig, code, word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")])
def test_signals_during_solve_end_with_one_line(shared_foon_dir, sig, code, word):
    rng = random.Random(7)
    for _ in range(3):
        proc = subprocess.Popen(
            _cli("solve", "--data", shared_foon_dir, "--goals", "all-objects", "--format", "json"),
            cwd=REPO,
            env=_env(),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        time.sleep(1.5 + rng.random() * 2)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=60)
        if proc.returncode == 0:
            continue  # finished first
        assert proc.returncode == code, err
        assert err.strip().splitlines() == [f"foon2asp: {word}"], err


def _children(pid: int) -> set[int]:
    out = set()
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                out.add(int(entry.name))
    return out


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc to find child processes")
def test_batch_interrupt_and_parent_kill_leave_no_workers(shared_foon_dir, tmp_path):
    out = tmp_path / "r.jsonl"
    args = ("batch", "--data", shared_foon_dir, "--goals", "all-objects", "--workers", "2", "--no-shortcuts")
    proc = subprocess.Popen(
        _cli(*args, "--output", out), cwd=REPO, env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    deadline = time.time() + 60
    while time.time() < deadline and (not out.exists() or out.read_bytes().count(b"\n") < 20):
        time.sleep(0.05)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert err.strip().splitlines()[-1] == "foon2asp: interrupted" and "Traceback" not in err
    records = read_results(out)
    assert records and all(r.get("status") for r in records)
    # SIGKILL of the parent: the workers follow it
    proc = subprocess.Popen(
        _cli(*args, "--output", out, "--resume"), cwd=REPO, env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    workers: set[int] = set()
    deadline = time.time() + 60
    while time.time() < deadline and len(workers) < 2:
        workers = _children(proc.pid)
        time.sleep(0.1)
    assert workers
    proc.kill()
    proc.wait()
    deadline = time.time() + 10
    while time.time() < deadline and any(Path(f"/proc/{w}").exists() for w in workers):
        time.sleep(0.1)
    alive = [w for w in workers if Path(f"/proc/{w}").exists() and "Z" not in (Path(f"/proc/{w}/stat").read_text())]
    assert not alive
