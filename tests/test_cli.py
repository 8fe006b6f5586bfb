"""The command line: JSON shape, goal selection, formats, and one-line errors."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys

import clingo
import pytest
from click.testing import CliRunner

import foon2asp
from conftest import DEMO
from foon2asp.asp.options import AspOptions
from foon2asp.batch.results_file import read_results
from foon2asp.cli.main import main
from foon2asp.errors import InputError
from foon2asp.foon.parser import parse_lines

OBJ_KEYS = {"label", "states", "ingredients", "container"}
SMOOTHIE = DEMO / "llm" / "smoothie-2.json"
CAVEAT = (
    "Note: a missing step cannot be detected without a kitchen: whatever no unit of the tree makes is"
    " assumed to be in the kitchen (give --kitchen FILE, or --data or --foon to check against a FOON)"
)


def run(*args, ok=True):
    result = CliRunner().invoke(main, list(map(str, args)))
    if ok:
        assert result.exit_code == 0, result.output + str(result.exception)
    return result


def assert_one_line_error(result, *words):
    assert result.exit_code == 2
    err = result.stderr.strip()
    assert len(err.splitlines()) == 1, err
    assert err.startswith("foon2asp: error: ")
    assert "Traceback" not in result.output
    for w in words:
        assert w in err, (w, err)


def test_json_all_goals_shared(shared_foon_dir):
    out = json.loads(run("solve", "--data", shared_foon_dir, "--goals", "all", "--format", "json").stdout)
    assert len(out) == 25
    for res in out:
        assert set(res) >= {"goal", "method", "status", "cost", "units", "time_s"}
        assert set(res["goal"]) == OBJ_KEYS
        assert res["method"] == "asp-units"
        if res["status"] == "optimal":
            assert res["cost"]["units"] == len(res["units"])
            for unit in res["units"]:
                assert set(unit) == {"motion", "inputs", "outputs"}
                assert all(set(o) == OBJ_KEYS for o in unit["inputs"] + unit["outputs"])
    by_label = {r["goal"]["label"]: r for r in out}
    assert by_label["greek salad"]["cost"]["units"] == 25
    assert by_label["whipped cream"]["status"] == "unreachable"
    assert by_label["whipped cream"]["units"] == []


def test_demo_is_default():
    out = json.loads(run("solve", "--data", "demo", "--goals", "all", "--format", "json").stdout)
    assert [r["goal"]["label"] for r in out] == ["tomato salad", "scrambled egg", "whipped cream", "pancake"]
    assert [r["status"] for r in out] == ["optimal", "optimal", "unreachable", "unreachable"]
    text = run("solve", "--data", "demo", "--goal", "tomato salad").stdout
    assert "Status: optimal" in text and "1. chop" in text


def test_foon_format_round_trips(shared_foon_dir):
    js = json.loads(run("solve", "--data", shared_foon_dir, "--goal", "macaroni", "--format", "json").stdout)[0]
    text = run("solve", "--data", shared_foon_dir, "--goal", "macaroni", "--format", "foon").stdout
    assert text.count("//") == len(js["units"]) + 1
    foon = parse_lines(text)
    assert [u.to_json() for u in foon.units] == js["units"]


def test_output_dir(tmp_path):
    run("solve", "--data", "demo", "--goals", "all", "--format", "json", "--output", tmp_path)
    files = sorted(p.name for p in tmp_path.iterdir())
    assert len(files) == 4 and files[0].startswith("001-tomato_salad")
    assert json.loads((tmp_path / files[0]).read_text())[0]["status"] == "optimal"


def test_goal_from_foon_label_and_ambiguity():
    # not in the goals file, but a unique produced object
    out = json.loads(run("solve", "--data", "demo", "--goal", "pancake batter", "--format", "json").stdout)
    assert out[0]["status"] == "optimal" and len(out[0]["units"]) == 1
    res = run("solve", "--data", "demo", "--goal", "tomato", ok=False)
    assert_one_line_error(res, "ambiguous" if "ambiguous" in res.stderr else "names", "tomato, chopped")


def test_unknown_goal_suggests_labels():
    res = run("solve", "--data", "demo", "--goal", "tomato salat", ok=False)
    assert_one_line_error(res, "tomato salad")


def test_bad_kitchen_json(tmp_path):
    for name in ("FOON.txt", "goal_nodes.json", "motion.txt", "utensils.txt"):
        (tmp_path / name).write_text((DEMO / name).read_text())
    (tmp_path / "kitchen.json").write_text('[\n {"label": "knife"},\n {"label": oops}\n]\n')
    res = run("solve", "--data", tmp_path, "--goals", "all", ok=False)
    assert_one_line_error(res, "kitchen.json:3:", "bad JSON")


def test_bad_foon_line(tmp_path):
    for name in ("kitchen.json", "goal_nodes.json"):
        (tmp_path / name).write_text((DEMO / name).read_text())
    (tmp_path / "FOON.txt").write_text("//\nO\ttomato\nS\twhole\nQ\twhat\n")
    res = run("solve", "--data", tmp_path, "--goals", "all", ok=False)
    assert_one_line_error(res, "FOON.txt:4:", "unknown line type")


def test_goal_not_in_foon(tmp_path):
    goals = tmp_path / "goals.json"
    goals.write_text(
        '[\n  {"label": "tomato salad", "states": ["mixed"], "container": "bowl"},\n'
        '  {"label": "tomato salad", "states": ["burnt"], "container": "bowl"}\n]\n'
    )
    res = run("solve", "--data", "demo", "--goals", goals, ok=False)
    assert_one_line_error(res, "goals.json:3:", "not an object of the FOON")


def test_bad_motion_rate(tmp_path):
    for name in ("FOON.txt", "kitchen.json", "goal_nodes.json"):
        (tmp_path / name).write_text((DEMO / name).read_text())
    (tmp_path / "motion.txt").write_text("chop\t0.1\nslice\tfast\n")
    assert_one_line_error(run("solve", "--data", tmp_path, "--goals", "all", ok=False), "motion.txt:2:")


def test_missing_data_dir(tmp_path):
    assert_one_line_error(run("solve", "--data", tmp_path / "nope", "--goals", "all", ok=False), "nope")


def test_facts_command(tmp_path, shared_foon_dir):
    out = tmp_path / "facts.lp"
    run("facts", "--data", shared_foon_dir, "-o", out)
    ctl = clingo.Control()
    ctl.load(str(out))
    ctl.ground([("base", [])])

    def count(name, arity):
        return sum(1 for _ in ctl.symbolic_atoms.by_signature(name, arity))

    assert count("unit", 1) == 2376
    assert count("goal_node", 2) == 25
    assert count("goal", 1) == 0


def test_merge_command(tmp_path, shared_111_dir):
    files = sorted(shared_111_dir.glob("*.txt"))[:5]
    out = tmp_path / "merged.txt"
    res = run("merge", *files, "-o", out)
    from foon2asp.foon.parser import read_foon, read_foons

    assert read_foon(out).units == read_foons(files).units
    assert "merged 5 file(s)" in res.stderr


def test_module_entry_point(shared_foon_dir):
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "foon2asp",
            "solve",
            "--data",
            str(shared_foon_dir),
            "--goal",
            "ice",
            "--format",
            "json",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)[0]["cost"]["units"] == 1


def test_strict_turns_warnings_into_errors(tmp_path, shared_111_dir):
    bad = shared_111_dir / "0083-pastel-fried_savory_pastry.txt"
    res = run("merge", bad, "-o", tmp_path / "m.txt")
    assert "warning" in res.stderr and ":517:" in res.stderr
    assert_one_line_error(run("merge", "--strict", bad, "-o", tmp_path / "m2.txt", ok=False), ":517:")


# ---------------------------------------------------------------- check without a kitchen


def test_a_tree_alone_lists_the_leaves_it_assumed_and_says_what_it_cannot_see():
    res = run("check", SMOOTHIE, ok=False)
    assert res.exit_code == 1  # step 3 cannot fire in the order written
    lines = res.stdout.splitlines()
    assert lines[1] == "Judged on its own: kitchen = its leaves (7 objects)"
    assert lines[2] == (
        "Assumed in the kitchen (its leaves): banana, whole; knife; cutting board; blueberries, fresh;"
        " blender, empty; milk, in [carton]; glass, empty"
    )
    assert lines[3] == CAVEAT
    (report,) = json.loads(run("check", SMOOTHIE, "--format", "json", ok=False).stdout)
    assert report["kitchen_assumed"] is True and report["note"] == CAVEAT.removeprefix("Note: ")
    assert len(report["kitchen"]) == 7


def test_a_missing_step_passes_unseen_without_a_kitchen_and_is_caught_with_one(tmp_path):
    smoothie = DEMO / "llm" / "smoothie-1.json"  # valid on its own
    full = json.loads(run("check", smoothie, "--format", "json", ok=False).stdout)[0]
    assert full["valid"] is True
    kitchen = tmp_path / "kitchen.json"
    kitchen.write_text(json.dumps(full["kitchen"]))  # its leaves, as a kitchen of its own
    # drop the first unit (peel): the peeled banana becomes a leaf, so it is taken to be in the kitchen
    path = tmp_path / "no-peel.json"
    path.write_text(json.dumps(json.loads(smoothie.read_text())[1:]))
    (alone,) = json.loads(run("check", path, "--format", "json", ok=False).stdout)
    assert alone["valid"] is True  # the missing step is not seen...
    assert {"label": "banana", "states": ["peeled"], "ingredients": [], "container": None} in alone["kitchen"]
    assert alone["kitchen_assumed"] is True and alone["note"] == CAVEAT.removeprefix("Note: ")  # ...and it says so
    given = run("check", path, "--kitchen", kitchen, "--format", "json", ok=False)
    assert given.exit_code == 1
    (report,) = json.loads(given.stdout)
    assert report["problem"] == "missing-input" and "banana, peeled" in report["message"]
    assert report["kitchen_assumed"] is False and report["note"] is None
    assert "Note:" not in run("check", path, "--kitchen", kitchen, ok=False).stdout


# ---------------------------------------------------------------- objects: made by


def test_a_unit_that_needs_the_object_does_not_make_it():
    # the demo's only unit that outputs "stove, on" (heat) also needs it
    res = run("objects", "stove", "--data", "demo", ok=False)
    assert res.exit_code == 0, res.output
    assert res.stdout == "#19  stove, on   (kitchen, only output by 1 unit that needs it)\n"
    (info,) = json.loads(run("objects", "stove", "--data", "demo", "--format", "json", ok=False).stdout)
    assert info["producers"] == 0
    made = json.loads(run("objects", "--data", "demo", "--produced", "--format", "json", ok=False).stdout)
    assert 19 not in {o["id"] for o in made} and all(o["producers"] > 0 for o in made)
    tomato = run("objects", "tomato", "--data", "demo", ok=False).stdout.splitlines()
    assert tomato[1] == "#2  tomato, chopped   (made by 2 units)"


def test_the_fried_rice_packet_is_made_by_no_unit(shared_foon_dir):
    res = run("objects", "packet, contains {carrot,corn,green pea}", "--data", shared_foon_dir, ok=False)
    assert res.stdout.endswith("packet, contains {carrot,corn,green pea}   (only output by 1 unit that needs it)\n")


# ---------------------------------------------------------------- solve -o DIR


def test_solve_into_a_folder_prints_one_line_per_file(tmp_path):
    out = tmp_path / "svg"
    res = run("solve", "--data", "demo", "--goals", "all", "--format", "svg", "-o", out, ok=False)
    assert res.exit_code == 0, res.output
    assert res.stdout.splitlines() == [
        f"wrote {out / '001-tomato_salad.svg'} (optimal)",
        f"wrote {out / '002-scrambled_egg.svg'} (optimal)",
        f"wrote {out / '003-whipped_cream.svg'} (unreachable)",
        f"wrote {out / '004-pancake.svg'} (unreachable)",
    ]
    assert (out / "001-tomato_salad.svg").read_text().lstrip().startswith("<?xml")


def test_solve_into_a_folder_with_several_methods_and_formats(tmp_path):
    for fmt, ext in (("text", "txt"), ("json", "json"), ("png", "png")):
        out = tmp_path / fmt
        args = ("--data", "demo", "--goal", "scrambled egg", "--methods", "asp,gbfs-h1", "--format", fmt, "-o", out)
        res = run("solve", *args, ok=False)
        assert res.exit_code == 1  # the greedy tree is invalid
        assert res.stdout.splitlines() == [
            f"wrote {out / f'001-scrambled_egg-asp.{ext}'} (optimal)",
            f"wrote {out / f'001-scrambled_egg-gbfs-h1.{ext}'} (found, INVALID)",
        ]
        assert len(list(out.iterdir())) == 2


def test_clingo_options_go_to_clingo_replacing_foon2asps_own():
    """Options not foon2asp's go to clingo as its application takes them; one of foon2asp's
    defaults given again replaces it; the answer stays the proven optimum."""
    # with --objective success and no shortcuts, tomato salad is clingo's
    plain = run(
        "solve", "--data", DEMO, "--goal", "tomato salad", "--objective", "success", "--format", "json", "--no-shortcuts"
    )  # fmt: skip
    plain = json.loads(plain.stdout)
    tuned = run(
        "solve", "--data", DEMO, "--goal", "tomato salad", "--objective", "success", "--format", "json",
        "--no-shortcuts", "--configuration=crafty", "--opt-usc-shrink=inv", "--heuristic=Vsids",
    )  # fmt: skip
    tuned = json.loads(tuned.stdout)
    assert [(t["status"], t["cost"]) for t in tuned] == [(t["status"], t["cost"]) for t in plain]
    assert {t["proven_by"] for t in tuned} == {"clingo"}
    args = AspOptions(clingo_args=["--configuration=crafty", "--single-shot"]).args(["--single-shot"])
    assert args.count("--configuration=crafty") == 1 and "--configuration=trendy" not in args
    assert args.count("--single-shot") == 1 and args[-2:] == ["--configuration=crafty", "--single-shot"]


@pytest.mark.parametrize(
    ("command", "arg", "words"),
    [
        ("solve", "--nonsense=3", ["No such option '--nonsense' (not foon2asp's, not clingo's)."]),
        ("solve", "--goall", ["No such option '--goall'", "Did you mean '--goal' or '--goals'?"]),
        ("solve", "--configuraton=crafty", ["No such option '--configuraton'", "Did you mean '--configuration'?"]),
        ("batch", "--opt-strategi=usc", ["No such option '--opt-strategi'", "Did you mean '--opt-strategy'?"]),
        ("schedule", "--heuristik=Domain", ["No such option '--heuristik'", "Did you mean '--heuristic'?"]),
        ("solve", "--configuration=no-such-file", ["clingo option '--configuration=no-such-file'"]),
        ("schedule", "--nonsense=3", ["No such option '--nonsense'"]),
        ("batch", "--nonsense=3", ["No such option '--nonsense'"]),
        ("solve", "stray", ["unexpected argument 'stray'"]),
        ("batch --methods gbfs-h1", "--configuration=crafty", ["solver settings apply to ASP methods only"]),
    ],
)
def test_bad_clingo_options_are_one_line(command, arg, words, tmp_path):
    args = [*command.split(), "--data", DEMO, "--goal", "tomato salad", arg]
    if command.startswith("batch"):
        args += ["-o", tmp_path / "r.jsonl"]
    result = run(*args, ok=False)
    assert_one_line_error(result, *words)
    assert not (tmp_path / "r.jsonl").exists()


def test_clingo_options_reach_the_schedule_solver():
    """The schedule solver's controls get the clingo options of the request, replacing its own."""
    from foon2asp.schedule.solve import solver_arguments

    args = solver_arguments(AspOptions(clingo_args=["--configuration=crafty"]))
    assert "--configuration=crafty" in args and not any(
        a.startswith("--configuration=") and "crafty" not in a for a in args
    )
    assert solver_arguments(AspOptions()) != args


