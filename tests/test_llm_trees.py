"""Trees from language models through the command line and the library: the unit-list JSON read
wherever a FOON or a tree is read and written back (--format units-json), --kitchen leaves,
check of tree files on their own (verdicts against the independent validator), motion costs
(--motion-cost, --objective cost against brute force), exit codes and one-line errors."""

from __future__ import annotations

import json
import random
from decimal import Decimal
from pathlib import Path

import pytest
from click.testing import CliRunner

import foon2asp
from foon2asp.cli.main import main
from foon2asp.foon.model import Foon, FoonObject, Unit
from foon2asp.foon.parser import read_foon, read_foons
from foon2asp.foon.problem import Problem
from foon2asp.tree.validate import check_order, validate
from helpers import brute_force
from test_objectives import random_foon

REPO = Path(__file__).resolve().parent.parent
LLM = REPO / "data" / "llm"
SMOOTHIES = sorted(LLM.glob("smoothie-*.json"))
GLASS = "smoothie, blended, in [glass]"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def one_line_error(res, *words):
    assert res.exit_code == 2, res.output
    err = res.stderr.strip()
    assert len(err.splitlines()) == 1 and err.startswith("foon2asp: error: "), err
    for w in words:
        assert w in err, err


def node_json(obj: FoonObject, rng: random.Random) -> dict:
    """An object as a generator might write it: null or missing lists, no container key."""
    out: dict = {"label": obj.label.upper() if rng.random() < 0.2 else obj.label}
    for name, items in (("states", obj.states), ("ingredients", obj.ingredients)):
        if items or rng.random() < 0.5:
            out[name] = list(items)
        elif rng.random() < 0.5:
            out[name] = None
    if obj.container is not None or rng.random() < 0.5:
        out["container"] = obj.container
    return out


def quirky(units: list[Unit], rng: random.Random, extra: bool = True) -> tuple[list[dict], list[Unit]]:
    """``units`` in the unit-list form with every quirk: motion as string or object, null or
    missing fields, a unit repeated, a unit with a key missing (skipped); and the units a
    reader keeps, in the order it keeps them (first occurrences)."""
    tagged: list[tuple[dict, Unit | None]] = []
    for u in units:
        motion = {"label": u.motion} if rng.random() < 0.3 else u.motion
        entry = {
            "input_nodes": [node_json(o, rng) for o in u.inputs],
            "motion_node": motion,
            "output_nodes": [node_json(o, rng) for o in u.outputs],
        }
        tagged.append((entry, u))
    if extra and tagged:
        tagged.insert(rng.randrange(len(tagged) + 1), tagged[rng.randrange(len(tagged))])
        skipped = {"input_nodes": tagged[0][0]["input_nodes"], "motion_node": "x"}
        tagged.insert(rng.randrange(len(tagged) + 1), (skipped, None))
    kept = list({u.key(): u for _, u in tagged if u is not None}.values())
    return [e for e, _ in tagged], kept


def obj(label, *states):
    return FoonObject.make(label, states)


# ------------------------------------------------------------ reading everywhere, writing back


def test_merge_reads_unit_lists_and_writes_every_format(tmp_path):
    out = tmp_path / "mini.json"
    res = run("merge", *SMOOTHIES, "-o", out, "--format", "units-json")
    assert res.exit_code == 0, res.stderr
    warnings = [line for line in res.stderr.splitlines() if "warning" in line]
    # one line each, naming the file and the unit
    assert len(warnings) == 2 and all("smoothie-3.json" in w for w in warnings)
    assert "unit 6 cannot be used" in warnings[0] and "unit 3 repeats unit 2" in warnings[1]
    expected = read_foons(SMOOTHIES)
    merged = read_foon(out)
    units, extra = merged.units, merged.warnings
    assert extra == [] and [u.key() for u in units] == [u.key() for u in expected.units]
    # the other formats read back to the same units
    for fmt in ("foon", "foon-plain", "foon-json"):
        other = tmp_path / f"mini.{fmt}"
        assert run("merge", out, "-o", other, "--format", fmt).exit_code == 0
        assert {u.key() for u in read_foons([other]).units} == {u.key() for u in expected.units}
    res = run("merge", *SMOOTHIES, "-o", out, "--strict")
    one_line_error(res, "smoothie-3.json", "unit 6 cannot be used: no 'output_nodes'")


