"""The search baselines: IDS, GBFS-h1, GBFS-h2 (choices, faithfulness, completeness)."""

from __future__ import annotations

import html
import json
import random
import re
import shutil
import time

import pytest
from click.testing import CliRunner

from conftest import DEMO
from foon2asp import methods
from foon2asp.asp.options import AspOptions
from foon2asp.cli.main import main
from foon2asp.foon.goals import goal_id as goal_of
from foon2asp.search import IDS, gbfs, h1, h2
from foon2asp.tree.tasktree import measures
from foon2asp.tree.validate import check_order, validate
from helpers import best, brute_force, build, goal_id, obj


def run(problem, name, goal):
    return methods.runner(name, problem, AspOptions())(goal)


def test_registered():
    names = methods.names()
    for name in ("ids", "gbfs-h1", "gbfs-h2"):
        assert name in names
        assert methods.get(name).kind == "search"


# ---------------------------------------------------------------- IDS


def test_ids_prefers_shallow_tree_over_foon_order():
    # unit 0 (first in FOON order) needs a depth-2 chain; unit 1 needs a kitchen item
    p = build([("mix", ["a"], ["g"]), ("cook", ["k"], ["g"]), ("cut", ["k"], ["a"])], kitchen=["k"])
    tree = run(p, "ids", goal_id(p, "g"))
    assert tree.status == "found"
    assert tree.units == [1]
    assert tree.cost == measures(p, goal_id(p, "g"), [1])


def test_ids_takes_first_producer_in_foon_order_at_same_depth():
    p = build(
        [
            ("mix", ["k", "l", "m"], ["g"]),  # three inputs, FOON order first
            ("cook", ["k"], ["g"]),
        ],
        kitchen=["k", "l", "m"],
    )
    assert run(p, "ids", goal_id(p, "g")).units == [0]


def test_ids_order_is_executable_and_units_unique():
    # g <- u0(a, b); a <- u1(c); b <- u2(c); c <- u3(k): c is shared
    p = build(
        [("join", ["a", "b"], ["g"]), ("x", ["c"], ["a"]), ("y", ["c"], ["b"]), ("z", ["k"], ["c"])], kitchen=["k"]
    )
    g = goal_id(p, "g")
    tree = run(p, "ids", g)
    assert sorted(tree.units) == [0, 1, 2, 3]
    assert len(tree.units) == len(set(tree.units))
    assert check_order(p, g, tree.units) is None
    assert tree.units[0] == 3 and tree.units[-1] == 0


def test_ids_goal_in_kitchen_is_empty_tree():
    p = build([("cook", ["k"], ["g"])], kitchen=["k", "g"])
    tree = run(p, "ids", goal_id(p, "g"))
    assert tree.status == "found" and tree.units == []


def test_ids_cycle_is_not_found_and_bounded():
    # g needs x, x needs g: no tree; the bound stops at the fixpoint depth
    p = build([("a", ["x"], ["g"]), ("b", ["g"], ["x"]), ("c", ["k"], ["y"])], kitchen=["k"])
    search = IDS(p)
    tree = search(goal_id(p, "g"))
    assert tree.status == "not-found" and tree.units == []
    assert search.max_depth == 1
    assert all(depth <= search.max_depth for _, depth in search.memo)


def test_ids_memo_keeps_it_polynomial():
    # a ladder: a_k and b_k are each made from a_{k-1} and b_{k-1}; the
    # derivation tree has 2^n leaves, but (object, depth) pairs are few
    n = 40
    units = [("s", ["k"], ["a0"]), ("s", ["k"], ["b0"])]
    for k in range(1, n + 1):
        units.append(("m", [f"a{k - 1}", f"b{k - 1}"], [f"a{k}"]))
        units.append(("m", [f"a{k - 1}", f"b{k - 1}"], [f"b{k}"]))
    p = build(units, kitchen=["k"])
    search = IDS(p)
    g = goal_id(p, f"a{n}")
    tree = search(g)
    assert tree.status == "found"
    assert len(tree.units) == 2 * n + 1  # every b_k and a_k unit below, plus a_n's
    assert validate(p, g, tree.units).valid
    assert len(search.memo) <= len(p.objects) * (search.max_depth + 1)


