"""One vocabulary for every command: objects, goals by text, data beside --foon, query #show,
streaming, exit codes, the error style."""

from __future__ import annotations

import json
import shutil

from click.testing import CliRunner

from conftest import DEMO
from foon2asp.batch.results_file import read_results
from foon2asp.cli.main import main


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_objects_lists_every_scrambled_egg_and_each_text_solves(shared_foon_dir, tmp_path):
    res = run("objects", "scrambled egg", "--data", shared_foon_dir, "--format", "json")
    assert res.exit_code == 0, res.output
    listed = json.loads(res.stdout)
    assert len(listed) == 15
    assert set(listed[0]) == {"id", "text", "label", "states", "ingredients", "container", "in_kitchen", "producers"}
    assert all(o["label"] == "scrambled egg" and o["producers"] >= 1 for o in listed)
    text = run("objects", "scrambled egg", "--data", shared_foon_dir).stdout.splitlines()
    assert len(text) == 15 and text[0].startswith(f"#{listed[0]['id']} ")
    # an object's text and its #ID name the same goal
    pick = listed[-1]
    by_text = json.loads(run("solve", "--data", shared_foon_dir, "--goal", pick["text"], "--format", "json").stdout)
    by_id = json.loads(run("solve", "--data", shared_foon_dir, "--goal", f"#{pick['id']}", "--format", "json").stdout)
    assert by_text == [dict(by_id[0], time_s=by_text[0]["time_s"], stats=by_text[0].get("stats"))] or by_text == [
        dict(by_id[0], time_s=by_text[0]["time_s"])
    ]
    assert by_text[0]["goal"] == {k: pick[k] for k in ("label", "states", "ingredients", "container")}
    # the JSON listing is a goals file
    goals = tmp_path / "eggs.json"
    goals.write_text(res.stdout)
    lines = run("solve", "--data", shared_foon_dir, "--goals", goals, "--format", "jsonl").stdout.splitlines()
    assert [json.loads(line)["goal"]["ingredients"] for line in lines] == [o["ingredients"] for o in listed]


def test_objects_filters_and_suggestions():
    kitchen = json.loads(run("objects", "--data", "demo", "--kitchen", "--format", "json").stdout)
    assert kitchen and all(o["in_kitchen"] for o in kitchen)
    made = json.loads(run("objects", "--data", "demo", "--produced", "--format", "json").stdout)
    assert made and all(o["producers"] > 0 for o in made)
    derivable = json.loads(run("objects", "--data", "demo", "--derivable", "--format", "json").stdout)
    assert {o["id"] for o in kitchen} <= {o["id"] for o in derivable}
    res = run("objects", "scrambld eg", "--data", "demo")
    assert res.exit_code == 2 and "closest labels: scrambled egg" in res.stderr


def test_check_reads_the_goal_from_the_foon_header_and_the_single_sink(shared_foon_dir, tmp_path):
    out = run("solve", "--data", shared_foon_dir, "--goals", "all", "--format", "foon")
    path = tmp_path / "all.foon"
    path.write_text(out.stdout)
    res = run("check", path, "--data", shared_foon_dir, "--no-optimum", "--format", "json")
    reports = json.loads(res.stdout)
    assert len(reports) == 25
    assert all(r["goal_source"] == "named in the file" for r in reports)
    # the two unreachable goals have no tree in the file: confirmed unreachable, exit 0
    assert [r["valid"] for r in reports].count(None) == 2 and res.exit_code == 0
    assert sum(1 for r in reports if r["problem"] == "unreachable") == 2
    # one tree without its header: the goal is the tree's only sink
    one = run("solve", "--data", shared_foon_dir, "--goal", "macaroni", "--format", "foon").stdout
    bare = tmp_path / "bare.foon"
    bare.write_text("".join(line + "\n" for line in one.splitlines() if not line.startswith("#")))
    res = run("check", bare, "--data", shared_foon_dir, "--no-optimum", "--format", "json")
    assert res.exit_code == 0, res.output
    (report,) = json.loads(res.stdout)
    assert report["valid"] and report["goal_source"] == "inferred from the units"
    assert report["goal"]["label"] == "macaroni"


def test_check_goals_file_picks_each_trees_goal(tmp_path):
    text = run("solve", "--data", "demo", "--goal", "scrambled egg", "--format", "foon").stdout
    path = tmp_path / "egg.foon"
    path.write_text("".join(ln + "\n" for ln in text.splitlines() if not ln.startswith("#")))
    res = run("check", path, "--data", "demo", "--goals", "all", "--no-optimum", "--format", "json")
    assert res.exit_code == 0, res.output
    (report,) = json.loads(res.stdout)
    assert report["goal_source"] == "--goals" and report["goal"]["label"] == "scrambled egg" and report["valid"]