@pytest.mark.parametrize("seed", range(3))
def test_units_json_round_trip_through_solve_and_check(seed, tmp_path):
    """solve --format units-json writes trees that --foon, check and the library read back as the same units."""
    problem = random_foon(seed, 12)
    kb_dir = tmp_path / "data"
    kb_dir.mkdir()
    (kb_dir / "FOON.json").write_text(json.dumps(quirky(problem.units, random.Random(seed), extra=False)[0]))
    (kb_dir / "kitchen.json").write_text(json.dumps([o.to_json() for o in problem.kitchen_items]))
    kb = foon2asp.load(foon=kb_dir / "FOON.json")
    assert [u.key() for u in kb.problem.units] == [u.key() for u in problem.units]
    goals = [o for o in problem.objects if o.label.startswith("o") and problem.foon.object_ids[o] in problem.derivable]
    assert goals
    texts = [str(g) for g in goals]
    args = ["solve", "--foon", kb_dir / "FOON.json"] + [a for t in texts for a in ("--goal", t)]
    res = run(*args, "--format", "units-json")
    assert res.exit_code == 0, res.stderr
    trees = json.loads(res.stdout)
    trees = trees if len(goals) > 1 else [trees]
    assert len(trees) == len(goals)
    for goal, entries, tree in zip(goals, trees, kb.solve(goals)):
        path = tmp_path / "tree.json"
        path.write_text(json.dumps(entries))
        units = read_foon(path).units
        assert units == tree.units
        report = kb.check(path, str(goal), optimum=False)
        assert report.valid
    # the list of trees is read as several trees
    both = tmp_path / "trees.json"
    both.write_text(res.stdout)
    checked = run("check", both, "--foon", kb_dir / "FOON.json", *[a for t in texts for a in ("--goal", t)][:2])
    assert checked.stdout.count("Tree: ") == (len(goals) if len(goals) > 1 else 1)


def test_draw_reads_unit_lists(tmp_path):
    out = tmp_path / "t.dot"
    res = run("draw", SMOOTHIES[0], "-o", out)
    assert res.exit_code == 0, res.stderr
    text = out.read_text()
    assert text.count("shape=box") == 7 and "smoothie" in text
    res = run("draw", SMOOTHIES[2], "-o", out)
    assert res.exit_code == 0 and out.read_text().count("shape=box") == 7
    warnings = res.stderr.strip().splitlines()[:-1]
    assert len(warnings) == 2 and all(w.startswith("foon2asp: warning: ") and "smoothie-3.json" in w for w in warnings)
    one_line_error(run("draw", SMOOTHIES[2], "-o", out, "--strict"), "smoothie-3.json", "unit 6")


# ------------------------------------------------------------ --kitchen leaves


def test_kitchen_leaves_on_the_demo_data():
    demo = foon2asp.load("demo")
    leaves = foon2asp.load("demo", kitchen="leaves")
    units = demo.problem.units
    made = {o for u in units for o in u.outputs if not o.is_bare() and o not in u.inputs}
    assert set(leaves.problem.kitchen_items) == {o for u in units for o in u.inputs} - made
    cli = run("solve", "--data", "demo", "--kitchen", "leaves", "--goals", "all", "--format", "json")
    assert cli.exit_code in (0, 1), cli.stderr
    records = json.loads(cli.stdout)
    trees = leaves.solve("all")
    assert [r["status"] for r in records] == [t.status for t in trees]
    for r, t in zip(records, trees):
        assert r["cost"] == t.cost
        if t.has_tree:
            assert validate(leaves.problem, t.goal_id, t.unit_ids).valid
    # every goal the demo kitchen lets one make, the leaves let one make too
    for g in demo.goal_ids("all"):
        if g in demo.problem.derivable:
            assert leaves.object_id(demo.problem.objects[g]) in leaves.problem.derivable


def test_kitchen_leaves_on_merged_foon_111_files(shared_111_dir):
    paths = sorted(shared_111_dir.glob("*.txt"))[3:6]
    kb = foon2asp.load(foon=paths, kitchen="leaves")
    units = kb.problem.units
    made = {o for u in units for o in u.outputs if not o.is_bare() and o not in u.inputs}
    assert set(kb.problem.kitchen_items) == {o for u in units for o in u.inputs} - made
    for path in paths:
        last = read_foons([path]).units[-1]
        dish = next(o for o in last.outputs if not o.is_bare())
        tree = kb.solve(dish)
        assert tree.status == "optimal", path.name
        assert validate(kb.problem, tree.goal_id, tree.unit_ids).valid
        foons = [a for p in paths for a in ("--foon", p)]
        res = run("solve", *foons, "--kitchen", "leaves", "--goal", str(dish), "--format", "json")
        assert res.exit_code == 0, res.stderr
        assert json.loads(res.stdout)[0]["cost"] == tree.cost


