"""Checking task trees: reading them, the verdict, the first problem, exit codes."""

from __future__ import annotations

import itertools
import json
import random

import pytest
from click.testing import CliRunner

from conftest import DEMO
from foon2asp import methods
from foon2asp.asp.options import AspOptions
from foon2asp.cli.main import main
from foon2asp.errors import InputError
from foon2asp.foon.goals import resolve_label
from foon2asp.foon.parser import format_units, unit_lines
from foon2asp.foon.treefiles import read_trees
from foon2asp.tree.validate import check_units
from helpers import build, goal_id, obj


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def assert_cycle(problem, finding, units):
    """The cycle really is one: each object is made by its unit, which needs the next object,
    and none of them can be made from the kitchen with these units."""
    assert finding.kind == "cycle"
    derivable, _ = problem.derivation_levels(list(units))
    n = len(finding.cycle)
    assert n >= 1
    for k, (o, u) in enumerate(finding.cycle):
        nxt = finding.cycle[(k + 1) % n][0]
        assert u in units
        assert o in problem.products[u]
        assert nxt in problem.required[u]
        assert o not in derivable
    assert len({o for o, _ in finding.cycle}) == n


# ---------------------------------------------------------------- diagnosis on small FOONs


def test_cycle_named():
    p = build([("pour", ["x", "k"], ["g"]), ("fold", ["g"], ["x"]), ("cut", ["k"], ["y"])], kitchen=["k"])
    g = goal_id(p, "g")
    validation, finding = check_units(p, g, [0, 1, 2])
    assert not validation.valid
    assert_cycle(p, finding, [0, 1, 2])
    assert {o for o, _ in finding.cycle} == {g, goal_id(p, "x")}
    assert "circular support" in finding.message


def test_self_loop_named():
    # a unit whose output is one of its own inputs (as in the universal FOON's packet of vegetables)
    p = build([("pour", ["pk", "k"], ["pk", "g"])], kitchen=["k"])
    _, finding = check_units(p, goal_id(p, "g"), [0])
    assert_cycle(p, finding, [0])
    assert finding.cycle == [(goal_id(p, "pk"), 0)]


def test_missing_input():
    p = build([("pour", ["x", "k"], ["g"]), ("cut", ["k"], ["x"])], kitchen=["k"])
    _, finding = check_units(p, goal_id(p, "g"), [0])
    assert finding.kind == "missing-input"
    assert finding.obj == goal_id(p, "x") and finding.unit == 0


def test_goal_not_made():
    p = build([("pour", ["k"], ["g"]), ("cut", ["k"], ["x"])], kitchen=["k"])
    validation, finding = check_units(p, goal_id(p, "g"), [1])
    assert not validation.valid
    assert finding.kind == "goal-not-made" and finding.obj == goal_id(p, "g")


def test_valid_has_no_finding():
    p = build([("pour", ["x"], ["g"]), ("cut", ["k"], ["x"])], kitchen=["k"])
    validation, finding = check_units(p, goal_id(p, "g"), [0, 1])
    assert validation.valid and finding is None


def test_extra_unit_on_a_cycle_is_invalid_even_if_goal_made():
    p = build([("pour", ["k"], ["g"]), ("a", ["y"], ["x"]), ("b", ["x"], ["y"])], kitchen=["k"])
    validation, finding = check_units(p, goal_id(p, "g"), [0, 1, 2])
    assert not validation.valid
    assert_cycle(p, finding, [0, 1, 2])