def test_ids_utensil_rule_and_bare_outputs():
    bowl_tomato = obj("bowl", contains=["tomato"])
    tomato_in_bowl = obj("tomato", "chopped", inside="bowl")
    units = [
        # the bowl holding only the tomato is not a required input (utensil rule)
        ("mix", [bowl_tomato, tomato_in_bowl], ["salad"]),
        ("place", [obj("tomato", "chopped")], [tomato_in_bowl]),
        # an output with no state is not a product: this unit does not make the knife
        ("sharpen", ["k"], [obj("knife")]),
    ]
    p = build(units, kitchen=[obj("tomato", "chopped"), "k"], utensils={"bowl"})
    tree = run(p, "ids", goal_id(p, "salad"))
    assert tree.status == "found" and tree.units == [1, 0]
    assert run(p, "ids", p.foon.object_ids[obj("knife")]).status == "not-found"
    off = build(units, kitchen=[obj("tomato", "chopped"), "k"], utensils={"bowl"}, utensil_rule="off")
    assert run(off, "ids", goal_id(off, "salad")).status == "not-found"


# ---------------------------------------------------------------- GBFS


def choice_problem():
    """g has three producers: u0 (rate .5, 3 inputs), u1 (rate .9, 4 inputs), u2 (rate .9, 2 inputs)."""
    return build(
        [
            ("slow", ["k", "l", "m"], ["g"]),
            ("fast", ["k", "l", "m", "n"], ["g"]),
            ("quick", ["k", "l"], ["g"]),
            ("short", ["k"], ["g"]),
        ],
        kitchen=["k", "l", "m", "n"],
        rates={"slow": 0.5, "fast": 0.9, "quick": 0.9, "short": 0.2},
    )


def test_gbfs_h1_highest_rate_first_in_foon_order_on_ties():
    p = choice_problem()
    tree = run(p, "gbfs-h1", goal_id(p, "g"))
    assert tree.status == "found" and tree.units == [1]  # 'fast' and 'quick' tie at .9: 'fast' is first


def test_gbfs_h2_fewest_inputs():
    p = choice_problem()
    assert run(p, "gbfs-h2", goal_id(p, "g")).units == [3]


def test_gbfs_h2_ties_go_to_foon_order():
    p = build([("a", ["k", "l"], ["g"]), ("b", ["l", "k"], ["g"])], kitchen=["k", "l"])
    assert run(p, "gbfs-h2", goal_id(p, "g")).units == [0]


def test_gbfs_counts_all_inputs_but_queues_required_only():
    bowl_tomato = obj("bowl", contains=["tomato"])
    tomato_in_bowl = obj("tomato", "chopped", inside="bowl")
    p = build(
        [
            # 3 input nodes, but the bowl is not required (utensil rule) and has no producer
            ("mix", [bowl_tomato, tomato_in_bowl, "k"], ["g"]),
            ("stir", ["k", "l", "m", "n"], ["g"]),
        ],
        kitchen=[tomato_in_bowl, "k", "l", "m", "n"],
        utensils={"bowl"},
    )
    g = goal_id(p, "g")
    tree = run(p, "gbfs-h2", g)
    assert tree.status == "found" and tree.units == [0]
    assert validate(p, g, tree.units).valid


def test_gbfs_not_found_when_an_object_has_no_producer():
    p = build([("a", ["x", "k"], ["g"])], kitchen=["k"])
    for name in ("gbfs-h1", "gbfs-h2"):
        tree = run(p, name, goal_id(p, "g"))
        assert tree.status == "not-found" and tree.units == [] and tree.cost == {}


def test_gbfs_does_not_check_cycles():
    # the greedy choice for g (fast, few inputs) needs x, which only g makes
    p = build(
        [("pour", ["x"], ["g"]), ("fold", ["g", "k"], ["x"]), ("chop", ["k", "l", "m"], ["g"])],
        kitchen=["k", "l", "m"],
        rates={"pour": 0.9, "fold": 0.9, "chop": 0.1},
    )
    g = goal_id(p, "g")
    for name in ("gbfs-h1", "gbfs-h2"):
        tree = run(p, name, g)
        assert tree.status == "found"
        assert sorted(tree.units) == [0, 1]
        assert not validate(p, g, tree.units).valid
        assert tree.cost["depth"] is None
    assert run(p, "ids", g).units == [2]


def test_gbfs_order_is_reverse_selection_order():
    # selection order: u0 (for g), then u1 (for a), then u2 (for b): written reversed
    p = build([("join", ["a", "b"], ["g"]), ("x", ["k"], ["a"]), ("y", ["a"], ["b"])], kitchen=["k"])
    tree = gbfs(p, goal_id(p, "g"), h1, "gbfs-h1")
    assert tree.units == [2, 1, 0]
    # kept as is although u2 needs a, which u1 makes later in that order
    assert check_order(p, goal_id(p, "g"), tree.units) is not None
    assert validate(p, goal_id(p, "g"), tree.units).valid


def test_heuristics_scores():
    p = choice_problem()
    assert [h1(p, u) for u in range(4)] == [0.5, 0.9, 0.9, 0.2]
    assert [h2(p, u) for u in range(4)] == [-3, -4, -2, -1]


# ---------------------------------------------------------------- against brute force