def test_without_a_kitchen_the_error_proposes_leaves(tmp_path):
    foon = tmp_path / "mini.json"
    foon.write_text((LLM / "smoothie-1.json").read_text())
    one_line_error(run("solve", "--foon", foon, "--goal", GLASS), "--kitchen leaves", "kitchen.json")
    with pytest.raises(foon2asp.InputError, match="kitchen='leaves'"):
        foon2asp.load(foon=foon)
    assert foon2asp.load(foon=foon, kitchen="leaves").solve(GLASS).status == "optimal"


def test_objects_takes_a_kitchen_file_or_leaves(tmp_path):
    foon = tmp_path / "mini.json"
    foon.write_text((LLM / "smoothie-1.json").read_text())
    one_line_error(run("objects", "--foon", foon, "--derivable"), "--kitchen-file leaves", "kitchen.json")
    res = run("objects", "--foon", foon, "--derivable", "--kitchen-file", "leaves", "--format", "json")
    assert res.exit_code == 0, res.stderr
    kb = foon2asp.load(foon=foon, kitchen="leaves")
    assert {o["id"] for o in json.loads(res.stdout)} == set(kb.problem.derivable)
    kitchen = json.loads(
        run("objects", "--foon", foon, "--kitchen", "--kitchen-file", "leaves", "--format", "json").stdout
    )
    assert len(kitchen) == len(kb.problem.kitchen_items) > 0


# ------------------------------------------------------------ check on its own


def random_tree(rng: random.Random) -> list[Unit]:
    """A random generated tree: a chain towards a dish with side inputs, sometimes out of
    order, with a cycle, or with a missing step."""
    n = rng.randint(2, 6)
    mids = [obj(f"m{i}", "done") for i in range(n)]
    units = []
    for i in range(n):
        ins = [obj(f"k{rng.randrange(4)}", "raw")] + ([mids[i - 1]] if i else [])
        if rng.random() < 0.2 and i + 1 < n:
            ins.append(mids[i + 1])  # needs what a later unit makes: out of order, or a cycle
        if rng.random() < 0.15:
            ins.append(obj("tool"))  # a bare input: a leaf
        units.append(Unit(rng.choice(["chop", "pour", "mix"]), tuple(dict.fromkeys(ins)), (mids[i], obj("tool"))))
    if rng.random() < 0.3:
        rng.shuffle(units)
    if rng.random() < 0.2 and len(units) > 2:
        del units[rng.randrange(len(units) - 1)]
    return list({u.key(): u for u in units}.values())


def leaves_of(units: list[Unit]) -> list[FoonObject]:
    made = {o for u in units for o in u.outputs if not o.is_bare() and o not in u.inputs}
    return list(dict.fromkeys(o for u in units for o in u.inputs if o not in made))


def test_check_verdicts_equal_the_validator(tmp_path):
    rng = random.Random(5)
    paths, trees = [], []
    for k in range(40):
        entries, units = quirky(random_tree(rng), rng)
        path = tmp_path / f"t{k}.json"
        path.write_text(json.dumps(entries, indent=rng.choice([None, 1])))
        paths.append(path)
        trees.append(units)
    res = run("check", *paths, "--format", "json")
    reports = json.loads(res.stdout)
    assert len(reports) == len(paths)
    seen = set()
    for path, units, rep in zip(paths, trees, reports):
        foon = Foon()
        for u in units:
            foon.add_unit(u)
        problem = Problem(foon, leaves_of(units))
        last = [o for o in units[-1].outputs if not o.is_bare()]
        goals = [problem.foon.object_ids[o] for o in last]
        ids = list(range(len(units)))
        in_order = all(check_order(problem, g, ids) is None for g in goals)
        as_set = all(validate(problem, g, ids).valid for g in goals)
        assert rep["tree"] == str(path) and rep["valid"] == in_order, (path.name, rep["message"])
        assert rep["valid_as_set"] == as_set
        assert (rep["problem"] is None) == in_order and (rep["message"] is None) == in_order
        assert set(rep) >= {"valid", "problem", "message", "cycle"}
        if rep["problem"] == "cycle":
            assert len(rep["cycle"]) >= 1 and not as_set
        if rep["problem"] == "order":
            # the first unit that cannot fire waits for what a later unit makes
            assert as_set and rep["blocked"]["made_by"] > rep["blocked"]["step"]
        seen.add(rep["problem"])
    # (an object no unit makes is a leaf: with the leaves as kitchen no input is ever missing)
    assert {None, "order", "cycle"} <= seen and "missing-input" not in seen
    assert res.exit_code == (0 if all(r["valid"] for r in reports) else 1) == 1
    # one report per file, text too; warnings name the file and the unit
    text = run("check", *paths[:3])
    assert text.stdout.count("Tree: ") == 3
    assert all(("t0.json" in w or "t1.json" in w or "t2.json" in w) and "unit" in w for w in text.stderr.splitlines())


