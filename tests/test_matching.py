"""Hierarchy levels, normalisation and synonyms (foon2asp.foon.matching).

The levels are checked against an independent reference: the FOON *text*
rewritten at the level (state lines dropped as the level says, every object
given one marker state so that no object is bare, the marker left off the
outputs that are not products), parsed and solved at level 3 with the
unchanged code, goal by goal, on ../shared/foon and on merged foon-111 files.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.loaders import Dataset
from foon2asp.foon.matching import LevelUnit, Projection, Texts, key_last, noun_key, parse_synonyms, project_dataset
from foon2asp.foon.model import FoonObject
from foon2asp.foon.parser import parse_lines, read_foons
from foon2asp.foon.problem import Problem
from foon2asp.methods.runner import solve_goals as run_goals
from foon2asp.tree.validate import validate


def solve_goals(problem, goals, method="asp", options=None, **kw):
    """The goal runner's trees for ``goals`` (default: the units objective)."""
    return run_goals(problem, goals, method, options or AspOptions(), **kw)


EXAMPLE = Path(__file__).resolve().parent.parent / "data" / "matching"

#: the state every object of a rewritten FOON holds (no real FOON state is spelled so)
MARK = "zz-at-level"


# --- the reference: FOON text rewritten at a level ------------------------------------------


def _fields(line: str) -> list[str]:
    return [" ".join(f.split()).lower() for f in line.split("\t")[1:]]


def _blocks(text: str) -> list[tuple[list[tuple[str, list[str]]], str, list[tuple[str, list[str]]]]]:
    """Units of FOON text (either dialect) as (inputs, motion line, outputs); an object is
    its O line and its S lines, verbatim."""
    units = []
    ins: list[tuple[str, list[str]]] = []
    outs: list[tuple[str, list[str]]] = []
    motion = None
    for raw in text.splitlines():
        line = raw.rstrip("\r")
        if not line.strip() or line.startswith("#"):
            continue
        if line.startswith("//"):
            if motion is not None:
                units.append((ins, motion, outs))
            ins, outs, motion = [], [], None
        elif line[0] == "O":
            (outs if motion is not None else ins).append((line, []))
        elif line[0] == "S":
            (outs if motion is not None else ins)[-1][1].append(line)
        elif line[0] == "M":
            motion = line
    if motion is not None:
        units.append((ins, motion, outs))
    return units


def _kept(states: list[str], level: int) -> list[str]:
    if level == 1:
        return []
    if level == 2:
        return [s for s in states if _fields(s)[0] not in ("contains", "ingredients")]
    return states


def _key(o_line: str, states: list[str]) -> tuple:
    return (_fields(o_line)[0], frozenset(" ".join(_fields(s)) for s in states))


def rewrite_foon(text: str, level: int) -> str:
    """FOON text at ``level``: the state lines the level ignores dropped, the marker state on
    every input and on every output that is a product at the level (not bare in the FOON,
    not equal at the level to an input of its unit)."""
    out = ["//"]
    for ins, motion, outs in _blocks(text):
        keys = {_key(o, _kept(s, level)) for o, s in ins}
        for o, states in ins:
            out += [o, *_kept(states, level), f"S\t{MARK}"]
        out.append(motion)
        for o, states in outs:
            kept = _kept(states, level)
            made = bool(states) and (level == 3 or _key(o, kept) not in keys)
            out += [o, *kept] + ([f"S\t{MARK}"] if made else [])
        out.append("//")
    return "\n".join(out) + "\n"


def rewrite_object(obj: FoonObject, level: int) -> FoonObject:
    """An object of a kitchen or goals file at ``level``, with the marker state."""
    states = list(obj.states) if level >= 2 else []
    return FoonObject.make(
        obj.label, [*states, MARK], obj.ingredients if level == 3 else (), obj.container if level >= 2 else None
    )


def optimum(problem: Problem, goals: list[FoonObject]) -> list[int | None]:
    """The fewest units of a tree for each goal (None: no tree), by the unchanged solver."""
    ids = [problem.foon.object_ids.get(g) for g in goals]
    known = [g for g in ids if g is not None]
    trees = {t.goal: t for t in solve_goals(problem, known, options=AspOptions())}
    out: list[int | None] = []
    for g in ids:
        tree = trees.get(g) if g is not None else None
        if tree is not None and tree.has_tree:
            assert tree.status == "optimal"
            assert validate(problem, g, tree.units).valid
            out.append(len(tree.units))
        else:
            out.append(None)
    return out