def test_the_library_checks_clingo_options_as_the_command_line_does():
    kb = foon2asp.load(DEMO)
    with pytest.raises(InputError, match=r"clingo option '--nonsense': .*unknown option: 'nonsense'"):
        kb.solve("tomato salad", clingo_args=["--nonsense"])
    with pytest.raises(InputError, match="clingo's options start with '-'"):
        kb.solve("tomato salad", clingo_args="crafty")
    tree = kb.solve("tomato salad", objective="success", shortcuts=False, clingo_args=("--configuration=crafty",))
    assert (tree.status, tree.cost["units"], tree.proven_by) == ("optimal", 5, "clingo")


# One vocabulary for every command: objects, goals by text, data beside --foon, query #show,
# streaming, exit codes, the error style.


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_objects_lists_every_scrambled_egg_and_each_text_solves(shared_foon_dir, tmp_path):
    res = invoke("objects", "scrambled egg", "--data", shared_foon_dir, "--format", "json")
    assert res.exit_code == 0, res.output
    listed = json.loads(res.stdout)
    assert len(listed) == 15
    assert set(listed[0]) == {"id", "text", "label", "states", "ingredients", "container", "in_kitchen", "producers"}
    assert all(o["label"] == "scrambled egg" and o["producers"] >= 1 for o in listed)
    text = invoke("objects", "scrambled egg", "--data", shared_foon_dir).stdout.splitlines()
    assert len(text) == 15 and text[0].startswith(f"#{listed[0]['id']} ")
    # an object's text and its #ID name the same goal
    pick = listed[-1]
    by_text = json.loads(invoke("solve", "--data", shared_foon_dir, "--goal", pick["text"], "--format", "json").stdout)
    by_id = json.loads(
        invoke("solve", "--data", shared_foon_dir, "--goal", f"#{pick['id']}", "--format", "json").stdout
    )
    assert by_text == [dict(by_id[0], time_s=by_text[0]["time_s"], stats=by_text[0].get("stats"))] or by_text == [
        dict(by_id[0], time_s=by_text[0]["time_s"])
    ]
    assert by_text[0]["goal"] == {k: pick[k] for k in ("label", "states", "ingredients", "container")}
    # the JSON listing is a goals file
    goals = tmp_path / "eggs.json"
    goals.write_text(res.stdout)
    lines = invoke("solve", "--data", shared_foon_dir, "--goals", goals, "--format", "jsonl").stdout.splitlines()
    assert [json.loads(line)["goal"]["ingredients"] for line in lines] == [o["ingredients"] for o in listed]


