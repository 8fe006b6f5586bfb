"""Consolidating candidate trees (foon2asp.consolidate, ``foon2asp consolidate``): the optimum of
the merged candidates against brute force over subsets of the merged units, never worse than
the best candidate executable on its own; each candidate's verdict against the independent
validator; each unit's sources; what to add when the goal is unreachable; the report formats."""

from __future__ import annotations

import itertools
import json
import random
import shutil
from collections import Counter
from decimal import Decimal
from pathlib import Path

import pytest
from click.testing import CliRunner

import foon2asp
from foon2asp.cli.main import main
from foon2asp.foon.model import Foon, FoonObject, Unit
from foon2asp.foon.problem import Problem
from foon2asp.foon.unitlist import read_unit
from foon2asp.tree.tasktree import measures
from foon2asp.tree.validate import check_order, validate
from helpers import brute_force
from test_llm_trees import leaves_of, quirky

REPO = Path(__file__).resolve().parent.parent
LLM = REPO / "data" / "llm"
SMOOTHIES = sorted(LLM.glob("smoothie-*.json"))
KEYS = {"goal", "status", "cost", "units", "candidates", "missing"}
CANDIDATE_KEYS = {"file", "valid", "problem", "cost", "used_units"}
COSTS = {"chop": Decimal("0.6"), "pour": Decimal("0.2"), "mix": Decimal("0.35"), "heat": Decimal("0")}


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def o(label, *states):
    return FoonObject.make(label, states)


def random_recipe(rng: random.Random) -> tuple[list[list[Unit]], FoonObject]:
    """2-4 candidate trees of one dish sharing objects: each picks a producer for the dish and
    for every intermediate it needs among a pool of alternatives; some are written out of
    order, miss a step or hold a superfluous unit."""
    dish = o("dish", "done")
    mids = [o(f"m{i}", "done") for i in range(5)]
    pool: dict[FoonObject, list[Unit]] = {}
    for i, m in enumerate([*mids, dish]):
        earlier = mids[:i] if m != dish else mids
        for _ in range(rng.randint(1, 2)):
            ins = [o(f"k{rng.randrange(4)}", "raw")] + rng.sample(earlier, min(len(earlier), rng.randint(0, 2)))
            unit = Unit(rng.choice(sorted(COSTS)), tuple(dict.fromkeys(ins)), (m, o("pan")))
            pool.setdefault(m, [])
            if all(u.key() != unit.key() for u in pool[m]):
                pool[m].append(unit)
    candidates = []
    for _ in range(rng.randint(2, 4)):
        chosen: dict[FoonObject, Unit] = {}

        def pick(obj: FoonObject) -> None:
            if obj in chosen or obj not in pool:
                return
            chosen[obj] = rng.choice(pool[obj])
            for i in chosen[obj].inputs:
                pick(i)

        pick(dish)
        order = sorted(chosen.values(), key=lambda u: [*mids, dish].index(u.outputs[0]))
        if rng.random() < 0.25:
            rng.shuffle(order)
            order.remove(chosen[dish])
            order.append(chosen[dish])
        if rng.random() < 0.2 and len(order) > 1:
            order.pop(0)  # a missing step: its product becomes a leaf, or another candidate makes it
        if rng.random() < 0.2:
            spare = rng.choice([u for us in pool.values() for u in us])
            if spare.key() not in {u.key() for u in order}:
                order.insert(0, spare)
        candidates.append(order)
    return candidates, dish


def write(tmp_path: Path, candidates: list[list[Unit]], rng: random.Random) -> list[Path]:
    paths = []
    for k, units in enumerate(candidates, 1):
        entries, _ = quirky(units, rng, extra=rng.random() < 0.5)
        path = tmp_path / f"cand-{k}.json"
        path.write_text(json.dumps(entries, indent=1))
        paths.append(path)
    return paths


def file_steps(path: Path) -> list[tuple[int, Unit]]:
    """Each unit a reader keeps with its number in the file (every entry counts), first occurrences."""
    out, seen = [], set()
    for k, entry in enumerate(json.loads(path.read_text()), 1):
        unit, _ = read_unit(entry, str(path), None, k)
        if unit is not None and unit.key() not in seen:
            seen.add(unit.key())
            out.append((k, unit))
    return out


def merged(candidates: list[list[Unit]]) -> Problem:
    """The merged candidates as a problem of their own, the kitchen their leaves (built here, not by foon2asp)."""
    foon = Foon()
    for units in candidates:
        for u in units:
            foon.add_unit(u)
    return Problem(foon, leaves_of(foon.units))


def key(problem: Problem, goal: int, units, objective: tuple[str, ...]):
    m = measures(problem, goal, list(units))
    parts = {
        "units": m["units"],
        "inputs": m["inputs"],
        "depth": m["depth"],
        "cost": sum((COSTS[problem.units[u].motion] for u in units), Decimal(0)),
    }
    names = list(objective) + ([] if "units" in objective else ["units"])
    return tuple(parts[n] for n in names)


OBJECTIVES = [("units",), ("cost",), ("cost", "units"), ("inputs", "cost"), ("depth",)]


