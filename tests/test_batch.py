"""Batch solving: equal to single solves, resumable after a kill, workers, Dask, summary, synthetic FOONs."""

from __future__ import annotations

import csv
import io
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import foon2asp
from foon2asp import methods
from foon2asp.asp.options import AspOptions
from foon2asp.batch.pool import BatchSpec, dask_executor
from foon2asp.batch.results_file import read_results, run_batch, summarize
from foon2asp.errors import InputError
from foon2asp.foon import goals as goals_mod
from foon2asp.methods.plan import session_of as Session
from foon2asp.methods.runner import GoalRunner
from foon2asp.report.tables import render_summary
from foon2asp.tree.serialize import tree_json
from foon2asp.tree.validate import validate
from helpers import best, build, goal_id
from synth import shape, synthesize

REPO = Path(__file__).resolve().parent.parent


def key(record: dict) -> tuple:
    return (json.dumps(record["goal"], sort_keys=True), record["requested_method"])


def outcome(record: dict) -> tuple:
    """What must agree between runs: status and the optimised cost (the tree may be another optimum)."""
    return (record["status"], record["cost"].get("units"))


def choice_foon():
    """g has two producers (1 unit vs 2 units); c only via a cycle; h has one chain (no choice)."""
    return build(
        [
            ("mix", ["a", "b"], ["g"]),  # 0: needs a and b
            ("cut", ["k"], ["a"]),  # 1
            ("cut", ["l"], ["b"]),  # 2
            ("bake", ["m"], ["g"]),  # 3: the one-unit tree
            ("boil", ["c"], ["d"]),  # 4: c rests on a cycle
            ("boil", ["d"], ["c"]),  # 5
            ("fry", ["a"], ["h"]),  # 6: h <- a <- k, no choice
        ],
        kitchen=["k", "l", "m"],
        rates={"mix": 0.9, "cut": 0.5, "bake": 0.2, "fry": 0.8},
    )


# ---------------------------------------------------------------- equal to single solves


@pytest.mark.parametrize("grounding", ["whole", "per-goal"])
@pytest.mark.parametrize("shortcuts", [True, False])
def test_batch_equals_brute_force_on_small_foon(tmp_path, grounding, shortcuts):
    p = choice_foon()
    goals = [goal_id(p, x) for x in ("g", "h", "d", "a")]
    spec = BatchSpec(p, ["asp"], AspOptions(), grounding, shortcuts)
    report = run_batch(spec, goals, tmp_path / "r.jsonl", progress=False)
    assert report.done == 4
    records = read_results(tmp_path / "r.jsonl")
    by_goal = {r["goal"]["label"]: r for r in records}
    for label, g in zip("ghda", goals):
        top, trees = best(p, g, lambda m: m["units"])
        rec = by_goal[label]
        if not trees:
            assert rec["status"] == "unreachable"
            continue
        assert rec["status"] == "optimal"
        assert rec["cost"]["units"] == top
    assert by_goal["g"]["cost"]["units"] == 1  # the bake unit, not mix + two cuts
    assert by_goal["h"]["cost"]["units"] == 2
    assert by_goal["d"]["status"] == "unreachable"


def test_shortcut_matches_solver_exactly():
    """A no-choice goal: the shortcut gives the solver's tree, measures and asp_cost."""
    p = choice_foon()
    h = goal_id(p, "h")
    for objective in (("units",), ("success",), ("inputs",)):
        options = AspOptions(objective=objective)
        fast = GoalRunner("asp", p, options, "whole", shortcuts=True)
        fast(goal_id(p, "g"))
        tree = fast(h)
        assert fast.counts["only-tree"] == 1
        ref = Session(p, options).solve(h)
        assert tree.proven_by == "only-tree" and tree.stats == {}
        same = {"time_s": 0, "stats": None, "proven_by": None}
        assert tree_json(p, tree) | same == tree_json(p, ref) | same