def compare_with_reference(text: str, data: Dataset, level: int) -> list[int | None]:
    """Optimum per goal of the projection at ``level`` and of the rewritten FOON: equal."""
    projected, _ = project_dataset(data, level)
    mine = optimum(Problem.from_dataset(projected), [g for g, _ in projected.goals])
    ref_foon = parse_lines(rewrite_foon(text, level), "rewritten")
    ref_kitchen = [rewrite_object(o, level) for o in data.kitchen]
    reference = Problem(ref_foon, ref_kitchen, data.motion, data.utensils)
    theirs = optimum(reference, [rewrite_object(g, level) for g, _ in data.goals])
    assert mine == theirs
    return mine


@pytest.mark.parametrize("level", [1, 2])
def test_levels_match_the_rewritten_universal_foon(shared_foon_dir, level):
    data = Dataset.load(shared_foon_dir)
    text = (shared_foon_dir / "FOON.txt").read_text(encoding="utf-8")
    got = compare_with_reference(text, data, level)
    assert len(got) == 25
    # level 3 finds no tree for two goals; the lower levels find trees for more of them
    assert sum(x is not None for x in got) >= 23


def _recipes(shared_111_dir: Path, count: int = 12) -> list[Path]:
    garlic = [p for p in sorted(shared_111_dir.glob("*.txt")) if "garlic" in p.name or "bread" in p.name]
    return garlic[:count]


@pytest.mark.parametrize("level", [1, 2])
def test_levels_match_the_rewritten_merged_recipes(shared_111_dir, shared_foon_dir, level):
    files = _recipes(shared_111_dir)
    assert len(files) >= 6
    foon = read_foons(files)
    made = {o for u in foon.units for o in u.outputs}
    used = {o for u in foon.units for o in u.inputs}
    everything = list(dict.fromkeys(o for u in foon.units for o in (*u.inputs, *u.outputs)))
    kitchen = [o for o in everything if o not in made]
    goals = [(o, 0) for o in everything if o in made and o not in used and not o.is_bare()]
    base = Dataset.load(shared_foon_dir)
    data = Dataset(foon, kitchen, goals, base.motion, base.utensils)
    text = "".join(f.read_text(encoding="utf-8") + "\n//\n" for f in files)
    got = compare_with_reference(text, data, level)
    assert len(got) == len(goals) and any(x is not None for x in got)


# --- the projection itself -----------------------------------------------------------------


def test_level_3_is_the_identity(shared_foon_dir):
    data = Dataset.load(shared_foon_dir)
    projected, projection = project_dataset(data, 3)
    assert projected is data and projection.identity
    assert projection.object(data.kitchen[0]) is data.kitchen[0]


def test_level_3_normalised_keeps_the_problem_when_nothing_is_joined():
    data = Dataset.load(EXAMPLE)
    projected, projection = project_dataset(data, 3, normalize=True)
    assert not projection.identity and not projection.texts_joined and projected.foon is not data.foon
    before, after = Problem.from_dataset(data), Problem.from_dataset(projected)
    assert [str(u) for u in after.units] == [str(u) for u in before.units]
    assert after.objects == before.objects
    assert (after.products, after.required, after.kitchen) == (before.products, before.required, before.kitchen)


def _unit_text(motion: str, ins: list[str], outs: list[str]) -> str:
    return "\n".join([*ins, f"M\t{motion}", *outs, "//"]) + "\n"