@pytest.mark.parametrize("seed", range(40))
def test_diagnosis_agrees_with_validator(seed):
    rng = random.Random(seed)
    names = ["k", "a", "b", "c", "g"]
    units = [
        (rng.choice(["m", "n"]), rng.sample(names, rng.randint(1, 2)), [rng.choice(names[1:])])
        for _ in range(rng.randint(3, 7))
    ]
    p = build(units, kitchen=["k"])
    g = goal_id(p, "g") if obj("g", "s") in p.foon.object_ids else None
    if g is None:
        return
    for k in range(len(p.units) + 1):
        for subset in itertools.combinations(range(len(p.units)), k):
            subset = list(subset)
            validation, finding = check_units(p, g, subset)
            assert (finding is None) == validation.valid
            if finding is None:
                continue
            made, _ = p.derivation_levels(subset)
            if finding.kind == "cycle":
                assert_cycle(p, finding, subset)
            elif finding.kind == "missing-input":
                assert finding.obj not in made
                assert finding.obj in p.required[finding.unit] and finding.unit in subset
                assert not any(finding.obj in p.products[u] for u in subset)
            else:
                assert finding.kind == "goal-not-made"
                assert not any(g in p.products[u] for u in subset)


# ---------------------------------------------------------------- reading tree files


TREE = """# a tree as the earlier programs wrote it
//
O\tegg
S\tuncracked
O\tbowl
S\tempty
M\tcrack
O\tbowl
S\tcontains\t{egg white and yolk}
O\tegg white and yolk
S\tin\t[bowl]
//
"""


def test_read_foon_text_with_and_without_leading_separator(tmp_path):
    for text in (TREE, TREE.replace("//\n", "", 1), TREE.rstrip("/\n") + "\n"):
        path = tmp_path / "t.txt"
        path.write_text(text)
        (tree,) = read_trees(path)
        assert len(tree.units) == 1
        assert tree.units[0].unit.motion == "crack"
        assert tree.units[0].line == text.splitlines().index("O\tegg") + 1
        assert tree.goal is None


def test_read_json_result_list(tmp_path):
    path = tmp_path / "t.json"
    res = cli("solve", "--data", "demo", "--goals", "all", "--format", "json")
    assert res.exit_code == 0
    path.write_text(res.stdout)
    trees = read_trees(path)
    assert len(trees) == 4
    assert [len(t.units) for t in trees] == [len(r["units"]) for r in json.loads(res.stdout)]
    assert trees[0].goal.label == "tomato salad" and trees[0].method == "asp-units"
    assert trees[1].line > trees[0].line


@pytest.mark.parametrize(
    "text, line",
    [
        ("O\tegg\nX\tbad line\n", 2),
        ("O\tegg\nM\tcrack\nM\tcrack\n", 3),
        ('[\n  {"goal": null,\n   "units": [1, 2]\n  }\n]\n', 2),
        ('[\n  {"units": []},\n  {"units": 5}\n]\n', 3),
        ('[\n  {"units": [\n  oops\n]}]\n', 3),
    ],
)
def test_bad_tree_files_name_the_line(tmp_path, text, line):
    path = tmp_path / "bad.txt"
    path.write_text(text)
    with pytest.raises(InputError) as info:
        read_trees(path)
    assert info.value.path == str(path) and info.value.line == line


def test_empty_tree_file_is_bad_input(tmp_path):
    path = tmp_path / "empty.txt"
    path.write_text("# nothing\n//\n")
    res = cli("check", path, "--data", DEMO)
    assert res.exit_code == 2
    assert str(path) in res.stderr and len(res.stderr.strip().splitlines()) == 1


# ---------------------------------------------------------------- the command on the demo data


def write_tree(tmp_path, name, problem, units):
    path = tmp_path / name
    path.write_text(format_units(problem.units[u] for u in units))
    return path


def test_check_demo_valid_and_greedy_trap(tmp_path, demo_problem):
    data, problem = demo_problem
    g = resolve_label(data, problem, "scrambled egg")
    asp = methods.runner("asp", problem, AspOptions())(g)
    greedy = methods.runner("gbfs-h1", problem, AspOptions())(g)
    ok = cli("check", write_tree(tmp_path, "asp.txt", problem, asp.units), "--data", DEMO)
    assert ok.exit_code == 0, ok.output
    assert "Verdict: VALID" in ok.stdout and "this tree is the optimum" in ok.stdout
    bad = cli("check", write_tree(tmp_path, "greedy.txt", problem, greedy.units), "--data", DEMO, "--format", "json")
    assert bad.exit_code == 1
    (report,) = json.loads(bad.stdout)
    assert report["valid"] is False and report["problem"] == "cycle"
    cycle_objects = {(c["object"]["label"], c["object"]["container"]) for c in report["cycle"]}
    # the egg is poured bowl -> jar -> bowl (see data/FOON.txt)
    assert cycle_objects == {("egg", "bowl"), ("egg", "jar")}
    assert report["optimum"]["cost"]["units"] == len(asp.units)


