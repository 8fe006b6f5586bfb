"""`foon2asp schedule`, `batch --schedule`, `check` of schedules and the library calls behind them."""

from __future__ import annotations

import copy
import json
import random
import shutil
from decimal import Decimal

import pytest

import foon2asp
from conftest import REPO
from foon2asp import api
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.spec import ScheduleSpec
from helpers import build
from test_cli import assert_one_line_error, run
from test_solve import (
    AGENT_SETS,
    ENCODINGS,
    brute_schedule,
    longer_tree_shorter_chain,
    random_spec,
    random_tree,
)

needs_dot = pytest.mark.skipif(shutil.which("neato") is None, reason="Graphviz is not installed")

#: the keys issue 20 names for every object of `schedule --format json`
KEYS = {"goal", "status", "makespan", "bounds", "baseline", "agents", "schedule", "tree"}
KNIFE = ("knife",)


def write_data(tmp_path, problem, name="data"):
    d = tmp_path / name
    api.write_foon(problem.foon, d / "FOON.txt")
    (d / "kitchen.json").write_text(json.dumps([o.to_json() for o in problem.kitchen_items]))
    return d


def spec_files(tmp_path, spec: ScheduleSpec) -> list[str]:
    """The schedule options that give ``spec``: --agents and the three files."""
    d = spec.durations
    table: dict = {m: float(Decimal(v) / 1000) for m, v in d.motions.items()}
    table.update({k: {m: float(Decimal(v) / 1000) for m, v in t.items()} for k, t in d.kinds.items()})
    files = {
        "durations": json.dumps(table),
        "capabilities": json.dumps({k: sorted(v) for k, v in spec.capabilities.items()}),
        "resources": json.dumps(dict(spec.resources)),
    }
    args = ["--agents", ",".join(f"{k}={n}" for k, n in spec.agents)]
    for name, text in files.items():
        path = tmp_path / f"{name}.json"
        path.write_text(text)
        args += [f"--{name}", path]
    return args


# ---------------------------------------------------------------- the JSON on ../shared/foon


def test_json_keys_statuses_and_the_library(shared_foon_dir):
    res = run("schedule", "--data", shared_foon_dir, "--goals", "all", "--agents", "arm=2", "--format", "json")
    out = json.loads(res.stdout)
    assert isinstance(out, list) and len(out) == 25
    kb = foon2asp.load(shared_foon_dir)
    spec = ScheduleSpec((("arm", 2),))
    lib = kb.schedule("all", agents="arm=2")
    assert [s.to_dict()["goal"] for s in lib] == [r["goal"] for r in out]
    statuses = {}
    for r, s in zip(out, lib):
        assert KEYS <= set(r), KEYS - set(r)
        statuses[r["status"]] = statuses.get(r["status"], 0) + 1
        assert r["agents"] == ["arm-1", "arm-2"] and s.makespan == r["makespan"]
        if r["status"] == "unreachable":
            assert r["makespan"] is None and r["schedule"] == [] and r["bounds"] == {} and r["baseline"] == {}
            continue
        assert r["status"] == "optimal"
        assert set(r["bounds"]) >= {"chain", "work", "lower"} and r["baseline"]["method"] == "longest-chain-first"
        assert r["bounds"]["lower"] <= r["makespan"] <= r["baseline"]["makespan"]
        assert set(r["schedule"][0]) == {"unit", "agent", "start", "end"}
        assert set(r["schedule"][0]["unit"]) == {"motion", "inputs", "outputs"}
        assert len(r["schedule"]) == len(r["tree"]["units"])
        assert check_schedule(kb.problem, r, spec) is None
    assert statuses == {"optimal": 23, "unreachable": 2}
    assert res.exit_code == 0


def test_the_text_says_the_lower_bound_is_the_one_known_before_the_search():
    res = run("schedule", "--data", "demo", "--goal", "scrambled egg", "--agents", "arm=1,human=1")
    assert res.stdout.splitlines()[1] == (
        "Status: optimal  Makespan: 3 s  (list scheduling 3 s; lower bound before the search 3 s: chain 3 s,"
        " work 2 s, energy 3 s)"
    )