def test_foon_alone_reads_the_files_beside_it(tmp_path):
    for name in ("FOON.txt", "kitchen.json", "goal_nodes.json"):
        shutil.copy(DEMO / name, tmp_path / name)
    res = run("solve", "--foon", tmp_path / "FOON.txt", "--format", "json")
    assert res.exit_code == 0, res.output
    assert [r["goal"]["label"] for r in json.loads(res.stdout)] == [
        "tomato salad",
        "scrambled egg",
        "whipped cream",
        "pancake",
    ]
    assert "no motion.txt beside" in res.stderr and "no utensils.txt beside" in res.stderr
    (tmp_path / "kitchen.json").unlink()
    res = run("solve", "--foon", tmp_path / "FOON.txt")
    assert res.exit_code == 2 and "no kitchen.json beside the FOON file" in res.stderr
    res = run("solve", "--goal", "tomato salad")
    assert res.exit_code == 2 and "no data given" in res.stderr and "--data demo" in res.stderr


def test_query_prints_only_what_it_shows_and_warns(tmp_path):
    prog = tmp_path / "n.lp"
    prog.write_text("n(N) :- N = #count { U : unit(U) }.\n#show n/1.\n")
    res = run("query", prog, "--data", "demo", "--encoding", "reachable", "--format", "json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    (model,) = out["models"]
    assert [a["predicate"] for a in model["atoms"]] == ["n"]
    assert out["encodings"] == ["tree", "reachable"]  # reachable pulls in tree
    typo = tmp_path / "typo.lp"
    typo.write_text("p(O) :- kitchn(O).\n#show p/1.\n")
    res = run("query", typo, "--data", "demo")
    assert res.exit_code == 0
    assert "foon2asp: warning:" in res.stderr and "kitchn" in res.stderr


def test_jsonl_streams_one_line_per_goal_and_compare_jsonl():
    lines = run("solve", "--data", "demo", "--format", "jsonl").stdout.splitlines()
    assert [json.loads(line)["goal"]["label"] for line in lines] == [
        "tomato salad",
        "scrambled egg",
        "whipped cream",
        "pancake",
    ]
    rows = [json.loads(line) for line in run("compare", "--data", "demo", "--format", "jsonl").stdout.splitlines()]
    assert len(rows) == 16 and all("valid" in r for r in rows)


def test_human_steps_need_success_and_models_are_ranked(shared_foon_dir):
    res = run("solve", "--data", "demo", "--goal", "tomato salad", "--human-steps", "2")
    assert res.exit_code == 2 and "'success' is an objective" in res.stderr
    res = run("solve", "--data", shared_foon_dir, "--goal", "macaroni", "--models", "3", "--format", "json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert [t["status"] for t in out] == ["optimal", "ranked", "ranked"]
    assert [t["cost"]["units"] for t in out] == sorted(t["cost"]["units"] for t in out)


def test_batch_rows_carry_valid(shared_foon_dir, tmp_path):
    out = tmp_path / "r.jsonl"
    res = run("batch", "--data", shared_foon_dir, "--method", "gbfs-h1", "-o", out, "--no-progress")
    records = read_results(out)  # the configuration header is not a record
    assert len(records) == 25 and all("valid" in r for r in records)
    invalid = [r for r in records if r["status"] == "found" and not r["valid"]]
    assert invalid and res.exit_code == 1
    assert any("valid" in line.split() for line in res.stdout.splitlines())  # the summary's column


def test_method_and_methods_are_one_option():
    a = json.loads(
        run("solve", "--data", "demo", "--goal", "tomato salad", "--methods", "ids", "--format", "json").stdout
    )
    b = json.loads(
        run("solve", "--data", "demo", "--goal", "tomato salad", "--method", "ids", "--format", "json").stdout
    )
    assert a[0]["method"] == b[0]["method"] == "ids"
    res = run("compare", "--data", "demo", "--goal", "tomato salad", "--method", "asp", "--format", "json")
    assert res.exit_code == 0 and [r["method"] for r in json.loads(res.stdout)] == ["asp"]


def test_usage_errors_have_the_one_error_style():
    for args in (["solve", "--bogus"], ["solve", "--format", "nope"], ["nope"]):
        res = run(*args)
        assert res.exit_code == 2, args
        err = res.stderr.strip()
        assert err.startswith("foon2asp: error: ") and len(err.splitlines()) == 1, err


def test_exit_codes_unreachable_is_answered():
    # whipped cream is proven unreachable in the demo: an answer, exit 0
    res = run("solve", "--data", "demo", "--goal", "whipped cream")
    assert res.exit_code == 0 and "unreachable" in res.stdout
    res = run("missing", "--data", "demo", "--goal", "pancake", "--objective", "success", "--format", "json")
    assert res.exit_code == 0 and json.loads(res.stdout)[0]["status"] == "optimal"


def test_numbers_are_printed_with_one_rule(shared_foon_dir, tmp_path):
    """Text outputs print a measure with 4 significant digits; JSON keeps the full value."""
    from foon2asp.tree.serialize import number

    js = json.loads(run("solve", "--data", shared_foon_dir, "--goal", "greek salad", "--format", "json").stdout)[0]
    success = js["cost"]["success"]
    text = run("solve", "--data", shared_foon_dir, "--goal", "greek salad").stdout
    assert f"success {number(success)}," in text and number(success) == f"{success:.4g}" != str(success)
    tree = tmp_path / "t.foon"
    tree.write_text(run("solve", "--data", shared_foon_dir, "--goal", "greek salad", "--format", "foon").stdout)
    checked = run("check", tree, "--data", shared_foon_dir).stdout
    assert f"success {number(success)}," in checked
    assert number(25) == "25" and number(0.02187) == "0.02187"
