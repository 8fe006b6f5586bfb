"""One request value (Options) for every answer; the library's own answers for what the command line prints;
library errors that speak of values while the command line words them with its flags."""

from __future__ import annotations

import json
import shutil

import pytest
from click.testing import CliRunner

import foon2asp
from conftest import DEMO
from foon2asp import Constraints, Options, api
from foon2asp.cli.main import main
from foon2asp.tree.validate import validate


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture(scope="module")
def kb(shared_foon_dir):
    return foon2asp.load(shared_foon_dir)


@pytest.fixture(scope="module")
def demo():
    return foon2asp.load("demo")


def test_keywords_map_onto_one_request():
    same = dict(time_limit=3, models=2, max_depth=9, human_steps=1, opt_strategy="bb", threads=2, grounding="per-goal")
    keywords = dict(
        objective="success, units",
        **same,
        shortcuts=False,
        forbid_motions=["heat"],
        forbid_objects=["stove"],
        require_motions=["boil"],
        require_objects=["pot"],
        max_units=7,
        rules=[":- use(1)."],
        constraint_files=["no.lp"],
    )
    spec = Constraints(("no.lp",), (":- use(1).",), ("heat",), ("stove",), ("boil",), ("pot",), 7)
    expected = Options(objective=("success", "units"), constraints=spec, all_optimal=False, shortcuts=False, **same)
    assert Options.of(**keywords) == expected
    # keywords go on top of a request, field by field (constraints too)
    base = Options(objective=("inputs",), constraints=Constraints(rules=(":- use(2).",)), threads=4)
    layered = Options.of(base, forbid_motions=["fry"], time_limit=1)
    assert layered.objective == ("inputs",) and layered.threads == 4 and layered.time_limit == 1
    assert layered.constraints == Constraints(rules=(":- use(2).",), forbid_motion=("fry",))
    assert Options.of(base) is base and Options(objective="") == Options()
    with pytest.raises(TypeError, match="forbid_motion"):
        Options.of(forbid_motion=["heat"])  # the keyword is forbid_motions


def test_solve_with_options_equals_solve_with_keywords(kb):
    request = Options.of(objective="success", forbid_motions=["heat"])
    by_value = kb.solve("macaroni", options=request)
    by_keywords = kb.solve("macaroni", objective="success", forbid_motions=["heat"])
    assert by_value.unit_ids == by_keywords.unit_ids and by_value.cost == by_keywords.cost
    assert "heat" not in {u.motion for u in by_value.units}
    assert validate(kb.problem, by_value.goal_id, by_value.unit_ids).valid
    solver = kb.options(request)
    [again] = kb.solve_iter([by_value.goal_id], "asp", solver)  # the solver options made once, used again
    assert again.unit_ids == by_value.unit_ids
    with pytest.raises(foon2asp.InputError, match="unknown objective 'fastest'"):
        kb.solve("macaroni", options=Options(objective=("fastest",)))


def test_check_solves_its_optimum_with_the_callers_options(kb, tmp_path):
    fewest = kb.solve("macaroni")
    best = kb.solve("macaroni", objective="success")
    assert best.cost["success"] > fewest.cost["success"]  # the two objectives disagree on macaroni
    assert kb.check(fewest).optimum.unit_ids == fewest.unit_ids
    report = kb.check(fewest, objective="success")
    assert report.valid and report.optimum.unit_ids == best.unit_ids
    assert report.optimum.cost == best.cost
    # a file is checked the same way, and the constraints of the request hold for its optimum
    path = tmp_path / "m.foon"
    path.write_text(fewest.to_foon())
    request = Options.of(objective="success", forbid_motions=["heat"])
    (from_file,) = kb.check_all(path, options=request)
    optimum = from_file.optimum
    assert optimum.unit_ids == kb.solve("macaroni", options=request).unit_ids
    assert "heat" not in {u.motion for u in optimum.units} and "heat" in {u.motion for u in fewest.units}
    assert validate(kb.problem, optimum.goal_id, optimum.unit_ids).valid


def _no_goals_file(tmp_path):
    for name in ("FOON.txt", "kitchen.json"):
        shutil.copy(DEMO / name, tmp_path / name)
    return tmp_path / "FOON.txt"


def test_library_errors_speak_of_values_and_the_cli_of_flags(tmp_path):
    foon = _no_goals_file(tmp_path)
    bare = foon2asp.load(foon=foon)
    cases = [
        (lambda: bare.select_goals((), "all"), ["solve", "--foon", foon, "--goals", "all"]),
        (lambda: bare.select_goals(), ["solve", "--foon", foon]),
        (lambda: bare.solve("tomato salad", human_steps=1), ["solve", "--data", "demo", "--human-steps", "1"]),
    ]
    seen = []
    for call, argv in cases:
        with pytest.raises(foon2asp.InputError) as err:
            call()
        assert "--" not in str(err.value) and err.value.hint
        res = run(*argv)
        assert res.exit_code == 2
        seen.append(res.stderr.strip().splitlines()[-1])
    looked_for = tmp_path / "goal_nodes.json"
    assert seen == [
        f"foon2asp: error: --goals all needs a goals file, and there is no {looked_for} (give --goals FILE)",
        f"foon2asp: error: no goal given and no goals file (there is no {looked_for}): use --goal TEXT, --goals FILE"
        " or --goals all-objects",
        "foon2asp: error: human steps only change the tree when 'success' is an objective (a person's step succeeds"
        " for sure); use --objective success or units,success",
    ]
    (tmp_path / "kitchen.json").unlink()
    with pytest.raises(foon2asp.InputError) as err:
        foon2asp.load(foon=foon)
    assert "--" not in str(err.value)
    line = run("solve", "--foon", foon).stderr.strip()
    assert line == (
        f"foon2asp: error: no kitchen.json beside the FOON file (looked for {tmp_path / 'kitchen.json'});"
        " give --kitchen FILE, --kitchen leaves (every object no unit makes, e.g. for merged generated trees)"
        " or --data DIR (--data demo for the demo data)"
    )