def test_text_is_a_timeline_per_agent_with_bounds_and_baseline(shared_foon_dir, tmp_path):
    table = tmp_path / "d.json"
    table.write_text('{"*": 2, "pour": 1.5}')
    res = run("schedule", "--data", shared_foon_dir, "--goal", "greek salad", "--agents", "arm=2,human=1",
              "--durations", table)  # fmt: skip
    text = res.stdout
    assert "Status: optimal  Makespan: " in text and "list scheduling " in text and "lower bound " in text
    lanes = [line.strip() for line in text.splitlines() if line.startswith("  ") and line.strip().endswith(":")]
    assert lanes == ["arm-1:", "arm-2:", "human-1:"]
    lib = foon2asp.load(shared_foon_dir).schedule("greek salad", agents="arm=2,human=1", durations=table)
    assert lib.to_text() == text and f"Makespan: {lib.makespan:g} s" in text


# ---------------------------------------------------------------- optimal = brute force


@pytest.mark.parametrize("seed", range(8))
def test_cli_makespan_equals_brute_force(seed, tmp_path):
    rng = random.Random(100 + seed)
    kinds = AGENT_SETS[seed % len(AGENT_SETS)]
    problem, goal, units = random_tree(rng, 4 if seed % 4 == 3 else 5)
    spec = random_spec(rng, kinds)
    want = brute_schedule(problem, units, spec)
    d = write_data(tmp_path, problem)
    encoding = ENCODINGS[seed % len(ENCODINGS)]
    args = ["schedule", "--data", d, "--goal", problem.objects[goal].label, "--format", "json", "--encoding", encoding]
    res = run(*args, *spec_files(tmp_path, spec))
    (r,) = json.loads(res.stdout)
    if want is None:
        assert r["status"] == "unschedulable" and r["makespan"] is None and "no agent can do" in r["reason"]
        return
    assert r["status"] == "optimal" and r["encoding"] == encoding
    assert round(r["makespan"] * 1000) == want[0] and r["human_units"] == want[1]
    kb = foon2asp.load(d)
    assert check_schedule(kb.problem, r, spec) is None
    path = tmp_path / "s.json"
    path.write_text(res.stdout)
    assert run("check", path, "--data", d, *spec_files(tmp_path, spec)).exit_code == 0


def test_unschedulable_is_a_status_not_an_error(shared_foon_dir, tmp_path):
    caps = tmp_path / "caps.json"
    caps.write_text('{"arm": ["pour"]}')
    res = run("schedule", "--data", shared_foon_dir, "--goal", "greek salad", "--agents", "arm=1",
              "--capabilities", caps, "--format", "json")  # fmt: skip
    (r,) = json.loads(res.stdout)
    assert r["status"] == "unschedulable" and r["makespan"] is None and "no agent can do" in r["reason"]
    assert res.exit_code == 0
    both = ["--agents", "arm=1,robot=1", "--capabilities", caps]
    res = run("schedule", "--data", shared_foon_dir, "--goal", "greek salad", *both)
    assert "Status: optimal" in res.stdout  # a kind not listed (robot) can do every motion, with a note
    assert res.stderr == (
        "foon2asp: warning: agents 'arm=1,robot=1': no capabilities file names the kind \"robot\": it can do"
        " every motion\n"
    )