@pytest.mark.parametrize("seed", range(12))
def test_optimum_equals_brute_force_and_beats_every_valid_candidate(seed, tmp_path):
    rng = random.Random(seed)
    candidates, dish = random_recipe(rng)
    paths = write(tmp_path, candidates, rng)
    table = tmp_path / "costs.json"
    table.write_text(json.dumps({m: float(c) for m, c in COSTS.items()}))
    problem = merged(candidates)
    g = problem.foon.object_ids[dish]
    valid_sets = brute_force(problem, g)
    for objective in OBJECTIVES:
        found = foon2asp.consolidate(paths, str(dish), objective=",".join(objective), motion_cost=table)
        (result,) = found
        assert result.goal == dish
        if not valid_sets:
            assert result.status == "unreachable"
            continue
        assert result.status == "optimal", (seed, objective)
        ids = [problem.foon.units.index(u) for u in result.units]
        assert validate(problem, g, ids).valid
        best = min(key(problem, g, t, objective) for t in valid_sets)
        assert key(problem, g, ids, objective) == best, (seed, objective)
        assert Decimal(str(result.cost["cost"])) == key(problem, g, ids, ("cost",))[0]
        tree_keys = {u.key() for u in result.units}
        for path, cand in zip(paths, result.candidates):
            assert cand.file == str(path)
            steps = file_steps(path)
            order = [problem.foon.units.index(u) for _, u in steps]
            # the verdict: its own units, in file order, from the merged kitchen (the independent validator)
            assert cand.valid == (check_order(problem, g, order) is None), (seed, path.name, cand.problem)
            assert (cand.problem is None) == cand.valid
            if cand.valid:
                assert validate(problem, g, order).valid
                assert key(problem, g, ids, objective) <= key(problem, g, order, objective)
            assert {k: v for k, v in cand.cost.items() if k != "cost"} == measures(problem, g, order)
            assert Decimal(str(cand.cost["cost"])) == key(problem, g, order, ("cost",))[0]
            # the steps the tree uses: the numbers in its file of its units in the tree
            assert cand.used_units == [k for k, u in steps if u.key() in tree_keys]
        # each unit of the tree names exactly the files holding it
        for unit, sources in zip(result.units, result.sources):
            holders = [str(p) for p, units in zip(paths, candidates) if unit.key() in {u.key() for u in units}]
            assert sources == holders


def test_used_units_are_numbered_as_in_the_file():
    """Steps count every entry of the file, the skipped and repeated ones too (as the warnings do)."""
    (result,) = foon2asp.consolidate(SMOOTHIES)
    tree_keys = {u.key() for u in result.units}
    for path, cand in zip(SMOOTHIES, result.candidates):
        assert cand.used_units == [k for k, u in file_steps(path) if u.key() in tree_keys]
    third = result.candidates[2]
    assert third.used_units[-1] == len(json.loads(SMOOTHIES[2].read_text()))  # the last entry, not the 7th unit


def test_default_goal_is_the_most_shared_last_product(tmp_path):
    rng = random.Random(3)
    a, b = o("dish", "done"), o("dish", "burnt")
    kit = o("k", "raw")
    c1 = [Unit("heat", (kit,), (a,))]
    c2 = [Unit("mix", (kit,), (o("m", "done"),)), Unit("heat", (o("m", "done"),), (a,))]
    c3 = [Unit("heat", (kit, o("oil")), (b,))]
    paths = write(tmp_path, [c1, c2, c3], rng)
    counts = Counter(o for c in (c1, c2, c3) for o in c[-1].outputs if not o.is_bare())
    top = max(counts, key=counts.__getitem__)
    (result,) = foon2asp.consolidate(paths)
    assert result.goal == top == a
    every = foon2asp.consolidate(paths, goals="all")
    assert [r.goal for r in every] == [a, b]
    assert [r.cost["units"] for r in every] == [1, 1]
    # --together: one tree making both
    (meal,) = foon2asp.consolidate(paths, [str(a), str(b)], together=True)
    assert meal.goals == [a, b] and meal.status == "optimal" and len(meal.units) == 2
    assert isinstance(meal.to_dict()["goal"], list)


def test_unreachable_goal_names_the_fewest_objects_to_add(tmp_path):
    """Two candidates that each need what only the other's unit makes from the goal's part: a cycle."""
    x, y, dish = o("x", "done"), o("y", "done"), o("dish", "done")
    c1 = [Unit("mix", (y,), (x,)), Unit("heat", (x,), (dish,))]
    c2 = [Unit("mix", (x,), (y,)), Unit("heat", (y,), (dish,))]
    paths = write(tmp_path, [c1, c2], random.Random(1))
    (result,) = foon2asp.consolidate(paths)
    assert result.status == "unreachable" and result.units == []
    problem = merged([c1, c2])
    g = problem.foon.object_ids[dish]
    # brute force: the fewest objects whose addition to the kitchen makes the dish
    for k in range(len(problem.objects) + 1):
        helps = [
            set(add)
            for add in itertools.combinations(range(len(problem.objects)), k)
            if g in Problem(problem.foon, problem.kitchen_items + [problem.objects[a] for a in add]).derivable
        ]
        if helps:
            break
    assert len(result.missing) == k and {problem.foon.object_ids[m] for m in result.missing} in helps
    assert [c.valid for c in result.candidates] == [False, False]
    # on its own a candidate lacks what only the other makes
    assert all(c.problem.startswith("missing input") for c in result.candidates)
    data = result.to_dict()
    assert set(data) == KEYS and data["missing"] == [m.to_json() for m in result.missing]