def test_batch_equals_solve_on_shared(shared_problem, tmp_path):
    data, p = shared_problem
    goal_ids = goals_mod.resolve(data, p, None, "all")
    spec = BatchSpec(p, ["asp", "gbfs-h1"], AspOptions())
    run_batch(spec, goal_ids, tmp_path / "r.jsonl", progress=False)
    records = {key(r): r for r in read_results(tmp_path / "r.jsonl")}
    assert len(records) == 2 * len(set(goal_ids))
    for name in ("asp", "gbfs-h1"):
        run = methods.runner(name, p, AspOptions())
        for g in goal_ids:
            single = tree_json(p, run(g))
            single["requested_method"] = name
            rec = records[key(single)]
            assert outcome(rec) == outcome(single)
            if name == "gbfs-h1":
                assert rec["units"] == single["units"]  # deterministic search: the same tree
            if rec["status"] == "optimal":
                units = [unit_id(p, u) for u in rec["units"]]
                assert validate(p, g, units).valid
    statuses = {r["status"] for r in records.values() if r["requested_method"] == "asp"}
    assert statuses == {"optimal", "unreachable"}


def unit_id(problem, unit_json: dict) -> int:
    from foon2asp.foon.loaders import object_from_json
    from foon2asp.foon.model import Unit

    unit = Unit(
        unit_json["motion"],
        tuple(object_from_json(o, "", 0) for o in unit_json["inputs"]),
        tuple(object_from_json(o, "", 0) for o in unit_json["outputs"]),
    )
    return problem.foon._keys[unit.key()]


# ---------------------------------------------------------------- resume