def test_a_misspelt_kind_is_an_error_not_a_schedule_that_breaks_the_file(tmp_path):
    """--agents arms=2 with a capabilities file keyed "arm": no schedule with the heat the file forbids."""
    caps = tmp_path / "arm-only.json"
    caps.write_text('{"arm": ["crack", "beat", "fry"]}')
    base = ["schedule", "--data", "demo", "--goal", "scrambled egg", "--capabilities", caps]
    assert "Status: unschedulable" in run(*base, "--agents", "arm=2").stdout
    assert_one_line_error(
        run(*base, "--agents", "arms=2", ok=False), f'{caps}:1: no agent has the kind "arm"', "did you mean arms?"
    )
    assert_one_line_error(run(*base, "--agents", "arm=2,humann=1", ok=False), '"humann"', "did you mean human?")
    assert_one_line_error(
        run("schedule", "--data", "demo", "--goal", "scrambled egg", "--agents", "humann=1", ok=False),
        'agents \'humann=1\': the kind "humann" is named in no file and is not "human" (a person)',
    )
    # a kind no file names: the defaults, with a note; --strict makes it an error
    res = run(*base, "--agents", "arm=2,human=1")
    assert "Status: optimal" in res.stdout and res.stderr.count("\n") == 1
    assert 'no capabilities file names the kind "human": it can do every motion' in res.stderr
    assert_one_line_error(run(*base, "--agents", "arm=2,human=1", "--strict", ok=False), '"human"', "--strict")
    # the same in check and batch --schedule
    record = tmp_path / "s.json"
    run(*base, "--agents", "arm=2", "--format", "json", "-o", record)
    assert_one_line_error(
        run("check", record, "--data", "demo", "--agents", "arms=2", "--capabilities", caps, ok=False),
        "did you mean arms?",
    )
    out = tmp_path / "r.jsonl"
    batch = ["batch", "--data", "demo", "--output", out, "--schedule", "--capabilities", caps, "--agents", "arms=2"]
    assert_one_line_error(run(*batch, ok=False), f"{caps}:1", '"arm"')
    assert not out.exists()  # refused before any work


def test_the_library_refuses_a_misspelt_kind_as_the_command_line_does(tmp_path):
    caps = tmp_path / "arm-only.json"
    caps.write_text('{"arm": ["crack", "beat", "fry"]}')
    kb = foon2asp.load("demo")
    with pytest.raises(foon2asp.InputError) as err:
        kb.schedule("scrambled egg", agents="arms=2", capabilities=caps)
    assert str(err.value) == f'{caps}:1: no agent has the kind "arm" (the agents: arms=2); did you mean arms?'
    with pytest.raises(foon2asp.InputError, match="did you mean human"):
        kb.schedule("scrambled egg", agents={"humann": 1})
    with pytest.raises(foon2asp.InputError, match="did you mean arms"):
        kb.solve("scrambled egg").schedule(agents="arms=2", capabilities=caps)
    with pytest.raises(foon2asp.InputError, match="^capabilities: no agent has the kind"):
        kb.schedule("scrambled egg", api.ScheduleSpec((("arms", 2),), capabilities={"arm": frozenset({"fry"})}))
    s = kb.schedule("scrambled egg", agents="arm=2,human=1", capabilities=caps)
    assert s.status == "optimal" and s.spec.warnings == (
        "agents 'arm=2,human=1': no capabilities file names the kind \"human\": it can do every motion",
    )


# ---------------------------------------------------------------- joint


def test_joint_reports_both_makespans(tmp_path):
    problem = longer_tree_shorter_chain()
    d = write_data(tmp_path, problem)
    base = ["schedule", "--data", d, "--goal", "g", "--agents", "arm=3"]
    (fixed,) = json.loads(run(*base, "--format", "json").stdout)
    (joint,) = json.loads(run(*base, "--joint", "--format", "json").stdout)
    assert fixed["makespan"] == 3.0 and len(fixed["tree"]["units"]) == 3
    assert joint["status"] == "optimal" and joint["makespan"] == 2.0 and len(joint["tree"]["units"]) == 4
    assert joint["fixed_tree"] == {"status": "optimal", "makespan": 3.0, "units": 3}
    text = run(*base, "--joint").stdout
    assert "Makespan: 2 s" in text and "Given tree: 3 s (optimal)" in text
    kb = foon2asp.load(d)
    lib = kb.solve("g").schedule(agents="arm=3", joint=True)
    assert lib.makespan == 2.0 and lib.fixed is not None and lib.fixed.makespan == 3.0
    assert lib.check() is None and len(lib.tree.units) == 4