def random_problem(rng: random.Random):
    names = ["k1", "k2", "a", "b", "c", "d", "g"]
    units = []
    for _ in range(rng.randint(3, 8)):
        ins = rng.sample(names, rng.randint(1, 3))
        out = rng.choice(["a", "b", "c", "d", "g"])
        units.append((rng.choice(["pour", "mix", "cut"]), ins, [out]))
    rates = {"pour": 0.9, "mix": 0.5, "cut": 0.1}
    return build(units, kitchen=["k1", "k2"], rates=rates)


@pytest.mark.parametrize("seed", range(150))
def test_against_brute_force(seed):
    p = random_problem(random.Random(seed))
    if as_id(p, "g") is None:
        return
    g = as_id(p, "g")
    smallest, _ = best(p, g, lambda m: m["units"])
    exists = bool(brute_force(p, g))
    ids = run(p, "ids", g)
    # IDS is complete and sound: it finds a tree iff one exists, and it is valid
    assert (ids.status == "found") == exists
    if exists:
        assert validate(p, g, ids.units).valid
        assert check_order(p, g, ids.units) is None
        assert len(ids.units) >= smallest
        assert ids.cost["depth"] == p.derivation_levels()[0][g]
    for name in ("gbfs-h1", "gbfs-h2"):
        tree = run(p, name, g)
        if tree.status == "found" and validate(p, g, tree.units).valid:
            assert len(tree.units) >= smallest


def as_id(problem, label):
    return problem.foon.object_ids.get(obj(label, "s"))


# ---------------------------------------------------------------- the universal FOON


@pytest.fixture(scope="module")
def shared_trees(shared_problem):
    data, problem = shared_problem
    goals = [goal_of(problem, o) for o, _ in data.goals]
    runs = {name: methods.runner(name, problem, AspOptions()) for name in ("ids", "gbfs-h1", "gbfs-h2")}
    return problem, {problem.objects[g].label: (g, {n: r(g) for n, r in runs.items()}) for g in goals}


def test_shared_ids_found_iff_derivable_and_valid(shared_trees):
    problem, trees = shared_trees
    assert len(trees) == 25
    levels, _ = problem.derivation_levels()
    for label, (g, by) in trees.items():
        t = by["ids"]
        assert (t.status == "found") == (g in problem.derivable), label
        if t.status == "found":
            assert validate(problem, g, t.units).valid, label
            assert check_order(problem, g, t.units) is None, label
            assert t.cost["depth"] == levels[g], label
    assert {k for k, (g, by) in trees.items() if by["ids"].status == "not-found"} == {"whipped cream", "fried rice"}


def test_shared_greedy_trees_always_found_some_invalid(shared_trees):
    problem, trees = shared_trees
    for label, (g, by) in trees.items():
        for name in ("gbfs-h1", "gbfs-h2"):
            assert by[name].status == "found", (label, name)
    for label in ("whipped cream", "fried rice"):
        g, by = trees[label]
        for name in ("gbfs-h1", "gbfs-h2"):
            assert not validate(problem, g, by[name].units).valid, (label, name)


def test_solve_command_accepts_search_methods():
    import json

    from click.testing import CliRunner

    from foon2asp.cli.main import main

    for name in ("ids", "gbfs-h1", "gbfs-h2"):
        res = CliRunner().invoke(
            main, ["solve", "--data", "demo", "--goal", "tomato salad", "--method", name, "--format", "json"]
        )
        assert res.exit_code == 0, res.output
        (out,) = json.loads(res.stdout)
        assert out["method"] == name and out["status"] == "found"
        assert out["cost"]["units"] == len(out["units"]) > 0


# What the search baselines' trees look like in every output: text says INVALID and never None.


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_text_of_an_invalid_greedy_tree_says_invalid():
    res = cli("solve", "--data", "demo", "--goal", "scrambled egg", "--method", "gbfs-h1")
    assert res.exit_code == 1  # an invalid tree
    lines = res.stdout.splitlines()
    assert lines[1] == "Method: gbfs-h1  Status: found  (units 4, success 0.1458, inputs 8, depth -)"
    assert lines[2] == (
        "INVALID: circular support: [egg, beaten, in [bowl]] is made by unit 8 (pour), which needs"
        " [egg, beaten, in [jar]]; [egg, beaten, in [jar]] is made by unit 9 (pour), which needs [egg, beaten, in [bowl]]"
    )
    assert "None" not in res.stdout
    valid = cli("solve", "--data", "demo", "--goal", "tomato salad", "--method", "gbfs-h1")
    assert valid.exit_code == 0 and "INVALID" not in valid.stdout and "None" not in valid.stdout


