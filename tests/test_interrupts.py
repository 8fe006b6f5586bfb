"""Signals (foon2asp.asp.interrupts): SIGINT and SIGTERM end a command with one line, and a batch leaves no workers."""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from foon2asp.asp import interrupts
from foon2asp.asp.interrupts import deferred_signals, kept_interrupts
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


def test_a_signal_that_comes_as_a_deferred_section_begins_is_delivered_at_its_end(monkeypatch):
    """SIGINT handled just after the section put its recorder in place (before the section had
    begun in earnest) is the section's: delivered when it ends, never cleared with the last one's."""
    real = signal.signal

    def installing(signum, handler):
        previous = real(signum, handler)
        if signum == signal.SIGINT and handler is interrupts._record:
            signal.raise_signal(signal.SIGINT)  # handled (recorded) as this call returns
        return previous

    monkeypatch.setattr(signal, "signal", installing)
    with pytest.raises(KeyboardInterrupt):
        with deferred_signals():
            pass
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


class _Dropping:
    """An object whose finaliser is interrupted (as clingo's ``Control.__del__`` can be)."""

    def __del__(self):
        raise KeyboardInterrupt


class _HalfBuilt:
    """An object whose finaliser fails because an interrupt stopped its constructor."""

    def __del__(self):
        raise AttributeError("'Control' object has no attribute '_rep'")


def test_an_interrupt_that_a_finaliser_drops_is_raised_at_the_next_deferred_section(capsys):
    entered = []
    with pytest.raises(KeyboardInterrupt):
        with kept_interrupts():
            _Dropping()  # freed at once: Python would print "Exception ignored" and go on
            with deferred_signals():
                entered.append(True)
    assert not entered
    assert capsys.readouterr().err == ""


def test_an_interrupt_that_a_finaliser_drops_is_raised_when_the_body_ends(capsys):
    after, hook = [], sys.unraisablehook
    with pytest.raises(KeyboardInterrupt):
        with kept_interrupts():
            _Dropping()
            after.append(True)
    assert after and capsys.readouterr().err == ""
    assert sys.unraisablehook is hook  # outside, finalisers are reported as before


def test_after_an_interrupt_a_half_built_objects_finaliser_is_not_reported(capsys):
    with pytest.raises(KeyboardInterrupt):
        with kept_interrupts():
            try:
                signal.raise_signal(signal.SIGINT)
            finally:
                _HalfBuilt()
    assert capsys.readouterr().err == ""


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


def _ready(pid: int) -> bool:
    """Has the command's own code started (it catches SIGTERM: foon2asp.__main__)? A signal before
    that reaches the interpreter's own start, which no program can handle."""
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("SigCgt:"):
                return bool(int(line.split()[1], 16) & 1 << (signal.SIGTERM - 1))
    except OSError:
        pass
    return False