def test_together_schedules_one_tree_of_the_meal(shared_foon_dir, tmp_path):
    """A meal: one tree for both dishes (the tree solve --together gives), one schedule of it,
    which check accepts; with --joint never longer; the library gives the same."""
    meal = ["--goal", "carrot salad", "--goal", "coleslaw"]
    (tree,) = json.loads(run("solve", "--data", shared_foon_dir, *meal, "--together", "--format", "json").stdout)
    base = ["schedule", "--data", shared_foon_dir, *meal, "--agents", "arm=2", "--together", "--format", "json"]
    (fixed,) = json.loads(run(*base).stdout)
    assert fixed["status"] == "optimal" and len(fixed["tree"]["units"]) == len(tree["units"])
    assert len(fixed["schedule"]) == len(tree["units"])
    (joint,) = json.loads(run(*base, "--joint").stdout)
    assert joint["status"] == "optimal" and joint["makespan"] <= fixed["makespan"]
    path = tmp_path / "meal.json"
    path.write_text(json.dumps([fixed, joint]))
    lines = run("check", path, "--data", shared_foon_dir, "--agents", "arm=2").stdout.splitlines()
    assert len(lines) == 2 and all("carrot salad + coleslaw: valid schedule" in line for line in lines)
    lib = foon2asp.load(shared_foon_dir).schedule(["carrot salad", "coleslaw"], agents="arm=2", together=True)
    assert lib.makespan == fixed["makespan"] and len(lib.tree.units) == len(tree["units"]) and lib.check() is None


# ---------------------------------------------------------------- check rejects each violation


@pytest.fixture
def case(tmp_path):
    """cut a and cut b (both with the knife) on two arms in parallel, then mix them; its schedule file."""
    problem = build(
        [("cut", ["k", KNIFE], ["a"]), ("cut", ["k", KNIFE], ["b"]), ("mix", ["a", "b"], ["g"])], ["k", KNIFE]
    )
    d = write_data(tmp_path, problem)
    (tmp_path / "dur.json").write_text('{"cut": 2, "mix": 1}')
    opts = ["--data", d, "--agents", "arm=2", "--durations", tmp_path / "dur.json"]
    res = run("schedule", "--goal", "g", "--format", "json", *opts)
    (record,) = json.loads(res.stdout)
    assert record["makespan"] == 3.0 and record["status"] == "optimal"
    return tmp_path, opts, record


def check_file(tmp_path, opts, record, *extra):
    path = tmp_path / "changed.json"
    path.write_text(json.dumps([record]))
    return run("check", path, *opts, *extra, ok=False)


def cut(record, label):
    return next(e for e in record["schedule"] if e["unit"]["outputs"][0]["label"] == label)


def test_check_accepts_the_schedule(case):
    tmp_path, opts, record = case
    res = check_file(tmp_path, opts, record)
    assert res.exit_code == 0 and "valid schedule (optimal), makespan 3 s" in res.stdout
    out = json.loads(check_file(tmp_path, opts, record, "--format", "json").stdout)
    assert out[0]["valid"] is True and out[0]["problem"] is None


def _precedence(r):
    e = cut(r, "g")
    e["start"], e["end"] = 1.0, 2.0
    r["makespan"] = 2.0


def _overlap(r):
    for e in r["schedule"]:
        e["agent"] = "arm-1"


def _drop(r):
    r["schedule"] = [e for e in r["schedule"] if e["unit"]["outputs"][0]["label"] != "b"]


def _stranger(r):
    r["agents"].append("arm-3")
    cut(r, "g")["agent"] = "arm-3"


VIOLATIONS = {
    "precedence": (_precedence, [], "before"),
    "one unit per agent": (_overlap, [], "does units"),
    "the tree": (_drop, [], "the tree is not valid"),
    "agents": (_stranger, [], "'arm-3' is not one of the agents"),
}