def test_resume_after_kill_loses_and_repeats_nothing(shared_foon_dir, shared_problem, tmp_path):
    data, p = shared_problem
    objects = goals_mod.all_objects(p)[:120]
    goals_file = tmp_path / "goals.json"
    goals_file.write_text(json.dumps([p.objects[o].to_json() for o in objects]))
    out = tmp_path / "r.jsonl"
    cmd = [
        sys.executable,
        "-m",
        "foon2asp",
        "batch",
        "--data",
        str(shared_foon_dir),
        "--goals",
        str(goals_file),
        "--methods",
        "asp,gbfs-h1",
        "--no-shortcuts",
        "--output",
        str(out),
    ]
    env = dict(os.environ, PYTHONPATH=str(REPO))
    proc = subprocess.Popen(cmd, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.time() + 60
    while time.time() < deadline:
        if out.exists() and out.read_bytes().count(b"\n") >= 41:
            break
        time.sleep(0.01)
    assert proc.poll() is None, "the batch finished before it could be killed"
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    before = out.read_bytes()
    assert before.endswith(b"\n"), "a killed batch left a broken line"
    first = read_results(out)
    assert 40 <= len(first) < 240
    # a machine crash could still cut a line: simulate one
    with open(out, "ab") as fh:
        fh.write(b'{"goal": {"label": "cut sh')
    done = subprocess.run(cmd + ["--resume"], cwd=REPO, env=env, capture_output=True, text=True, timeout=120)
    invalid = any(r["status"] == "found" and r["valid"] is False for r in read_results(out))
    assert done.returncode == (1 if invalid else 0), done.stderr
    assert f"{240 - len(first)} new result(s), {len(first)} already done" in done.stdout
    final = read_results(out)
    assert out.read_bytes().startswith(before)  # finished lines kept byte for byte
    keys = [key(r) for r in final]
    assert len(keys) == len(set(keys)) == 240  # nothing lost, nothing repeated
    assert all(json.loads(line) for line in out.read_text().splitlines())


def test_existing_output_needs_resume(tmp_path):
    out = tmp_path / "r.jsonl"
    out.write_text('{"goal": {"label": "x"}, "status": "optimal"}\n')
    env = dict(os.environ, PYTHONPATH=str(REPO))
    cmd = [sys.executable, "-m", "foon2asp", "batch", "--data", "demo", "--goals", "all", "--output", str(out)]
    done = subprocess.run(cmd, cwd=REPO, env=env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert "use --resume" in done.stderr and "Traceback" not in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1


def test_read_results_repairs_cut_line_and_rejects_bad_middle(tmp_path):
    path = tmp_path / "r.jsonl"
    path.write_text('{"a": 1}\n{"b": 2}\n{"c": ')
    assert read_results(path, repair=True) == [{"a": 1}, {"b": 2}]
    assert path.read_text() == '{"a": 1}\n{"b": 2}\n'
    path.write_text('{"a": 1}\nnot json\n{"b": 2}\n')
    with pytest.raises(InputError) as err:
        read_results(path)
    assert "line 2" in str(err.value) or ":2" in str(err.value)


# ---------------------------------------------------------------- workers and Dask


def _subset(p, n=60):
    objects = goals_mod.all_objects(p)
    return objects[:: max(1, len(objects) // n)][:n]


def test_workers_give_same_results(shared_problem, tmp_path):
    _, p = shared_problem
    goal_ids = _subset(p)
    spec = BatchSpec(p, ["asp", "gbfs-h2"], AspOptions())
    one = run_batch(spec, goal_ids, tmp_path / "one.jsonl", progress=False)
    two = run_batch(spec, goal_ids, tmp_path / "two.jsonl", workers=2, progress=False)
    assert one.done == two.done == 2 * len(goal_ids)
    a = {key(r): outcome(r) for r in read_results(tmp_path / "one.jsonl")}
    b = {key(r): outcome(r) for r in read_results(tmp_path / "two.jsonl")}
    assert a == b
    assert {s for s, _ in a.values()} >= {"optimal", "found"}


def test_auto_workers_hand_the_rest_to_a_pool(shared_problem, tmp_path, monkeypatch):
    """AUTO: a short batch stays in this process; one past the switch time goes on in a pool
    of every usable core, with the same results as one process."""
    from foon2asp.batch import pool

    _, p = shared_problem
    goal_ids = _subset(p, 24)
    spec = BatchSpec(p, ["asp"], AspOptions())
    one = run_batch(spec, goal_ids, tmp_path / "one.jsonl", progress=False)
    short = run_batch(spec, goal_ids, tmp_path / "short.jsonl", workers=pool.AUTO, progress=False)
    assert short.workers == 1
    monkeypatch.setattr(pool, "SWITCH_S", 0.0)
    cores = pool.usable_cores()
    long = run_batch(spec, goal_ids, tmp_path / "long.jsonl", workers=pool.AUTO, progress=False)
    assert long.workers == cores
    assert one.done == short.done == long.done == len(goal_ids)
    results = [
        {key(r): outcome(r) for r in read_results(tmp_path / f"{name}.jsonl")} for name in ("one", "short", "long")
    ]
    assert results[0] == results[1] == results[2]
    assert {s for s, _ in results[0].values()} == {"optimal"}


def test_workers_option_takes_a_number_or_auto(shared_foon_dir, tmp_path):
    from click.testing import CliRunner

    from foon2asp.cli import main

    base = ["batch", "--data", str(shared_foon_dir), "--goal", "#0"]
    for bad, said in (("0", "0 is not in 1..1024"), ("x", "'x' is not a number of workers or 'auto'")):
        got = CliRunner().invoke(main, [*base, "-o", str(tmp_path / f"{bad}.jsonl"), "--workers", bad])
        assert got.exit_code == 2 and said in got.output, got.output
    for good in ("auto", "AUTO", "1"):
        got = CliRunner().invoke(main, [*base, "-o", str(tmp_path / f"{good}.jsonl"), "--workers", good])
        assert got.exit_code == 0, got.output
        assert "with 1 worker(s)" in got.output
    kb = foon2asp.load(shared_foon_dir)
    assert kb.batch(goals=["#0"], workers="auto").workers == 1
    for bad in (0, "two", True):
        with pytest.raises(InputError, match="workers must be 1..1024 or 'auto'"):
            kb.batch(goals=["#0"], workers=bad)


# A batch script as researchers write it: no ``if __name__ == "__main__":`` guard.
# argv: results file, start method ("" chooses), "thread" (another thread runs meanwhile)
UNGUARDED = """
import sys, threading
from foon2asp.batch import pool
pool.START_METHOD = sys.argv[2] or None
if "thread" in sys.argv[3:]:
    stop = threading.Event()
    threading.Thread(target=stop.wait).start()
import foon2asp
kb = foon2asp.load({data!r})
try:
    run = kb.batch(goals="all-objects", output=sys.argv[1], workers=2)
finally:
    if "thread" in sys.argv[3:]:
        stop.set()
print("done", run.done, "workers", run.workers)
"""


def _run_script(tmp_path, text, *args):
    script = tmp_path / "script.py"
    script.write_text(text.format(data=str(REPO / "data")))
    out = tmp_path / "r.jsonl"
    env = dict(os.environ, PYTHONPATH=str(REPO))
    t0 = time.perf_counter()
    try:
        done = subprocess.run(
            [sys.executable, str(script), str(out), *args],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            timeout=90,
        )
    except subprocess.TimeoutExpired:  # the workers ran the script again and the pool replaced them forever
        pytest.fail("the batch script did not end within 90 s")
    return done, out, time.perf_counter() - t0


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="workers are forked on Linux only")
def test_script_without_main_guard_runs_its_pool(tmp_path):
    done, out, _ = _run_script(tmp_path, UNGUARDED, "")
    assert done.returncode == 0, done.stderr
    lines = out.read_text().splitlines()
    assert done.stdout.split() == ["done", str(len(lines) - 1), "workers", "2"]
    assert len(lines) > 10 and all(json.loads(line)["status"] for line in lines[1:])
    assert "RuntimeError" not in done.stderr


@pytest.mark.parametrize("how", [("spawn",), ("forkserver",), ("", "thread")])
def test_script_without_main_guard_stops_at_once_where_workers_run_it_again(tmp_path, how):
    """Spawned workers (also forkserver's, and any worker while another thread runs) run the script
    again: the batch stops at once, saying what to add, and writes no result."""
    done, out, elapsed = _run_script(tmp_path, UNGUARDED, *how)
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last.endswith('put the script\'s code under `if __name__ == "__main__":` (or use workers=1)'), done.stderr
    assert "RuntimeError" not in done.stderr and "done" not in done.stdout
    assert len(out.read_text().splitlines()) == 1  # the header alone
    assert elapsed < 30


def test_guarded_script_runs_its_pool_with_spawned_workers(tmp_path):
    body = UNGUARDED.split("import foon2asp\n")[1]
    guarded = (
        "import sys\nfrom foon2asp.batch import pool\npool.START_METHOD = sys.argv[2] or None\n"
        "import foon2asp\n\ndef main():\n"
        + "".join(f"    {line}\n" for line in body.splitlines())
        + "\nif __name__ == '__main__':\n    main()\n"
    )
    done, out, _ = _run_script(tmp_path, guarded, "spawn")
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["done", str(len(out.read_text().splitlines()) - 1), "workers", "2"]


def test_dask_local_cluster(shared_problem, tmp_path):
    distributed = pytest.importorskip("distributed")

    _, p = shared_problem
    goal_ids = _subset(p, 40)
    spec = BatchSpec(p, ["asp", "gbfs-h1"], AspOptions())
    local = run_batch(spec, goal_ids, tmp_path / "local.jsonl", progress=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None, processes=True) as cluster:
        with distributed.Client(cluster) as client:
            remote = run_batch(
                spec, goal_ids, tmp_path / "dask.jsonl", progress=False, executor=dask_executor(client, chunk=5)
            )
    assert remote.done == local.done == 80
    a = {key(r): outcome(r) for r in read_results(tmp_path / "local.jsonl")}
    b = {key(r): outcome(r) for r in read_results(tmp_path / "dask.jsonl")}
    assert a == b

    def trees(name):
        return {key(r): r["units"] for r in read_results(tmp_path / name) if r["requested_method"] == "asp"}

    assert trees("local.jsonl") == trees("dask.jsonl")  # canonical trees: the same trees on Dask


def test_dask_missing_is_a_clear_error(monkeypatch):
    import builtins

    real = builtins.__import__

    def fake(name, *args, **kwargs):
        if name == "distributed":
            raise ModuleNotFoundError("No module named 'distributed'", name="distributed")
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", fake)
    with pytest.raises(InputError, match=r"foon2asp\[dask\]"):
        dask_executor("tcp://127.0.0.1:1")


# ---------------------------------------------------------------- summary


def test_summary_counts_and_formats(tmp_path):
    p = choice_foon()
    goals = [goal_id(p, x) for x in ("g", "h", "d")]
    report = run_batch(BatchSpec(p, ["asp", "gbfs-h1"]), goals, tmp_path / "r.jsonl", progress=False)
    rows = {r["method"]: r for r in summarize(report.records)}
    assert rows["asp"]["statuses"] == {"optimal": 2, "unreachable": 1}
    assert (rows["asp"]["units_min"], rows["asp"]["units_max"]) == (1, 2)
    assert rows["gbfs-h1"]["results"] == 3
    table = list(csv.DictReader(io.StringIO(render_summary(list(rows.values()), "csv"))))
    assert {t["method"] for t in table} == {"asp", "gbfs-h1"}
    assert table[0]["statuses"] in ("optimal=2 unreachable=1", "found=2 not-found=1") or table[0]["statuses"]
    md = render_summary(list(rows.values()), "markdown", report)
    assert "| method | results |" in md and "| asp | 3 | optimal=2 unreachable=1 |" in md
    assert "6 new result(s)" in render_summary(list(rows.values()), "text", report)


def test_all_objects_count(shared_problem):
    _, p = shared_problem
    objects = goals_mod.all_objects(p)
    # independently: outputs that count as products, minus kitchen items
    made = {o for u in range(len(p.units)) for o in p.products[u]}
    assert len(objects) == len(made - p.kitchen)
    assert len(objects) > 3000


# ---------------------------------------------------------------- synthetic FOONs


def test_synthetic_foon_keeps_shape(shared_problem):
    data, p = shared_problem
    base = shape(p)
    syn = synthesize(data, 3, seed=7)
    q = syn.problem()
    s = shape(q)
    assert s["units"] >= 3 * base["units"]
    assert s["units"] <= 3 * base["units"] * 1.05
    assert abs(s["producers_per_object"] - base["producers_per_object"]) < 0.1
    assert abs(s["required_inputs_per_unit"] - base["required_inputs_per_unit"]) < 0.1
    assert s["max_depth"] == base["max_depth"]
    assert s["derivable"] >= 3 * base["derivable"]
    assert s["cycles"] >= 2 * base["cycles"]  # cross-links may join cycles of two copies
    # seeded: the same seed gives the same FOON, another seed another one
    again = synthesize(data, 3, seed=7)
    assert [u.key() for u in again.foon.units] == [u.key() for u in syn.foon.units]
    other = synthesize(data, 3, seed=8)
    assert [u.key() for u in other.foon.units] != [u.key() for u in syn.foon.units]


def test_synthetic_copy_solves_like_base(shared_problem, tmp_path):
    """A goal of copy 2 has a tree at most as large as in the base (cross-links only add producers)."""
    data, p = shared_problem
    syn = synthesize(data, 3, seed=1)
    syn.write(tmp_path / "syn")
    from foon2asp.foon.loaders import Dataset
    from foon2asp.foon.problem import Problem

    q = Problem.from_dataset(Dataset.load(tmp_path / "syn"))
    assert len(q.units) == len(syn.foon.units)
    base_goal = goals_mod.resolve(data, p, ("greek salad",), None)[0]
    obj = p.objects[base_goal]
    from synth import _rename

    copy_goal = q.foon.object_ids[_rename(obj, 2)]
    base_tree = Session(p).solve(base_goal)
    runner = GoalRunner("asp", q, AspOptions(opt_strategy="usc"), "per-goal")
    tree = runner(copy_goal)
    assert tree.status == base_tree.status == "optimal"
    assert len(tree.units) <= len(base_tree.units)
    assert validate(q, copy_goal, tree.units).valid


def test_a_pool_ends_without_a_traceback(shared_foon_dir, tmp_path):
    """The pool ends its workers with SIGTERM: nothing but the summary reaches stderr."""
    import subprocess
    import sys

    out = tmp_path / "r.jsonl"
    cmd = [sys.executable, "-m", "foon2asp", "batch", "--data", str(shared_foon_dir), "--goals", "all"]
    done = subprocess.run([*cmd, "--workers", "2", "-o", str(out), "--no-progress"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr and "Terminated" not in done.stderr, done.stderr
    assert len(out.read_text().splitlines()) > 25


def test_a_command_that_starts_no_pool_never_imports_multiprocessing(tmp_path):
    """Importing multiprocessing reads the kernel's randomness in the way that waits until the
    kernel has gathered enough (a minute on a freshly started machine): only a pool imports it."""
    probe = (
        "import sys; from foon2asp.cli.main import main\n"
        "try:\n    main(sys.argv[1:])\nexcept SystemExit:\n    pass\n"
        "print('multiprocessing' in sys.modules, file=sys.stderr)\n"
    )
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parent.parent))

    def imports_it(*args: str) -> str:
        done = subprocess.run([sys.executable, "-c", probe, *args], env=env, capture_output=True, text=True)
        return done.stderr.splitlines()[-1]

    assert imports_it("solve", "--data", "demo", "--goal", "tomato salad") == "False"
    assert (
        imports_it("merge", str(foon2asp.api.load("demo").data.paths["foon"]), "-o", str(tmp_path / "m.txt")) == "False"
    )
    one = ["batch", "--data", "demo", "--workers", "1", "--output", str(tmp_path / "r1.jsonl")]
    assert imports_it(*one) == "False"
    two = ["batch", "--data", "demo", "--workers", "2", "--output", str(tmp_path / "r2.jsonl")]
    assert imports_it(*two) == "True"
    assert len(read_results(tmp_path / "r2.jsonl")) == len(read_results(tmp_path / "r1.jsonl")) > 0