def test_check_exit_codes_on_json_with_several_trees(tmp_path):
    res = cli("solve", "--data", "demo", "--goals", "all", "--format", "json")
    path = tmp_path / "asp.json"
    path.write_text(res.stdout)
    # tomato salad and scrambled egg are valid; the two unreachable goals have no tree to check
    out = cli("check", path, "--data", DEMO, "--format", "json", "--no-optimum")
    assert out.exit_code == 0
    reports = json.loads(out.stdout)
    assert [r["valid"] for r in reports] == [True, True, None, None]
    assert [r["problem"] for r in reports[2:]] == ["unreachable", "unreachable"]
    answers = json.loads(res.stdout)
    only_valid = answers[:2]
    path.write_text(json.dumps(only_valid))
    assert cli("check", path, "--data", DEMO, "--no-optimum").exit_code == 0
    # a tree that does not make its goal is invalid: exit 1
    answers[0]["goal"] = answers[1]["goal"]
    path.write_text(json.dumps(answers))
    assert cli("check", path, "--data", DEMO, "--no-optimum").exit_code == 1


def test_check_order_as_written(tmp_path, demo_problem):
    data, problem = demo_problem
    g = resolve_label(data, problem, "tomato salad")
    units = methods.runner("asp", problem, AspOptions())(g).units
    res = cli(
        "check",
        write_tree(tmp_path, "rev.txt", problem, list(reversed(units))),
        "--data",
        DEMO,
        "--goal",
        "tomato salad",
    )
    assert res.exit_code == 0  # the set is judged; the order is reported
    assert "not executable as written" in res.stdout


# ---------------------------------------------------------------- the command on the universal FOON


@pytest.fixture(scope="module")
def shared_trees(shared_problem, tmp_path_factory):
    data, problem = shared_problem
    out = tmp_path_factory.mktemp("trees")
    goals = {
        label: resolve_label(data, problem, label)
        for label in ("greek salad", "whipped cream", "fried rice", "macaroni")
    }
    paths = {}
    for name in ("asp", "gbfs-h1", "gbfs-h2"):
        run = methods.runner(name, problem, AspOptions())
        for label, g in goals.items():
            tree = run(g)
            paths[label, name] = (write_tree(out, f"{label}-{name}.txt", problem, tree.units), tree)
    return data, problem, goals, paths


def test_shared_valid_tree(shared_foon_dir, shared_trees):
    _, problem, goals, paths = shared_trees
    path, tree = paths["greek salad", "asp"]
    res = cli("check", path, "--data", shared_foon_dir)
    assert res.exit_code == 0, res.output
    assert f"Units: {len(tree.units)} read, {len(tree.units)} found in the FOON, 0 unknown" in res.stdout
    assert "(inferred from the units)" in res.stdout and "greek salad" in res.stdout.splitlines()[1]
    assert "Order: the steps as written are executable" in res.stdout


@pytest.mark.parametrize("method", ["gbfs-h1", "gbfs-h2"])
def test_shared_whipped_cream_greedy_is_circular(shared_foon_dir, shared_trees, method):
    _, problem, goals, paths = shared_trees
    path, tree = paths["whipped cream", method]
    res = cli("check", path, "--data", shared_foon_dir, "--goal", "whipped cream", "--format", "json")
    assert res.exit_code == 1
    (report,) = json.loads(res.stdout)
    assert report["valid"] is False and report["problem"] == "cycle"
    assert report["optimum"]["status"] == "unreachable"
    _, finding = check_units(problem, goals["whipped cream"], tree.units)
    assert_cycle(problem, finding, tree.units)
    assert [c["unit"] for c in report["cycle"]] == [u for _, u in finding.cycle]
    text = cli("check", path, "--data", shared_foon_dir, "--goal", "whipped cream", "--no-optimum")
    assert "circular support" in text.stdout and "(back to the start)" in text.stdout