@pytest.mark.parametrize("name", VIOLATIONS)
def test_check_rejects_each_violation(case, name):
    tmp_path, opts, record = case
    change, extra, words = VIOLATIONS[name]
    changed = copy.deepcopy(record)
    change(changed)
    res = check_file(tmp_path, opts, changed, *extra)
    assert res.exit_code == 1 and "INVALID schedule" in res.stdout and words in res.stdout, res.stdout


def test_check_rejects_capabilities_resources_and_durations(case):
    tmp_path, opts, record = case
    (tmp_path / "caps.json").write_text('{"arm": ["mix"]}')
    (tmp_path / "res.json").write_text('{"knife": 1}')
    (tmp_path / "dur2.json").write_text('{"cut": 2, "mix": 2}')
    res = check_file(tmp_path, opts, record, "--capabilities", tmp_path / "caps.json")
    assert res.exit_code == 1 and "cannot do 'cut'" in res.stdout
    res = check_file(tmp_path, opts, record, "--resources", tmp_path / "res.json")
    assert res.exit_code == 1 and "using 'knife' (capacity 1)" in res.stdout
    res = check_file(tmp_path, opts[:-1] + [tmp_path / "dur2.json"], record)
    assert res.exit_code == 1 and "takes 1 s, not 2 s" in res.stdout
    # the same options as the schedule's: valid; with resources the solver serialises the cuts
    got = run("schedule", "--goal", "g", "--format", "json", *opts, "--resources", tmp_path / "res.json")
    (serial,) = json.loads(got.stdout)
    assert serial["makespan"] == 5.0
    assert check_file(tmp_path, opts, serial, "--resources", tmp_path / "res.json").exit_code == 0


# ---------------------------------------------------------------- batch --schedule


def test_batch_schedule_writes_valid_schedules(shared_foon_dir, tmp_path):
    out = tmp_path / "results.jsonl"
    goals = ["greek salad", "ice", "whipped cream"]
    args = ["batch", "--data", shared_foon_dir, "--output", out, "--schedule", "--agents", "arm=2"]
    res = run(*args, *(a for g in goals for a in ("--goal", g)), ok=False)
    path = tmp_path / "results.schedules.json"
    assert path.is_file() and "wrote 3 schedule(s)" in res.stderr, res.stderr
    records = json.loads(path.read_text())
    assert [r["goal"]["label"] for r in records][:2] == ["greek salad", "ice"]
    kb = foon2asp.load(shared_foon_dir)
    spec = ScheduleSpec((("arm", 2),))
    by_lib = {s.to_dict()["goal"]["label"]: s.makespan for s in kb.schedule(goals[:2], agents="arm=2")}
    for r in records:
        assert KEYS <= set(r)
        if r["status"] == "unreachable":
            continue
        assert r["status"] == "optimal" and check_schedule(kb.problem, r, spec) is None
        assert r["makespan"] == by_lib[r["goal"]["label"]]
    checked = run("check", path, "--data", shared_foon_dir, "--agents", "arm=2", ok=False)
    assert checked.stdout.count("valid schedule (optimal)") == 2, checked.stdout
    assert checked.exit_code == 0 and "no schedule to check (unreachable)" in checked.stdout


@needs_dot
def test_batch_summary_html_shows_the_gantt_charts(shared_foon_dir, tmp_path):
    out = tmp_path / "results.jsonl"
    res = run("batch", "--data", shared_foon_dir, "--goal", "ice", "--output", out, "--schedule", "--summary", "html")
    assert "<h2>Schedules</h2>" in res.stdout and 'class="tree schedule"' in res.stdout
    assert res.stdout.count("<svg") == 2  # the tree and its schedule


# ---------------------------------------------------------------- pictures and errors


@needs_dot
def test_gantt_formats(shared_foon_dir, tmp_path):
    base = ["schedule", "--data", shared_foon_dir, "--goal", "greek salad", "--agents", "arm=2,human=1"]
    run(*base, "--format", "svg", "-o", tmp_path / "g.svg")
    svg = (tmp_path / "g.svg").read_text()
    assert "<svg" in svg and "arm&#45;2" in svg and "human&#45;1" in svg
    run(*base, "--format", "png", "-o", tmp_path / "g.png")
    assert (tmp_path / "g.png").read_bytes()[:4] == b"\x89PNG"
    run(*base, "--format", "pdf", "-o", tmp_path / "g.pdf")
    assert (tmp_path / "g.pdf").read_bytes()[:4] == b"%PDF"
    page = run(*base, "--format", "html").stdout
    assert page.startswith("<!DOCTYPE html>") and '<table id="schedules">' in page and "<svg" in page