def test_constraints_and_the_time_limit_reach_the_solver():
    candidates = [[u for _, u in file_steps(p)] for p in SMOOTHIES]
    problem = merged(candidates)
    g = problem.foon.object_ids[FoonObject.make("smoothie", ["blended"], (), "glass")]
    trees = brute_force(problem, g)
    allowed = [t for t in trees if all(problem.units[u].motion != "break" for u in t)]
    (free,) = foon2asp.consolidate(SMOOTHIES)
    (result,) = foon2asp.consolidate(SMOOTHIES, forbid_motions=["break"], time_limit=30)
    assert free.cost["units"] == min(len(t) for t in trees)
    assert result.status == "optimal" and all(u.motion != "break" for u in result.units)
    assert len(result.units) == min(len(t) for t in allowed) > free.cost["units"]


# ------------------------------------------------------------ the command line


def test_cli_json_has_exactly_the_keys_and_equals_the_library(tmp_path):
    costs = LLM / "motion-costs.json"
    res = run("consolidate", *SMOOTHIES, "--format", "json", "--objective", "cost,units", "--motion-cost", costs)
    assert res.exit_code == 0, res.stderr
    data = json.loads(res.stdout)
    assert isinstance(data, list) and len(data) == 1
    (goal,) = data
    assert set(goal) == KEYS
    assert all(set(c) == CANDIDATE_KEYS for c in goal["candidates"])
    assert all(set(u) == {"motion", "inputs", "outputs", "sources"} for u in goal["units"])
    lib = foon2asp.consolidate(SMOOTHIES, objective="cost,units", motion_cost=costs)
    assert data == lib.to_list()
    # status and cost as solve reports them on the merged FOON with the leaves as kitchen
    mini = tmp_path / "mini.json"
    assert run("merge", *SMOOTHIES, "-o", mini, "--format", "units-json").exit_code == 0
    args = ("--objective", "cost,units", "--motion-cost", costs, "--format", "json")
    solved = run("solve", "--foon", mini, "--kitchen", "leaves", "--goal", "smoothie, blended, in [glass]", *args)
    (record,) = json.loads(solved.stdout)
    assert (goal["status"], goal["cost"]) == (record["status"], record["cost"])
    assert [{k: v for k, v in u.items() if k != "sources"} for u in goal["units"]] == record["units"]
    # the valid candidates are never cheaper
    for c in goal["candidates"]:
        if c["valid"]:
            assert Decimal(str(c["cost"]["cost"])) >= Decimal(str(goal["cost"]["cost"]))


def test_cli_text_html_and_units_json(tmp_path):
    res = run("consolidate", *SMOOTHIES)
    assert res.exit_code == 0
    text = res.stdout
    assert "Candidates" in text and "from: " in text and text.count("INVALID") == 1
    assert "smoothie-2.json" in text and "step 3 (add) cannot fire in the order given" in text
    assert sum("warning" in line for line in res.stderr.splitlines()) == 2
    units = run("consolidate", *SMOOTHIES, "--format", "units-json")
    tree = tmp_path / "best.json"
    tree.write_text(units.stdout)
    assert [v.valid for v in foon2asp.check_tree(tree)] == [True]
    if shutil.which("dot") is None:
        pytest.skip("Graphviz 'dot' is not installed")
    out = tmp_path / "report.html"
    res = run("consolidate", *SMOOTHIES, "--format", "html", "-o", out)
    assert res.exit_code == 0, res.stderr
    page = out.read_text()
    assert page.count("<tr class=") == 4 and page.count("<svg") == 1
    svg = page.split("<svg", 1)[1]
    # the units are filled with the colours of their files: the first file's colour, and stripes of several
    assert "#9fc5e8" in svg and "#f6b26b" in svg


def test_cli_errors_are_one_line(tmp_path):
    for args, words in (
        ((tmp_path / "none.json",), "none.json"),
        ((*SMOOTHIES, "--strict"), "unit 6"),
        ((*SMOOTHIES, "--objective", "cost"), "--motion-cost"),
        ((*SMOOTHIES, "--goal", "pizza"), "pizza"),
    ):
        res = run("consolidate", *args)
        assert res.exit_code == 2, (args, res.output)
        err = res.stderr.strip().splitlines()
        assert err[-1].startswith("foon2asp: error: ") and words in err[-1], err
        assert all(line.startswith("foon2asp: warning: ") for line in err[:-1])
    bad = tmp_path / "bad.json"
    bad.write_text('[{"input_nodes": [{"label": 3}], "motion_node": "peel", "output_nodes": []}]')
    res = run("consolidate", bad)
    assert res.exit_code == 2 and "bad.json" in res.stderr and "unit 1" in res.stderr