def test_shared_fried_rice_greedy_rests_on_the_packet(shared_trees):
    _, problem, goals, paths = shared_trees
    packet = problem.foon.object_ids[obj("packet", contains=["carrot", "corn", "green pea"])]
    assert packet not in problem.kitchen
    # the only unit making the packet needs the packet itself
    assert all(packet in problem.required[u] for u in problem.producers[packet])
    for method in ("gbfs-h1", "gbfs-h2"):
        _, tree = paths["fried rice", method]
        _, finding = check_units(problem, goals["fried rice"], tree.units)
        assert_cycle(problem, finding, tree.units)
        assert packet in {o for o, _ in finding.cycle}


def test_shared_unknown_unit(tmp_path, shared_foon_dir, shared_trees):
    _, problem, goals, paths = shared_trees
    _, tree = paths["macaroni", "asp"]
    lines = []
    for step, u in enumerate(tree.units, 1):
        unit_text = unit_lines(problem.units[u])
        if step == 2:
            unit_text[0] += " flavoured"  # a label the FOON does not have
        lines += unit_text
    path = tmp_path / "unknown.txt"
    path.write_text("//\n" + "\n".join(lines) + "\n")
    res = cli("check", path, "--data", shared_foon_dir, "--goal", "macaroni", "--format", "json", "--no-optimum")
    assert res.exit_code == 1
    (report,) = json.loads(res.stdout)
    assert report["problem"] == "unknown-unit" and report["unknown_steps"] == [2]
    assert "flavoured" in report["message"]


def test_shared_wrong_goal(shared_foon_dir, shared_trees):
    _, problem, goals, paths = shared_trees
    path, _ = paths["macaroni", "asp"]
    res = cli("check", path, "--data", shared_foon_dir, "--goal", "greek salad")
    assert res.exit_code == 1
    assert "no unit of the tree makes the goal greek salad" in res.stdout


def test_shared_bad_input(tmp_path, shared_foon_dir):
    path = tmp_path / "bad.txt"
    path.write_text("//\nO\tonion\nS\twhole\nbad line\n")
    res = cli("check", path, "--data", shared_foon_dir)
    assert res.exit_code == 2
    err = res.stderr.strip()
    assert len(err.splitlines()) == 1 and f"{path}:4:" in err and "Traceback" not in res.output
    assert cli("check", tmp_path / "missing.txt", "--data", shared_foon_dir).exit_code == 2
    assert cli("check", path, "--data", tmp_path / "nope").exit_code == 2


# ``check`` on foon2asp's own answers for unreachable goals: no tree to check, confirmed by the FOON.


UNREACHABLE = (
    "Verdict: unreachable: no tree to check (confirmed: the goal is not derivable from the kitchen"
    " with any units of the FOON)"
)


def solved(tmp_path, data, fmt):
    res = cli("solve", "--data", data, "--goals", "all", "--format", fmt)
    assert res.exit_code == 0, res.output
    path = tmp_path / f"trees.{fmt}"
    path.write_text(res.stdout)
    return path


@pytest.fixture(params=["demo", "shared"])
def data(request):
    if request.param == "demo":
        return "demo", 4, 2
    return request.getfixturevalue("shared_foon_dir"), 25, 2  # whipped cream and fried rice


