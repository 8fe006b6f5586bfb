"""Bad input, options, paths, interrupts, locks and canonical trees: one regression test per finding."""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from foon2asp.asp.options import AspOptions
from foon2asp.asp.session import Session
from foon2asp.batch.results import ResultFile, read_header, read_results
from foon2asp.cli.main import main
from foon2asp.methods.bounds import Bounds
from foon2asp.methods.runner import GoalRunner, solve_goals
from helpers import brute_force, build, goal_id, one_line_error

REPO = Path(__file__).resolve().parent.parent
DEMO = REPO / "data"


#: commands that read data: the demo data unless the test names some (there is no silent default)
_DATA_COMMANDS = {"solve", "check", "compare", "reachable", "missing", "query", "batch", "facts", "objects"}


def run(*args):
    argv = [str(a) for a in args]
    if argv and argv[0] in _DATA_COMMANDS and not {"--data", "--foon"} & set(argv):
        argv += ["--data", "demo"]
    return CliRunner().invoke(main, argv)


def demo_copy(tmp_path: Path) -> Path:
    d = tmp_path / "data"
    d.mkdir()
    for f in DEMO.iterdir():
        if f.is_file():
            (d / f.name).write_bytes(f.read_bytes())
    return d


# ---- JSON limits -------------------------------------------------------------------


@pytest.mark.parametrize("name", ["kitchen.json", "goal_nodes.json"])
def test_deeply_nested_json_is_one_located_error(tmp_path, name):
    d = demo_copy(tmp_path)
    (d / name).write_text("[" * 5000 + "]" * 5000)
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert f"{name}:1:101: JSON nested deeper than 100 levels" in msg


def test_huge_number_is_one_located_error(tmp_path):
    d = demo_copy(tmp_path)
    (d / "goal_nodes.json").write_text('[\n {"label": "x", "states": [], "n": ' + "9" * 5000 + "}]")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert "goal_nodes.json:2:" in msg and "number longer than 100 characters" in msg


def test_deep_tree_json_in_check(tmp_path):
    tree = tmp_path / "t.json"
    tree.write_text('{"units": ' + "[" * 5000 + "]" * 5000 + "}")
    msg = one_line_error(run("check", tree, "--no-optimum"))
    assert "t.json:1:" in msg and "nested deeper" in msg


def test_lone_surrogate_in_tree_json(tmp_path):
    tree = tmp_path / "t.json"
    tree.write_text('{"goal": {"label": "tom\\ud800ato"}, "units": []}')
    msg = one_line_error(run("check", tree, "--no-optimum"))
    assert "t.json:1:20: string holds U+D800 (lone surrogate)" in msg


# ---- characters and encodings -------------------------------------------------------


def test_nul_in_a_foon_label_is_refused_with_line_and_column(tmp_path):
    d = demo_copy(tmp_path)
    lines = (d / "FOON.txt").read_text().splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith("O"))
    lines[i] = lines[i][:3] + "\0" + lines[i][3:]
    (d / "FOON.txt").write_text("\n".join(lines) + "\n")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert f"FOON.txt:{i + 1}:4: U+0000 (NUL) is not allowed" in msg


@pytest.mark.parametrize("char", ["\x0b", "\x85", "\u2028", "\x1b"])
def test_control_characters_are_refused_and_escaped(tmp_path, char):
    d = demo_copy(tmp_path)
    (d / "utensils.txt").write_text("knife\nbo" + char + "wl\n", encoding="utf-8")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert "utensils.txt:2:3:" in msg
    assert char not in msg  # shown escaped, never raw


def test_not_utf8_names_line_and_byte(tmp_path):
    d = demo_copy(tmp_path)
    (d / "motion.txt").write_bytes(b"chop\t0.9\nsl\xffice\t0.8\n")
    msg = one_line_error(run("solve", "--data", d, "--goals", "all"))
    assert "motion.txt:2:3: not UTF-8 text: byte 0xff" in msg


def test_bom_and_crlf_are_read(tmp_path):
    d = demo_copy(tmp_path)
    text = (d / "FOON.txt").read_text()
    (d / "FOON.txt").write_bytes(b"\xef\xbb\xbf" + text.replace("\n", "\r\n").encode())
    res = run("solve", "--data", d, "--goal", "tomato salad")
    assert res.exit_code == 0, res.stderr
    assert "units 4" in res.output


@pytest.mark.parametrize(
    "name, text, said, unsaid",
    [
        # a plain comment is no warning; one that looks like a label is
        ("utensils.txt", "# utensils\n#mixing bowl\nknife\n", "utensils.txt:2: line ignored", "utensils.txt:1"),
        ("motion.txt", "# nothing here\n", "no success rate in the file", None),
    ],
)
def test_data_file_lines_without_data_are_warned(tmp_path, name, text, said, unsaid):
    d = demo_copy(tmp_path)
    (d / name).write_text(text)
    res = run("solve", "--data", d, "--goal", "tomato salad")
    assert res.exit_code == 0
    assert said in res.stderr
    assert unsaid is None or unsaid not in res.stderr