def test_query_goals_file_gives_the_goal_nodes(demo, tmp_path):
    picked = [demo.object_info(g) for g in demo.select_goals(["scrambled egg", "tomato salad"])]
    goals = tmp_path / "two.json"
    goals.write_text(json.dumps(picked))
    prog = tmp_path / "nodes.lp"
    prog.write_text("#show node(N,O) : goal_node(N,O).\n")
    res = run("query", prog, "--data", "demo", "--goals", goals, "--format", "json")
    assert res.exit_code == 0, res.output
    (model,) = json.loads(res.stdout)["models"]
    assert [a["arguments"] for a in model["atoms"]] == [[1, picked[0]["id"]], [2, picked[1]["id"]]]


def test_the_library_answers_what_the_cli_prints(demo, shared_111_dir, tmp_path):
    out = run("facts", "--data", "demo", "--goals", "all-objects", "--goal", "tomato salad").stdout
    assert out == demo.facts(demo.select_goals((), "all-objects"), demo.select_goals(["tomato salad"]))
    assert run("facts", "--data", "demo").stdout == demo.facts()
    for fmt in ("text", "json"):
        assert run("reachable", "--data", "demo", "--format", fmt).stdout == demo.reachability(None).render(fmt)
    names = [line.split()[0] for line in run("methods").stdout.splitlines()]
    assert names == [m.name for m in api.methods()] and "gbfs-h1" in names
    files = sorted(shared_111_dir.glob("*.txt"))[:3]
    for fmt in api.FOON_FORMATS:
        run("merge", *files, "-o", tmp_path / f"cli.{fmt}", "--format", fmt)
        api.write_foon(api.read_foons(files), tmp_path / f"lib.{fmt}", fmt, "merged by foon2asp from 3 file(s)")
        assert (tmp_path / f"cli.{fmt}").read_text() == (tmp_path / f"lib.{fmt}").read_text()
        assert api.read_foons([tmp_path / f"lib.{fmt}"]).units == api.read_foons(files).units
    tree = tmp_path / "egg.foon"
    tree.write_text(demo.solve("scrambled egg", method="gbfs-h1").to_foon())
    run("draw", tree, "--data", "demo", "-o", tmp_path / "cli.dot")
    assert api.draw_file(tree, tmp_path / "lib.dot", kb=demo) == 1
    assert (tmp_path / "cli.dot").read_text() == (tmp_path / "lib.dot").read_text()


def test_batch_run_summarises_its_records(demo):
    run_ = demo.batch("all-objects", None, methods=["asp", "gbfs-h1"], objective="success")
    rows = {r["method"]: r for r in run_.summary()}
    assert set(rows) == {"asp", "gbfs-h1"}
    for method, row in rows.items():
        mine = [r for r in run_.records if r["requested_method"] == method]
        assert row["results"] == len(mine) == len(demo.select_goals((), "all-objects"))
        assert row["trees"] == sum(1 for r in mine if r["units"])
    assert run_.render("csv").splitlines()[0].startswith("method,results,statuses")
    assert run_.records[0]["method"] == "asp-success"


def test_a_request_changes_nothing_shared_and_its_warnings_are_told_once(demo, tmp_path):
    table = tmp_path / "costs.tsv"
    table.write_text("chop\t0.25\nmix\t1.5\n")
    solver, warnings = demo.options_and_warnings(motion_cost=table, forbid_motions=["fly"])
    assert solver.motion_costs["chop"] == 25 and solver.motion_costs["mix"] == 150
    assert warnings[0] == "no unit has motion 'fly'"
    assert warnings[1].startswith(f"{table}: 11 motions are not in the motion-cost table and cost 1 each: beat,")
    assert demo.warnings == foon2asp.load("demo").warnings and demo.problem.motion_costs is None
    assert demo.solve("tomato salad", motion_cost=table).cost["cost"] == 3.75  # chop, 2 x 1, mix
    assert "cost" not in demo.solve("tomato salad").cost  # the next request has no table
    res = run("solve", "--data", "demo", "--goal", "tomato salad", "--forbid-motion", "fly", "--motion-cost", table)
    assert res.exit_code == 0
    assert [line.split(": ", 2)[2] for line in res.stderr.splitlines() if "warning" in line] == warnings