def test_check_on_its_own_with_a_goal_a_kitchen_and_the_library(tmp_path):
    res = run("check", SMOOTHIES[1], "--format", "json")
    assert res.exit_code == 1
    (rep,) = json.loads(res.stdout)
    assert rep["problem"] == "order" and rep["blocked"]["step"] == 3 and rep["blocked"]["made_by"] == 4
    assert rep["blocked"]["waits_for"] == FoonObject.make("blender", (), ["banana"]).to_json()
    text = run("check", SMOOTHIES[1]).stdout
    assert "step 3 (add) cannot fire in the order given" in text and "Verdict: INVALID" in text
    # the library says the same
    (verdict,) = foon2asp.check_tree(SMOOTHIES[1])
    assert verdict.to_dict() == rep and not verdict.valid and verdict.valid_as_set
    # another goal, by label or text
    (v,) = foon2asp.check_tree(SMOOTHIES[0], "banana, sliced")
    assert v.valid and v.goals == [obj("banana", "sliced")]
    one_line_error(run("check", SMOOTHIES[0], "--goal", "smoothie"), "smoothie", "2 objects")
    one_line_error(run("check", SMOOTHIES[0], "--goal", "pizza"), "no object of the tree is labelled 'pizza'")
    # a kitchen file instead of the leaves
    kitchen = tmp_path / "kitchen.json"
    kitchen.write_text(json.dumps([obj("banana", "whole").to_json()]))
    res = run("check", SMOOTHIES[0], "--kitchen", kitchen, "--format", "json")
    (rep,) = json.loads(res.stdout)
    assert res.exit_code == 1 and rep["problem"] == "missing-input" and rep["kitchen_source"] == str(kitchen)
    # strict: a skipped unit is an error
    one_line_error(run("check", SMOOTHIES[2], "--strict"), "smoothie-3.json", "unit 6")
    one_line_error(run("check", SMOOTHIES[0], "--goals", "all"), "--goals needs a FOON")
    one_line_error(run("check", tmp_path / "nope.json"), "nope.json")


def test_check_several_files_against_a_foon(tmp_path):
    mini = tmp_path / "mini.json"
    assert run("merge", *SMOOTHIES, "-o", mini, "--format", "units-json").exit_code == 0
    res = run("check", *SMOOTHIES, "--foon", mini, "--kitchen", "leaves", "--goal", GLASS, "--format", "json")
    reports = json.loads(res.stdout)
    assert [r["tree"] for r in reports] == [str(p) for p in SMOOTHIES]
    # against the FOON the set is judged: every candidate is valid there
    assert all(r["valid"] for r in reports) and res.exit_code == 0
    assert len({r["optimum"]["cost"]["units"] for r in reports}) == 1


# ------------------------------------------------------------ motion costs


TABLE = {"m1": "0.9", "m2": "0.15", "m4": "0"}  # m3 is not listed: it costs 1


def write_data(tmp_path, problem) -> Path:
    d = tmp_path / "rand"
    d.mkdir(exist_ok=True)
    (d / "FOON.json").write_text(json.dumps(quirky(problem.units, random.Random(0), extra=False)[0]))
    (d / "kitchen.json").write_text(json.dumps([o.to_json() for o in problem.kitchen_items]))
    (d / "costs.tsv").write_text("".join(f"{m}\t{c}\n" for m, c in TABLE.items()))
    return d


def exact_cost(problem, units) -> Decimal:
    return sum((Decimal(TABLE.get(problem.units[u].motion, "1")) for u in units), Decimal(0))