def test_empty_goals_file_is_named(tmp_path):
    goals = tmp_path / "g.json"
    goals.write_text("[]")
    msg = one_line_error(run("solve", "--goals", goals))
    assert f"{goals}: the goals file lists no goal" in msg


# ---- options and paths --------------------------------------------------------------


@pytest.mark.parametrize(
    "args, option",
    [
        (["solve", "--goal", "tomato salad", "--max-depth", "2147483648"], "--max-depth"),
        (["solve", "--goal", "tomato salad", "--max-units", "2147483648"], "--max-units"),
        (["solve", "--goal", "tomato salad", "--time-limit", "nan"], "--time-limit"),
        (["solve", "--goal", "tomato salad", "--time-limit", "-1"], "--time-limit"),
        (["solve", "--goal", "tomato salad", "--time-limit", "inf"], "--time-limit"),
        (["batch", "--goals", "all", "--scheduler", "nonsense here"], "--scheduler"),
        (["batch", "--goals", "all", "--scheduler", "tcp://host:99999"], "--scheduler"),
    ],
)
def test_bad_options_are_one_line_naming_the_option(args, option):
    msg = one_line_error(run(*args))
    assert option in msg


def test_max_units_at_the_32_bit_limit_is_not_unreachable():
    res = run("solve", "--goal", "tomato salad", "--max-units", str(2**31 - 1))
    assert res.exit_code == 0, res.stderr
    assert "Status: optimal" in res.output and "units 4" in res.output


def test_output_folders_are_created(tmp_path):
    target = tmp_path / "new" / "deeper" / "x.lp"
    res = run("facts", "-o", target)
    assert res.exit_code == 0, res.stderr
    assert target.read_text().startswith("%") or target.stat().st_size > 0
    merged = tmp_path / "m" / "x.txt"
    assert run("merge", DEMO / "FOON.txt", "-o", merged).exit_code == 0 and merged.exists()
    out = tmp_path / "trees" / "sub"
    assert run("solve", "--goal", "tomato salad", "--output", out).exit_code == 0
    assert len(list(out.iterdir())) == 1


@pytest.mark.parametrize(
    "args",
    [
        ["solve", "--goal", "tomato salad", "--output", "/proc/version/x"],
        ["facts", "-o", "/proc/version/x.lp"],
        ["merge", str(DEMO / "FOON.txt"), "-o", "/proc/version/x.txt"],
        ["batch", "--goals", "all", "--output", "/proc/version/x.jsonl"],
    ],
)
def test_unwritable_outputs_are_one_line_naming_the_path(args):
    msg = one_line_error(run(*args))
    assert "/proc/version" in msg


def test_internal_error_is_exit_3_with_traceback_only_under_debug(monkeypatch):
    from foon2asp.foon import goals

    def boom(*a, **k):
        raise ZeroDivisionError("boom")

    monkeypatch.setattr(goals, "resolve", boom)
    msg = one_line_error(run("solve", "--goal", "x"), code=3)
    assert "internal error: ZeroDivisionError: boom" in msg and "please report" in msg
    res = CliRunner().invoke(main, ["--debug", "solve", "--data", "demo", "--goal", "x"])
    assert res.exit_code == 3 and "Traceback" in res.stderr


# ---- interrupts ---------------------------------------------------------------------


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


# ---- the results file: lock and header ----------------------------------------------


def test_second_writer_is_refused(tmp_path):
    out = tmp_path / "r.jsonl"
    with ResultFile(out):
        msg = one_line_error(run("batch", "--goals", "all", "--output", out, "--resume", "--no-progress"))
    assert "in use by another running batch" in msg


def test_header_records_the_configuration_and_resume_checks_it(tmp_path):
    out = tmp_path / "r.jsonl"
    assert run("batch", "--goal", "tomato salad", "--output", out, "--no-progress").exit_code == 0
    first = json.loads(out.read_text().splitlines()[0])
    assert first["foon2asp_results"] == 1
    config = read_header(out)
    assert config["objective"] == ["units"] and len(config["input_sha256"]) == 64
    assert len(read_results(out)) == 1
    msg = one_line_error(run("batch", "--goals", "all", "--output", out, "--resume", "--objective", "success"))
    assert "differs in: objective" in msg
    msg = one_line_error(run("batch", "--goals", "all", "--output", out, "--resume", "--time-limit", "5"))
    assert "differs in: time_limit" in msg
    res = run("batch", "--goals", "all", "--output", out, "--resume", "--no-progress")
    assert res.exit_code == 0 and "1 already done" in res.output
    assert out.read_text().count("foon2asp_results") == 1


# ---- canonical trees ----------------------------------------------------------------


def canonical_brute(problem, goal):
    trees = brute_force(problem, goal)
    top = min(len(t) for t in trees)
    n = len(problem.units)
    return min((t for t in trees if len(t) == top), key=lambda t: [0 if u in t else 1 for u in range(n)])