def test_level_1_merges_units_passes_outputs_through_and_keeps_bare_outputs_unmade():
    text = (
        "//\n"
        + _unit_text("chop", ["O\tonion\nS\twhole", "O\tknife"], ["O\tonion\nS\tchopped", "O\tknife"])
        + _unit_text("chop", ["O\tonion\nS\tpeeled", "O\tknife"], ["O\tonion\nS\tdiced", "O\tknife"])
        + _unit_text("fry", ["O\tonion\nS\tchopped", "O\tpan"], ["O\tfried onion\nS\tgolden", "O\tpan\nS\tdirty"])
    )
    foon = parse_lines(text)
    projection = Projection(1)
    level1 = projection.foon(foon)
    assert len(level1.units) == 2  # the two chops are one unit at level 1
    chop, fry = level1.units
    assert isinstance(chop, LevelUnit) and chop.made == frozenset()  # onion -> onion passes through
    assert fry.made == {FoonObject("fried onion")}  # the pan passes through (pan -> dirty pan)
    problem = Problem(level1, [FoonObject("onion"), FoonObject("knife"), FoonObject("pan")])
    fried = level1.object_ids[FoonObject("fried onion")]
    assert problem.producers == {fried: [1]}
    assert projection.sources[FoonObject("onion")] == [
        "onion, whole",
        "onion, chopped",
        "onion, peeled",
        "onion, diced",
    ]
    assert len(projection.sources[FoonObject("knife")]) == 1
    # the bare knife output is no product at level 3 either, and stays none at level 1
    assert all(FoonObject("knife") not in u.made for u in level1.units if isinstance(u, LevelUnit))


def test_level_2_keeps_states_and_container_drops_ingredients():
    obj = FoonObject.make("bowl", ["mixed", "on [table]"], ["flour", "egg"], "counter")
    assert Projection(2).object(obj) == FoonObject.make("bowl", ["mixed", "on [table]"], (), "counter")
    assert Projection(1).object(obj) == FoonObject("bowl")
    with pytest.raises(InputError, match="--level"):
        Projection(4)


def test_worked_example_level_2_finds_a_tree_level_3_cannot():
    data = Dataset.load(EXAMPLE)
    goal = data.goals[0][0]
    trees = {}
    for level in (3, 2):
        projected, projection = project_dataset(data, level)
        problem = Problem.from_dataset(projected)
        g = problem.foon.object_ids[projection.object(goal)]
        [tree] = solve_goals(problem, [g])
        trees[level] = tree
        if tree.has_tree:
            assert validate(problem, g, tree.units).valid
            motions = [problem.units[u].motion for u in tree.units]
    assert trees[3].status == "unreachable"
    assert trees[2].status == "optimal" and len(trees[2].units) == 4
    assert sorted(motions) == ["chop", "chop", "shake", "toss"] and motions[-1] == "toss"


# --- normalisation and synonyms ------------------------------------------------------------


def test_singular_of_the_last_word():
    for plural, one in (("blueberries", "blueberry"), ("tomatoes", "tomato"), ("leaves", "leaf"), ("knives", "knife")):
        assert noun_key(plural) == noun_key(one) == one
    assert noun_key("smoothies") == noun_key("smoothie")  # inflect's singular is "smoothy"
    for mass in ("rice", "glass", "swiss cheese", "cheese", "lettuce", "milk", "flour", "fish"):
        assert key_last(mass) == mass
    assert key_last("fresh blueberries") == "fresh blueberry" == key_last("Fresh blueberry".lower())
    assert key_last("") == "" and noun_key("{a,b}") == "{a,b}" and noun_key("7up") == "7up"


SMOOTHIE = """//
O\tblueberries
S\twhole
O\tcolander
M\twash
O\tBlueberries
S\twashed
O\tcolander
//
O\tmilk
S\tin\t[carton]
O\tfridge
M\tchill
O\tliquidmilk
S\tcold
//
O\tblueberry
S\twashed
O\tMilk
S\tcold
O\tblender
M\tblend
O\tsmoothie
S\tblended
S\tin\t[blenders]
//
"""


def _smoothie(tmp_path: Path, normalize: bool, synonyms: str | None) -> tuple[str, Projection]:
    (tmp_path / "FOON.txt").write_text(SMOOTHIE, encoding="utf-8")
    kitchen = [
        {"label": "blueberries", "states": ["whole"]},
        {"label": "colander"},
        {"label": "milk", "states": [], "container": "carton"},
        {"label": "fridge"},
        {"label": "blender "},
    ]
    (tmp_path / "kitchen.json").write_text(json.dumps(kitchen), encoding="utf-8")
    goal = [{"label": "smoothies", "states": ["blended"], "container": "blender"}]
    (tmp_path / "goal_nodes.json").write_text(json.dumps(goal), encoding="utf-8")
    data = Dataset.load(tmp_path)
    table = parse_synonyms(synonyms, "syn.txt", normalize) if synonyms else None
    projected, projection = project_dataset(data, 3, normalize, table)
    problem = Problem.from_dataset(projected)
    g = problem.foon.object_ids.get(projected.goals[0][0])
    if g is None:
        return "not an object", projection
    [tree] = solve_goals(problem, [g])
    if tree.has_tree:
        assert validate(problem, g, tree.units).valid
    return f"{tree.status} {len(tree.units)}" if tree.has_tree else tree.status, projection