@pytest.mark.parametrize("seed", range(6))
def test_objective_cost_equals_brute_force_through_the_library_and_the_cli(seed, tmp_path):
    problem = random_foon(seed)
    d = write_data(tmp_path, problem)
    kb = foon2asp.load(foon=d / "FOON.json")
    assert [u.key() for u in kb.problem.units] == [u.key() for u in problem.units]
    goals = [g for g, o in enumerate(problem.objects) if o.label.startswith("o")]
    for objective in ("cost", "cost,units", "units,cost", "inputs,cost"):
        trees = kb.solve([str(problem.objects[g]) for g in goals], objective=objective, motion_cost=d / "costs.tsv")
        names = objective.split(",") + ([] if "units" in objective else ["units"])
        for g, tree in zip(goals, trees):
            valid = brute_force(problem, g)
            if not valid:
                assert tree.status == "unreachable"
                continue

            def key(units):
                parts = {"cost": exact_cost(problem, units), "units": len(units)}
                parts["inputs"] = sum(len(problem.inputs[u]) for u in units)
                return tuple(parts[n] for n in names)

            assert tree.status == "optimal"
            ids = [problem.foon.units.index(u) for u in tree.units]
            assert validate(problem, g, ids).valid
            assert key(ids) == min(key(t) for t in valid), (seed, objective)
            # the reported cost is the exact decimal sum
            assert Decimal(str(tree.cost["cost"])) == exact_cost(problem, ids)
    # the command line prints the same trees and costs, and one warning names the unlisted motions
    texts = [str(problem.objects[g]) for g in goals]
    goal_args = [a for t in texts for a in ("--goal", t)]
    res = run(
        "solve",
        "--foon",
        d / "FOON.json",
        *goal_args,
        "--objective",
        "cost,units",
        "--motion-cost",
        d / "costs.tsv",
        "--format",
        "json",
    )
    assert res.exit_code == 0, res.stderr
    lib = kb.solve(texts, objective="cost,units", motion_cost=d / "costs.tsv")
    assert [r["cost"] for r in json.loads(res.stdout)] == [t.cost for t in lib]
    missing = [line for line in res.stderr.splitlines() if "not in the motion-cost table" in line]
    motions = {u.motion for u in problem.units}
    assert len(missing) == (1 if "m3" in motions else 0)
    if missing:
        assert "m3" in missing[0] and "costs.tsv" in missing[0]


def test_cost_is_reported_everywhere_a_table_is_given(tmp_path):
    costs = LLM / "motion-costs.json"
    res = run("solve", "--data", "demo", "--goal", "tomato salad", "--motion-cost", costs)
    assert res.exit_code == 0 and ", cost " in res.stdout.splitlines()[1]
    kb = foon2asp.load("demo")
    tree = kb.solve("tomato salad", motion_cost=costs)
    table = json.loads(costs.read_text())
    assert Decimal(str(tree.cost["cost"])) == sum(Decimal(str(table.get(u.motion, 1))) for u in tree.units)
    assert "cost" not in kb.solve("tomato salad").cost  # no table, no cost
    res = run("compare", "--data", "demo", "--goal", "tomato salad", "--motion-cost", costs, "--format", "json")
    records = json.loads(res.stdout)
    assert records and all("cost" in t["cost"] for t in records if t["units"])
    assert "/ cost " in run("compare", "--data", "demo", "--goal", "tomato salad", "--motion-cost", costs).stdout
    res = run("missing", "--data", "demo", "--goal", "tomato salad", "--objective", "cost", "--motion-cost", costs)
    assert res.exit_code == 0 and "cost" in res.stdout
    # check reports the cost of the tree and of the optimum with a table
    tree_file = tmp_path / "tree.json"
    tree_file.write_text(tree.render("json"))
    (checked,) = kb.check_all(tree_file, motion_cost=costs)
    assert checked.cost["cost"] == tree.cost["cost"] == checked.optimum.cost["cost"]
    # a mapping in the library is a table too
    assert kb.solve("tomato salad", objective="cost", motion_cost={"cut": 0.25}).status == "optimal"


def test_motion_cost_errors_are_one_line(tmp_path):
    bad = tmp_path / "bad.json"
    for text, words in (
        ('{"chop": -1}', "negative"),
        ('{"chop": "cheap"}', "must be a number"),
        ("chop\tNaN\n", "not a finite number"),
        ("chop\t0.125\n", "finer than 0.01"),
    ):
        bad.write_text(text)
        one_line_error(run("solve", "--data", "demo", "--goal", "tomato salad", "--motion-cost", bad), str(bad))
        one_line_error(run("solve", "--data", "demo", "--goal", "tomato salad", "--motion-cost", bad), words)
    one_line_error(
        run("solve", "--data", "demo", "--goal", "tomato salad", "--objective", "cost"),
        "--objective cost needs --motion-cost",
    )
    with pytest.raises(foon2asp.InputError, match="motion_cost=FILE"):
        foon2asp.load("demo").solve("tomato salad", objective="cost")
    costs = LLM / "motion-costs.json"
    res = run(
        "export",
        "pddl",
        "--data",
        "demo",
        "--goal",
        "tomato salad",
        "--objective",
        "cost",
        "-o",
        tmp_path / "p",
        "--motion-cost",
        costs,
    )
    assert res.exit_code == 0, res.stderr
    assert ":action-costs" in (tmp_path / "p" / "domain.pddl").read_text()