def test_one_line_errors(shared_foon_dir, tmp_path):
    base = ["schedule", "--data", shared_foon_dir, "--goal", "ice"]
    assert_one_line_error(run(*base, "--agents", "arm=two", ok=False), "'--agents'", "whole number")
    assert_one_line_error(run(*base, "--agents", "arm=1,arm=2", ok=False), "'--agents'", "twice")
    bad = tmp_path / "d.json"
    bad.write_text('{\n  "pour": 1,\n  "cut": -2\n}')
    assert_one_line_error(run(*base, "--durations", bad, ok=False), f"{bad}:3", '"cut"')
    bad.write_text('{"arm": "pour"}')
    assert_one_line_error(run(*base, "--capabilities", bad, ok=False), f"{bad}:1", "list of motion names")
    bad.write_text('{"knife": 0}')
    assert_one_line_error(run(*base, "--resources", bad, ok=False), f"{bad}:1", "whole number of at least 1")
    assert_one_line_error(run(*base, "--durations", tmp_path / "none.json", ok=False), "none.json")
    assert_one_line_error(run(*base, "--joint", "--objective", "depth", ok=False), "joint")


def test_kb_schedule_takes_a_spec_or_the_files(shared_foon_dir, tmp_path):
    kb = foon2asp.load(shared_foon_dir)
    one = kb.schedule("greek salad", agents={"arm": 2})
    assert isinstance(one, api.Schedule) and one.status == "optimal" and one.agents == ["arm-1", "arm-2"]
    same = kb.schedule("greek salad", api.ScheduleSpec.from_files("arm=2"))
    assert same.makespan == one.makespan and same.entries == one.entries
    tree = kb.solve("greek salad")
    assert tree.schedule(agents="arm=2").makespan == one.makespan
    assert tree.schedule().makespan == len(tree.units)  # one robot, 1 s per unit
    with pytest.raises(foon2asp.errors.InputError, match="not both"):
        kb.schedule("ice", api.ScheduleSpec(), agents="arm=2")
    path = tmp_path / "s.json"
    path.write_text(api.schedules_json([one]))
    assert api.is_schedule_file(path) and not api.is_schedule_file(shared_foon_dir / "goal_nodes.json")
    (verdict,) = kb.check_schedules(path, api.ScheduleSpec.from_files("arm=2"))
    assert verdict.valid and verdict.makespan == one.makespan
    (wrong,) = kb.check_schedules(path)
    assert not wrong.valid and "arm-1" in (wrong.problem or "")


def test_substitutes_stand_in_for_kitchen_items_when_scheduling_and_checking(tmp_path):
    data = REPO / "data" / "matching" / "onion"
    subs = ["--substitutes", data / "substitutes.json"]
    path = tmp_path / "s.json"
    res = run("schedule", "--data", data, "--goals", "all", "--format", "json", "-o", path, *subs)
    (record,) = json.loads(path.read_text())
    assert res.exit_code == 0 and record["status"] == "optimal" and record["tree"]["substitutions"]
    assert "valid schedule (optimal)" in run("check", path, "--data", data, *subs).stdout
    res = run("check", path, "--data", data, ok=False)  # without the substitutes the tree is not valid
    assert res.exit_code == 1 and "the tree is not valid" in res.stdout
    out = tmp_path / "r.jsonl"
    run("batch", "--data", data, "--goals", "all", "--output", out, "--schedule", *subs)
    (batched,) = json.loads((tmp_path / "r.schedules.json").read_text())
    assert batched["status"] == "optimal" and batched["makespan"] == record["makespan"]