def test_normalisation_and_synonyms_connect_units(tmp_path):
    assert _smoothie(tmp_path, False, None)[0] == "not an object"  # "smoothies" is no FOON object
    assert _smoothie(tmp_path, True, None)[0] == "unreachable"  # blueberries connect, the milk does not
    status, projection = _smoothie(tmp_path, True, "# spellings of milk\nliquidmilk = milk\n")
    assert status == "optimal 3"
    assert projection.texts_joined["blueberries"] == ["blueberries", "blueberry"]
    assert projection.texts_joined["milk"] == ["milk", "liquidmilk"]
    assert projection.texts_joined["smoothie"] == ["smoothie", "smoothies"]
    washed = FoonObject("blueberries", ("washed",))
    assert projection.sources[washed] == ["blueberries, washed", "blueberry, washed"]
    # without normalisation only the synonyms join
    status, projection = _smoothie(
        tmp_path, False, "liquidmilk = milk\nblueberry = blueberries\nsmoothies=smoothie\nblender=blenders"
    )
    assert status == "optimal 3"


def test_relation_states_key_their_objects():
    texts = Texts(True, {"tray": "baking sheet"})
    assert texts.state_key("on [plates]") == texts.state_key("on [plate]") == "on [plate]"
    assert texts.state_key("with {trays,cups}") == "with {baking sheet,cup}"
    assert texts.key("Trays ") == "baking sheet"


def test_synonym_chains_and_errors():
    assert parse_synonyms("a = b\nb = c\n# c = d\n\n") == {"a": "c", "b": "c"}
    assert parse_synonyms("Tomatoes = roma tomato", normalize=True) == {"tomato": "roma tomato"}
    for text, where, what in (
        ("a = b\nno equals sign\n", "syn.txt:2", "expected 'name = canonical name'"),
        ("a = b\na = c\n", "syn.txt:2", "already a synonym"),
        ("= b\n", "syn.txt:1", "both sides"),
        ("a = b\nb = a\n", "syn.txt:1", "cycle"),
    ):
        with pytest.raises(InputError) as err:
            parse_synonyms(text, "syn.txt")
        assert str(err.value).startswith(where) and what in str(err.value)


def test_projected_trees_are_valid_at_every_level(demo_problem):
    data, _ = demo_problem
    for level in (1, 2, 3):
        projected, projection = project_dataset(data, level, normalize=True)
        problem = Problem.from_dataset(projected)
        goals = [problem.foon.object_ids[g] for g, _ in projected.goals if g in problem.foon.object_ids]
        for tree in solve_goals(problem, goals):
            if tree.has_tree:
                assert validate(problem, tree.goal, tree.units).valid, (level, tree.goal)


def test_normalize_without_inflect_is_one_clear_error(monkeypatch, tmp_path):
    """inflect is the optional dependency of --normalize: without it the command says what to
    install in one line, and nothing else needs it."""
    import sys

    from click.testing import CliRunner

    from foon2asp.cli.main import main
    from foon2asp.foon import matching

    monkeypatch.setitem(sys.modules, "inflect", None)  # an import of inflect fails
    matching._engine.cache_clear()
    matching.noun_key.cache_clear()
    try:
        res = CliRunner().invoke(main, ["objects", "--data", "demo", "--normalize"])
        assert res.exit_code == 2, res.output
        assert res.output.strip().splitlines() == [
            "foon2asp: error: --normalize needs the inflect package: pip install 'foon2asp[normalize]' (or inflect)"
        ]
        plain = CliRunner().invoke(main, ["objects", "--data", "demo"])
        assert plain.exit_code == 0 and "tomato" in plain.output
    finally:
        matching._engine.cache_clear()
        matching.noun_key.cache_clear()