def test_objects_filters_and_suggestions():
    kitchen = json.loads(invoke("objects", "--data", "demo", "--kitchen", "--format", "json").stdout)
    assert kitchen and all(o["in_kitchen"] for o in kitchen)
    made = json.loads(invoke("objects", "--data", "demo", "--produced", "--format", "json").stdout)
    assert made and all(o["producers"] > 0 for o in made)
    derivable = json.loads(invoke("objects", "--data", "demo", "--derivable", "--format", "json").stdout)
    assert {o["id"] for o in kitchen} <= {o["id"] for o in derivable}
    res = invoke("objects", "scrambld eg", "--data", "demo")
    assert res.exit_code == 2 and "closest labels: scrambled egg" in res.stderr


def test_check_reads_the_goal_from_the_foon_header_and_the_single_sink(shared_foon_dir, tmp_path):
    out = invoke("solve", "--data", shared_foon_dir, "--goals", "all", "--format", "foon")
    path = tmp_path / "all.foon"
    path.write_text(out.stdout)
    res = invoke("check", path, "--data", shared_foon_dir, "--no-optimum", "--format", "json")
    reports = json.loads(res.stdout)
    assert len(reports) == 25
    assert all(r["goal_source"] == "named in the file" for r in reports)
    # the two unreachable goals have no tree in the file: confirmed unreachable, exit 0
    assert [r["valid"] for r in reports].count(None) == 2 and res.exit_code == 0
    assert sum(1 for r in reports if r["problem"] == "unreachable") == 2
    # one tree without its header: the goal is the tree's only sink
    one = invoke("solve", "--data", shared_foon_dir, "--goal", "macaroni", "--format", "foon").stdout
    bare = tmp_path / "bare.foon"
    bare.write_text("".join(line + "\n" for line in one.splitlines() if not line.startswith("#")))
    res = invoke("check", bare, "--data", shared_foon_dir, "--no-optimum", "--format", "json")
    assert res.exit_code == 0, res.output
    (report,) = json.loads(res.stdout)
    assert report["valid"] and report["goal_source"] == "inferred from the units"
    assert report["goal"]["label"] == "macaroni"