def test_text_and_json_agree_on_every_shared_goal(shared_foon_dir):
    for method in ("gbfs-h1", "gbfs-h2"):
        args = ("solve", "--data", shared_foon_dir, "--goals", "all", "--method", method)
        answers = json.loads(cli(*args, "--format", "json").stdout)
        text = cli(*args).stdout
        assert "None" not in text
        invalid = [a for a in answers if a.get("valid") is False]
        assert invalid  # the greedy trees for whipped cream and fried rice, at least
        assert text.count("\nINVALID: ") == len(invalid)
        for a in invalid:
            assert f"\nINVALID: {a['problem']}\n" in text


# ---------------------------------------------------------------- HTML pages

needs_dot = pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' is not installed")
TIME = re.compile(r'<p class="time">Time: ([\d.]+) s in all: solving ([\d.]+) s, drawing this page ([\d.]+) s \(')


def figures(page: str) -> dict[str, str]:
    """Each figure of an HTML page by its id."""
    return dict(re.findall(r'<figure [^>]*id="([^"]+)">(.*?)</figure>', page, re.S))


def node_classes(svg: str) -> list[str]:
    return re.findall(r'<g id="[^"]*" class="node ([^"]*)"', svg)


@needs_dot
def test_batch_summary_html_marks_invalid_trees_their_cycle_the_kitchen_and_the_goal(tmp_path):
    out = tmp_path / "r.jsonl"
    args = ("--goals", "all", "--methods", "asp,gbfs-h1", "--output", out, "--summary", "html", "--no-progress")
    res = cli("batch", "--data", "demo", *args)
    assert res.exit_code == 1  # the greedy trees for scrambled egg and whipped cream are invalid
    page = res.stdout
    heads = re.findall(r'<figure class="tree (\w+)" data-method="([^"]+)" data-units="(\d+)" id="(r\d)">', page)
    assert heads == [
        ("valid", "asp", "4", "r1"),
        ("valid", "gbfs-h1", "5", "r2"),
        ("valid", "asp", "4", "r3"),
        ("invalid", "gbfs-h1", "4", "r4"),
        ("invalid", "gbfs-h1", "3", "r5"),
    ]
    records = [json.loads(line) for line in out.read_text().splitlines()[1:]]
    invalid = [r for r in records if r.get("valid") is False and r["units"]]
    drawn = figures(page)
    for fig, record in zip(("r4", "r5"), invalid):
        assert "<b>INVALID</b>" in drawn[fig]
        assert f'<p class="problem">{html.escape(record["problem"], quote=True)}</p>' in drawn[fig]
        classes = node_classes(drawn[fig])
        assert sum("cycle" in c.split() for c in classes) == 4  # two objects and the two units making them
    for fig, svg in drawn.items():
        classes = [c.split() for c in node_classes(svg)]
        assert sum("goal" in c for c in classes) == 1, fig
        assert any("kitchen" in c for c in classes), fig
    assert "INVALID" not in drawn["r1"] + drawn["r2"] + drawn["r3"]


@needs_dot
def test_batch_summary_html_counts_the_time_spent_drawing(tmp_path, monkeypatch):
    from foon2asp.report import draw

    slow = draw.svg_text

    def svg_text(graph):
        time.sleep(0.2)
        return slow(graph)

    monkeypatch.setattr(draw, "svg_text", svg_text)
    out = tmp_path / "r.jsonl"
    args = ("--goals", "all", "--methods", "asp", "--output", out, "--summary", "html", "--no-progress")
    res = cli("batch", "--data", "demo", *args)
    assert res.exit_code == 0, res.output
    total, solving, drawing = map(float, TIME.search(res.stdout).groups())
    assert drawing >= 0.4  # two trees drawn, 0.2 s each
    assert solving < drawing and abs(total - solving - drawing) <= 0.011
    assert "with 1 worker(s)" in res.stdout.split("<table")[0]


@needs_dot
def test_compare_and_consolidate_pages_say_how_long_they_took():
    page = cli("compare", "--data", "demo", "--format", "html").stdout
    found = re.search(
        r'<p class="time">Time: ([\d.]+) s in all: solving ([\d.]+) s, drawing this page ([\d.]+) s'
        r" \(solving: each method&#x27;s times per goal, summed: ids [\d.]+ s, gbfs-h1 [\d.]+ s, gbfs-h2 [\d.]+ s,"
        r" asp optimum [\d.]+ s; loading the data is not counted\)\.</p>",
        page,
    )
    assert found
    smoothies = sorted(str(p) for p in (DEMO / "llm").glob("smoothie-*.json"))
    page = cli("consolidate", *smoothies, "--format", "html").stdout
    assert re.search(r'<p class="time">Time: [\d.]+ s in all: solving [\d.]+ s, drawing this page [\d.]+ s \(', page)
    assert '<a class="zoom" href="#c1">full size</a>' in page