@pytest.mark.parametrize("fmt", ["json", "foon"])
def test_round_trip_solve_check(tmp_path, data, fmt):
    folder, n, gone = data
    path = solved(tmp_path, folder, fmt)
    res = cli("check", path, "--data", folder)
    assert res.exit_code == 0, res.output
    assert res.stdout.count(UNREACHABLE) == gone
    assert "INVALID" not in res.stdout
    assert (
        res.stdout.splitlines()[-1]
        == f"Checked {n} trees: {n - gone} valid, 0 invalid, {gone} unreachable (no tree to check)"
    )
    # an unreachable answer has no size: no 'success 1' for a tree that is not there
    assert "Size: 0 units" not in res.stdout
    js = cli("check", path, "--data", folder, "--format", "json", "--no-optimum")
    assert js.exit_code == 0, js.output
    reports = json.loads(js.stdout)
    assert len(reports) == n
    gone_reports = [r for r in reports if r["problem"] == "unreachable"]
    assert len(gone_reports) == gone
    assert all(r["valid"] is None and r["message"].startswith("unreachable: no tree to check") for r in gone_reports)
    assert all(r["valid"] is True for r in reports if r not in gone_reports)


@pytest.mark.parametrize("fmt", ["json", "foon"])
def test_round_trip_through_an_output_folder(tmp_path, fmt):
    out = tmp_path / "trees"
    res = cli("solve", "--data", "demo", "--goals", "all", "--format", fmt, "-o", out)
    assert res.exit_code == 0, res.output
    files = sorted(out.iterdir())
    assert len(files) == 4
    res = cli("check", *files, "--data", DEMO, "--no-optimum")
    assert res.exit_code == 0, res.output
    assert res.stdout.count(UNREACHABLE) == 2
    assert res.stdout.splitlines()[-1] == "Checked 4 trees: 2 valid, 0 invalid, 2 unreachable (no tree to check)"
    # one file, one tree: no count at the end
    one = cli("check", files[2], "--data", DEMO, "--no-optimum")
    assert one.exit_code == 0 and "whipped cream" in one.stdout and UNREACHABLE in one.stdout
    assert "Checked" not in one.stdout


def test_no_units_for_a_reachable_goal_is_invalid(tmp_path):
    answers = json.loads(cli("solve", "--data", "demo", "--goals", "all", "--format", "json").stdout)
    answers[0].update(status="unknown", units=[], cost={})  # tomato salad, as a time limit would leave it
    path = tmp_path / "cut.json"
    path.write_text(json.dumps(answers))
    res = cli("check", path, "--data", DEMO, "--no-optimum")
    assert res.exit_code == 1
    assert (
        "Verdict: INVALID\nProblem: no tree to check, but the goal is derivable from the kitchen:"
        " the file gives no units for it\n"
    ) in res.stdout
    assert res.stdout.splitlines()[-1] == "Checked 4 trees: 1 valid, 1 invalid, 2 unreachable (no tree to check)"
    (first, *_) = json.loads(cli("check", path, "--data", DEMO, "--format", "json", "--no-optimum").stdout)
    assert first["valid"] is False and first["problem"] == "no-tree"


def test_a_meal_with_an_unreachable_dish(tmp_path):
    path = tmp_path / "meal.json"
    path.write_text(json.dumps([{"units": []}]))
    res = cli("check", path, "--data", DEMO, "--goal", "tomato salad", "--goal", "whipped cream", "--no-optimum")
    assert res.exit_code == 0, res.output
    assert (
        "Verdict: unreachable: no tree to check (confirmed: whipped cream, whipped, in [mixing bowl]"
        " is not derivable from the kitchen with any units of the FOON)"
    ) in res.stdout
    both = cli("check", path, "--data", DEMO, "--goal", "tomato salad", "--goal", "scrambled egg", "--no-optimum")
    assert (
        both.exit_code == 1
        and "Problem: no tree to check, but tomato salad, mixed, in [bowl] is derivable" in both.stdout
    )


# ---------------------------------------------------------------- files check reads, and those it does not