def test_check_goals_file_picks_each_trees_goal(tmp_path):
    text = invoke("solve", "--data", "demo", "--goal", "scrambled egg", "--format", "foon").stdout
    path = tmp_path / "egg.foon"
    path.write_text("".join(ln + "\n" for ln in text.splitlines() if not ln.startswith("#")))
    res = invoke("check", path, "--data", "demo", "--goals", "all", "--no-optimum", "--format", "json")
    assert res.exit_code == 0, res.output
    (report,) = json.loads(res.stdout)
    assert report["goal_source"] == "--goals" and report["goal"]["label"] == "scrambled egg" and report["valid"]


def test_foon_alone_reads_the_files_beside_it(tmp_path):
    for name in ("FOON.txt", "kitchen.json", "goal_nodes.json"):
        shutil.copy(DEMO / name, tmp_path / name)
    res = invoke("solve", "--foon", tmp_path / "FOON.txt", "--format", "json")
    assert res.exit_code == 0, res.output
    assert [r["goal"]["label"] for r in json.loads(res.stdout)] == [
        "tomato salad",
        "scrambled egg",
        "whipped cream",
        "pancake",
    ]
    assert "no motion.txt beside" in res.stderr and "no utensils.txt beside" in res.stderr
    (tmp_path / "kitchen.json").unlink()
    res = invoke("solve", "--foon", tmp_path / "FOON.txt")
    assert res.exit_code == 2 and "no kitchen.json beside the FOON file" in res.stderr
    res = invoke("solve", "--goal", "tomato salad")
    assert res.exit_code == 2 and "no data given" in res.stderr and "--data demo" in res.stderr