def random_foon(seed: int):
    rng = random.Random(seed)
    kitchen = ["k0", "k1", "k2", "k3"]
    objects = list(kitchen)
    units = []
    for i in range(rng.randint(4, 9)):
        ins = rng.sample(objects, rng.randint(1, min(2, len(objects))))
        out = f"o{rng.randint(0, 4)}"
        units.append((f"m{i}", ins, [out]))
        if out not in objects:
            objects.append(out)
    return build(units, kitchen)


@pytest.mark.parametrize("seed", range(12))
def test_canonical_tree_is_the_smallest_optimal_tree_in_every_grounding(seed):
    problem = random_foon(seed)
    goals = sorted({goal_id(problem, f"o{k}") for k in range(5) if f"o{k}" in {o.label for o in problem.objects}})
    for g in goals:
        if not brute_force(problem, g):
            continue
        want = canonical_brute(problem, g)
        trees = {
            "session": Session(problem, AspOptions()).solve(g),
            "driver": Session(problem, AspOptions(models=2)).solve(g),
        }
        for name, tree in trees.items():
            assert tuple(sorted(tree.units)) == want, (name, seed, g)
        # the goal runner's canonical tree: the bounds tree when it is optimal, else the smallest optimal one
        bounds_tree = Bounds(problem).tree(g)
        if bounds_tree is not None and len(bounds_tree) == len(want):
            want = bounds_tree
        for grounding in ("whole", "per-goal"):
            for shortcuts in (True, False):
                tree = GoalRunner("asp", problem, AspOptions(), grounding, shortcuts=shortcuts)(g)
                assert tuple(sorted(tree.units)) == want, (grounding, shortcuts, seed, g)


def test_same_trees_from_solve_batch_workers_and_groundings(shared_foon_dir, tmp_path):
    res = run("solve", "--data", shared_foon_dir, "--goals", "all", "--format", "json")
    assert res.exit_code == 0
    solved = {
        json.dumps(r["goal"], sort_keys=True): sorted(
            u["id"] if "id" in u else json.dumps(u, sort_keys=True) for u in r["units"]
        )
        for r in json.loads(res.output)
    }
    for extra in ([], ["--workers", "2"], ["--grounding", "per-goal"], ["--no-shortcuts"]):
        out = tmp_path / f"b{len(extra)}{'-'.join(extra)}.jsonl"
        res = run("batch", "--data", shared_foon_dir, "--goals", "all", "--output", out, "--no-progress", *extra)
        assert res.exit_code == 0, res.stderr
        batch = {
            json.dumps(r["goal"], sort_keys=True): sorted(
                u["id"] if "id" in u else json.dumps(u, sort_keys=True) for u in r["units"]
            )
            for r in read_results(out)
        }
        assert batch == solved, extra


def test_a_goal_the_bounds_decide_gets_the_same_tree_everywhere(shared_problem, shared_foon_dir, tmp_path):
    """A goal whose bounds tree is optimal but not the smallest optimal tree: solve, batch
    (both groundings, with and without shortcuts, two workers) and the library all give the
    bounds tree, the canonical one."""
    _, problem = shared_problem
    runner = GoalRunner("asp", problem, AspOptions(), "per-goal")
    bounds = Bounds(problem)
    goal = None
    for g in sorted(problem.derivable):
        tree = runner(g)
        upper = bounds.upper(g)
        if upper is None or bounds.lower(g) < upper or not tree.proven_by == "clingo":
            continue
        smallest = Session(problem, AspOptions()).solve(g)
        if sorted(smallest.units) != sorted(tree.units):
            goal = g
            break
    assert goal is not None, "no goal where the bounds tree differs from the smallest optimal tree"
    want = list(bounds.tree(goal))
    assert len(want) == len(smallest.units)
    trees = [next(iter(solve_goals(problem, [goal], "asp", AspOptions())))]
    trees += [GoalRunner("asp", problem, AspOptions(), gr, sc)(goal) for gr in ("whole", "per-goal") for sc in (1, 0)]
    for tree in trees:
        assert tree.status == "optimal" and sorted(tree.units) == want
    label = problem.objects[goal].to_json()
    key = json.dumps(label, sort_keys=True)
    res = run("solve", "--data", shared_foon_dir, "--goal", f"#{goal}", "--format", "json")
    assert res.exit_code == 0, res.stderr
    solved = json.loads(res.output)
    solved = solved[0] if isinstance(solved, list) else solved
    for extra in ([], ["--workers", "2", "--no-shortcuts"], ["--grounding", "per-goal"]):
        out = tmp_path / f"b{len(extra)}.jsonl"
        res = run("batch", "--data", shared_foon_dir, "--goal", f"#{goal}", "--output", out, "--no-progress", *extra)
        assert res.exit_code == 0, res.stderr
        (record,) = [r for r in read_results(out) if json.dumps(r["goal"], sort_keys=True) == key]
        assert record["units"] == solved["units"], extra
        assert len(record["units"]) == len(want)