def test_check_reads_the_results_of_batch_and_judges_each_tree(tmp_path):
    results = tmp_path / "results.jsonl"
    res = cli("batch", "--data", "demo", "--goals", "all", "--methods", "asp,gbfs-h2", "--output", results)
    assert res.exit_code == 1, res.output  # gbfs-h2's egg is invalid
    lines = results.read_text().splitlines()
    assert len(lines) == 9 and '"foon2asp_results"' in lines[0]
    res = cli("check", results, "--data", "demo", "--format", "json")
    assert res.exit_code == 1, res.output
    reports = json.loads(res.stdout)
    records = [json.loads(line) for line in lines[1:]]
    assert len(reports) == len(records) == 8
    for report, record in zip(reports, records):
        assert report["goal"]["label"] == record["goal"]["label"]
        assert report["method"] == record["method"]
        if record["units"]:
            assert report["valid"] == record["valid"], (report, record)
        else:
            assert (report["valid"], report["problem"]) == (None, "unreachable")
    res = cli("check", results, "--data", "demo")
    assert f"Tree: {results} (line 2)  method asp-units" in res.stdout


def test_a_cut_line_of_a_results_file_is_located(tmp_path):
    results = tmp_path / "results.jsonl"
    assert cli("batch", "--data", "demo", "--goals", "all", "--output", results).exit_code == 0
    text = results.read_text()
    results.write_text(text[: len(text) - 40])  # the last line cut short
    res = cli("check", results, "--data", "demo")
    assert res.exit_code == 2
    assert res.stderr.startswith(f"foon2asp: error: {results}:5:") and "bad JSON" in res.stderr


@pytest.mark.parametrize(
    "name, text, seems",
    [
        ("domain.pddl", "; written by foon2asp export pddl\n(define (domain foon)\n", "a PDDL domain or problem"),
        ("chart.svg", '<?xml version="1.0"?>\n<svg width="10pt"></svg>\n', "an SVG, HTML or XML document"),
        ("summary.csv", "method,results,statuses\nasp,4,optimal=2\n", "a CSV table"),
        ("plan.txt", "(u3-chop)\n; cost = 1 (unit cost)\n", "a plan (checked with --data or --foon"),
        ("notes.txt", "Remember to buy eggs.\n", None),
    ],
)
def test_a_file_check_does_not_read_gets_the_formats_it_reads(tmp_path, name, text, seems):
    path = tmp_path / name
    path.write_text(text)
    res = cli("check", path)
    assert res.exit_code == 2
    (line,) = res.stderr.splitlines()
    assert line.startswith(f"foon2asp: error: {path}: not a task tree")
    assert (f"not a task tree: {seems}" in line) if seems else ("not a task tree; check reads" in line)
    assert line.endswith(
        "check reads FOON text, FOON JSON, foon2asp JSON ('solve --format json', 'batch' results), the unit lists"
        " of generated trees ('solve --format units-json'), plans for 'export pddl' (with --data or --foon) and"
        " schedules ('schedule --format json')"
    )


def test_a_foon_file_with_a_bad_line_is_still_located(tmp_path):
    path = tmp_path / "tree.txt"
    path.write_text("O\ttomato\nS\twhole\nQ\twhat\n")
    res = cli("check", path)
    assert res.stderr.strip() == f"foon2asp: error: {path}:3: unknown line type 'Q\\twhat' (expected O, S, M, // or #)"


def test_a_tree_whose_last_unit_makes_nothing_names_that_unit(tmp_path):
    """Outputs without states, ingredients or container are no products: the goal cannot be told."""
    units = json.loads(cli("solve", "--data", "demo", "--goal", "tomato salad", "--format", "units-json").stdout)
    for unit in units:
        for node in unit["input_nodes"] + unit["output_nodes"]:
            node.update(states=[], ingredients=[], container=None)
    path = tmp_path / "bare.json"
    path.write_text("[\n" + ",\n".join(json.dumps(u) for u in units) + "\n]\n")
    res = cli("check", path, "--data", "demo")
    assert res.stderr.strip() == (
        f"foon2asp: error: {path}: cannot tell which object is the goal of this tree (its last unit, step 4 at"
        f" {path}:5 (mix), makes no object: it outputs tomato salad | spoon, with no states, ingredients or"
        " container); use --goal TEXT or --goals FILE"
    )
    res = cli("check", path)  # on its own
    assert res.exit_code == 1
    assert (
        "Problem: no goal: no unit makes an object; the last, step 4 (mix), outputs tomato salad | spoon, with no"
        " states, ingredients or container"
    ) in res.stdout