def test_query_prints_only_what_it_shows_and_warns(tmp_path):
    prog = tmp_path / "n.lp"
    prog.write_text("n(N) :- N = #count { U : unit(U) }.\n#show n/1.\n")
    res = invoke("query", prog, "--data", "demo", "--encoding", "reachable", "--format", "json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    (model,) = out["models"]
    assert [a["predicate"] for a in model["atoms"]] == ["n"]
    assert out["encodings"] == ["tree", "reachable"]  # reachable pulls in tree
    typo = tmp_path / "typo.lp"
    typo.write_text("p(O) :- kitchn(O).\n#show p/1.\n")
    res = invoke("query", typo, "--data", "demo")
    assert res.exit_code == 0
    assert "foon2asp: warning:" in res.stderr and "kitchn" in res.stderr


def test_jsonl_streams_one_line_per_goal_and_compare_jsonl():
    lines = invoke("solve", "--data", "demo", "--format", "jsonl").stdout.splitlines()
    assert [json.loads(line)["goal"]["label"] for line in lines] == [
        "tomato salad",
        "scrambled egg",
        "whipped cream",
        "pancake",
    ]
    rows = [json.loads(line) for line in invoke("compare", "--data", "demo", "--format", "jsonl").stdout.splitlines()]
    assert len(rows) == 16 and all("valid" in r for r in rows)


def test_human_steps_need_success_and_models_are_ranked(shared_foon_dir):
    res = invoke("solve", "--data", "demo", "--goal", "tomato salad", "--human-steps", "2")
    assert res.exit_code == 2 and "'success' is an objective" in res.stderr
    res = invoke("solve", "--data", shared_foon_dir, "--goal", "macaroni", "--models", "3", "--format", "json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert [t["status"] for t in out] == ["optimal", "ranked", "ranked"]
    assert [t["cost"]["units"] for t in out] == sorted(t["cost"]["units"] for t in out)


def test_batch_rows_carry_valid(shared_foon_dir, tmp_path):
    out = tmp_path / "r.jsonl"
    res = invoke("batch", "--data", shared_foon_dir, "--method", "gbfs-h1", "-o", out, "--no-progress")
    records = read_results(out)  # the configuration header is not a record
    assert len(records) == 25 and all("valid" in r for r in records)
    invalid = [r for r in records if r["status"] == "found" and not r["valid"]]
    assert invalid and res.exit_code == 1
    assert any("valid" in line.split() for line in res.stdout.splitlines())  # the summary's column


def test_method_and_methods_are_one_option():
    a = json.loads(
        invoke("solve", "--data", "demo", "--goal", "tomato salad", "--methods", "ids", "--format", "json").stdout
    )
    b = json.loads(
        invoke("solve", "--data", "demo", "--goal", "tomato salad", "--method", "ids", "--format", "json").stdout
    )
    assert a[0]["method"] == b[0]["method"] == "ids"
    res = invoke("compare", "--data", "demo", "--goal", "tomato salad", "--method", "asp", "--format", "json")
    assert res.exit_code == 0 and [r["method"] for r in json.loads(res.stdout)] == ["asp"]


def test_usage_errors_have_the_one_error_style():
    for args in (["solve", "--bogus"], ["solve", "--format", "nope"], ["nope"]):
        res = invoke(*args)
        assert res.exit_code == 2, args
        err = res.stderr.strip()
        assert err.startswith("foon2asp: error: ") and len(err.splitlines()) == 1, err


def test_exit_codes_unreachable_is_answered():
    # whipped cream is proven unreachable in the demo: an answer, exit 0
    res = invoke("solve", "--data", "demo", "--goal", "whipped cream")
    assert res.exit_code == 0 and "unreachable" in res.stdout
    res = invoke("missing", "--data", "demo", "--goal", "pancake", "--objective", "success", "--format", "json")
    assert res.exit_code == 0 and json.loads(res.stdout)[0]["status"] == "optimal"


def test_numbers_are_printed_with_one_rule(shared_foon_dir, tmp_path):
    """Text outputs print a measure with 4 significant digits; JSON keeps the full value."""
    from foon2asp.tree.serialize import number

    js = json.loads(invoke("solve", "--data", shared_foon_dir, "--goal", "greek salad", "--format", "json").stdout)[0]
    success = js["cost"]["success"]
    text = invoke("solve", "--data", shared_foon_dir, "--goal", "greek salad").stdout
    assert f"success {number(success)}," in text and number(success) == f"{success:.4g}" != str(success)
    tree = tmp_path / "t.foon"
    tree.write_text(invoke("solve", "--data", shared_foon_dir, "--goal", "greek salad", "--format", "foon").stdout)
    checked = invoke("check", tree, "--data", shared_foon_dir).stdout
    assert f"success {number(success)}," in checked
    assert number(25) == "25" and number(0.02187) == "0.02187"