def _interrupted_run(args: list[str], seed: int, span: float, results: Path | None = None) -> dict:
    """Start ``foon2asp ARGS``, send SIGINT at a random moment of its first ``span`` seconds once it has
    started (with ``results``: once that results file holds a result), and say how it ended."""
    rng = random.Random(seed)
    # every other run through the installed script, whose batch forks its workers (-m spawns them)
    script = Path(sys.executable).with_name("foon2asp")
    command = [str(script), *map(str, args)] if seed % 2 and script.exists() else _cli(*args)
    proc = subprocess.Popen(command, cwd=REPO, env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 30
    while not _ready(proc.pid) and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.002)
    while results and proc.poll() is None and time.monotonic() < deadline:
        if results.exists() and results.read_bytes().count(b"\n") >= 2:
            break
        time.sleep(0.002)
    time.sleep(rng.uniform(0, span))
    finished = proc.poll() is not None
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    after = time.monotonic() - sent
    return {"args": args, "seed": seed, "finished": finished, "code": proc.returncode, "err": err, "after": after}


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs /proc to see when a command has started")
def test_sigint_at_random_moments_stops_every_command_promptly_with_one_line(shared_foon_dir, tmp_path):
    """120 commands (batch with one and two workers, solve, schedule; long and short ones) each get
    SIGINT at a random moment, two at a time: each ends within two seconds (one on a quiet
    machine; the test runs beside others on two shared cores) with exit status 130 and the one
    line "foon2asp: interrupted" (or had ended before, with 0), whatever it was doing (starting,
    loading, grounding, solving, freeing a control, writing results); a batch's results file
    holds whole lines only, and its batch resumes to the full set of results."""
    foon, demo = str(shared_foon_dir), str(REPO / "data")
    listed = subprocess.run(_cli("objects", "--data", foon, "--format", "json"), env=_env(), capture_output=True)
    goals = tmp_path / "goals.json"
    goals.write_text(json.dumps([o for o in json.loads(listed.stdout) if o["producers"]][:600]))
    batch = ["batch", "--data", foon, "--goals", str(goals), "--output", "{out}", "--workers"]
    # (arguments, seconds within which the signal comes, whether it waits for a result written): the
    # long ones run for seconds, the short ones end in under half a second
    commands = [
        ([*batch, "1"], 1.2, False),
        ([*batch, "2"], 1.2, False),
        ([*batch, "1"], 0.5, True),
        ([*batch, "2"], 0.5, True),
        (["batch", "--data", demo, "--goals", "all-objects", "--output", "{out}"], 0.6, False),
        (["solve", "--data", foon, "--goals", "all-objects", "--format", "json"], 1.2, False),
        (["solve", "--data", demo, "--goals", "all"], 0.6, False),
        (["schedule", "--data", foon, "--goals", "all-objects", "--agents", "arm=2,human=1"], 1.2, False),
        (["schedule", "--data", demo, "--goals", "all", "--agents", "arm=1,human=1"], 0.6, False),
    ]
    runs = []
    for i in range(126):
        args, span, written = commands[i % len(commands)]
        out = tmp_path / f"r{i}.jsonl"
        runs.append(([a.format(out=out) for a in args], 1000 + i, span, out if written else None))
    with ThreadPoolExecutor(2) as pool:
        ends = list(pool.map(lambda run: _interrupted_run(*run), runs))
    # each as expected: it had ended (or was ending) as the signal came, with 0, or it stopped with one line
    wrong = [
        e
        for e in ends
        if not (e["finished"] or e["after"] < 2.0)
        or (e["code"], e["err"]) not in ((0, b""), (130, b"foon2asp: interrupted\n"))
        or e["finished"]
        and e["code"] != 0
    ]
    assert not wrong, "\n".join(
        f"{e['args'][:3]} seed {e['seed']}: {e['code']} after {e['after']:.2f} s: {e['err'].decode()}" for e in wrong
    )
    assert sum(e["code"] == 130 for e in ends) >= 100
    # the results files: whole lines only (a cut line would be dropped, and cut off by --resume)
    outs = [(e, Path(e["args"][e["args"].index("--output") + 1])) for e in ends if e["args"][0] == "batch"]
    outs = [(e, out) for e, out in outs if out.exists() and out.stat().st_size]
    assert len(outs) >= 20
    for _, out in outs:
        data = out.read_bytes()
        assert data.endswith(b"\n"), out
        assert len(read_results(out)) == data.count(b"\n") - 1  # the header, then results
    # an interrupted batch resumes to every goal's result once, the lines written before kept as they were
    chosen = [max((b for b in outs if b[0]["args"][-1] == n), key=lambda b: b[1].stat().st_size) for n in "12"]
    before = [out.read_bytes() for _, out in chosen]
    assert all(data.count(b"\n") > 2 for data in before)

    def resume(e: dict) -> subprocess.CompletedProcess:
        return subprocess.run(_cli(*e["args"], "--resume"), cwd=REPO, env=_env(), capture_output=True, text=True)

    with ThreadPoolExecutor(2) as pool:
        done = list(pool.map(resume, [e for e, _ in chosen]))
    for (_, out), old, finished in zip(chosen, before, done):
        assert finished.returncode == 0, finished.stderr
        assert out.read_bytes().startswith(old)
        records = read_results(out)
        assert len(records) == len({json.dumps(r["goal"], sort_keys=True) for r in records}) == 600
