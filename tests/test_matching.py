"""Hierarchy levels, normalisation and synonyms (foon2asp.foon.matching).

The levels are checked against an independent reference: the FOON *text*
rewritten at the level (state lines dropped as the level says, every object
given one marker state so that no object is bare, the marker left off the
outputs that are not products), parsed and solved at level 3 with the
unchanged code, goal by goal, on ../shared/foon and on merged foon-111 files.
"""

from __future__ import annotations

import json
import random
from pathlib import Path

import clingo
import pytest
from click.testing import CliRunner

import foon2asp
from conftest import REPO
from foon2asp import api
from foon2asp.asp.options import AspOptions
from foon2asp.cli.main import main
from foon2asp.errors import InputError
from foon2asp.foon.loaders import Dataset
from foon2asp.foon.matching import LevelUnit, Projection, Texts, key_last, noun_key, parse_synonyms, project_dataset
from foon2asp.foon.model import FoonObject
from foon2asp.foon.parser import parse_lines, read_foons
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import candidates, parse_substitutes
from foon2asp.methods.runner import solve_goals as run_goals
from foon2asp.tree.validate import validate
from test_substitutes import SUBS, _brute_force, _random_problem


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


# Looser matching on every command and in the library: --level, --normalize, --synonyms,
# --substitutes and --max-substitutions (the options of foon2asp.cli.flags, the keywords of
# foon2asp.api.load and foon2asp.api.Options).
#
# Levels are checked against the FOON text rewritten at the level (tests/test_matching.py's
# reference), substitutes against the brute force of tests/test_substitutes.py, both through the
# command line; normalisation and synonyms on files written here with mixed spellings.


ONION = REPO / "data" / "matching" / "onion"
SMOOTHIE_DIR = REPO / "data" / "matching" / "smoothie"
SALAD = REPO / "data" / "matching"
FLAGS = ("--level", "--normalize", "--synonyms", "--substitutes", "--max-substitutions")


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def ok(*args):
    result = run(*args)
    assert result.exit_code == 0, result.output + repr(result.exception)
    return result


def one_line_error(result, *words):
    assert result.exit_code == 2, result.output
    # warnings about the data (the matching folders have no motion.txt) may come first
    lines = [line for line in result.stderr.strip().splitlines() if not line.startswith("foon2asp: warning: ")]
    err = "\n".join(lines)
    assert len(lines) == 1 and err.startswith("foon2asp: error: "), err
    for word in words:
        assert word in err, (word, err)


def key(obj: dict) -> str:
    return json.dumps(obj, sort_keys=True)


# --- every command takes the flags ---------------------------------------------------------


def _leaf_commands(group, prefix=()):
    for name, command in sorted(group.commands.items()):
        if hasattr(command, "commands"):
            yield from _leaf_commands(command, (*prefix, name))
        else:
            yield (*prefix, name), command


#: commands that read no FOON
NO_FOON = {("methods",)}


def test_every_command_that_reads_a_foon_lists_the_flags():
    commands = [(path, c) for path, c in _leaf_commands(main) if path not in NO_FOON]
    assert {p[0] for p, _ in commands} >= {
        "solve", "compare", "batch", "check", "missing", "reachable", "objects",
        "merge", "draw", "consolidate", "export", "facts", "query",
    }  # fmt: skip
    for path, command in commands:
        names = {opt for p in command.params for opt in getattr(p, "opts", ())}
        assert set(FLAGS) <= names, (path, set(FLAGS) - names)
        level = next(p for p in command.params if "--level" in p.opts)
        assert level.default == 3, path


@pytest.fixture(scope="module")
def onion_tree(tmp_path_factory) -> Path:
    """The onion example's optimal tree with substitutes, as FOON text."""
    path = tmp_path_factory.mktemp("onion") / "tree.txt"
    result = ok("solve", "--data", ONION, "--substitutes", ONION / "substitutes.txt", "--format", "foon")
    path.write_text(result.stdout, encoding="utf-8")
    return path


def _command(name: str, tmp: Path, tree: Path) -> list:
    lp = tmp / "q.lp"
    lp.write_text("n(N) :- N = #count { O : object(O) }.\n#show n/1.\n", encoding="utf-8")
    data = ["--data", ONION]
    return {
        "solve": ["solve", *data],
        "compare": ["compare", *data, "--method", "asp"],
        "batch": ["batch", *data, "-o", tmp / "b.jsonl"],
        "check": ["check", tree, *data],
        "missing": ["missing", *data],
        "reachable": ["reachable", *data],
        "objects": ["objects", *data],
        "merge": ["merge", ONION / "FOON.txt", "-o", tmp / "m.txt"],
        "draw": ["draw", tree, *data, "-o", tmp / "t.dot"],
        "consolidate": ["consolidate", tree, "--kitchen", ONION / "kitchen.json", "--goal", "onion, fried, in [pan]"],
        "export": ["export", "pddl", *data, "-o", tmp / "pddl"],
        "facts": ["facts", *data],
        "query": ["query", lp, *data],
    }[name]


COMMANDS = [
    "solve", "compare", "batch", "check", "missing", "reachable", "objects",
    "merge", "draw", "consolidate", "export", "facts", "query",
]  # fmt: skip

#: what each command prints with the onion substitutes
WITH_SUBSTITUTES = {
    "solve": "uses red onion, whole for onion, whole",
    "check": "uses red onion, whole for onion, whole",
    "missing": "uses red onion, whole for onion, whole",
    "consolidate": "uses red onion, whole for onion, whole",
    "reachable": "yes  onion, fried, in [pan]",
    "facts": "substitute(",
}


@pytest.mark.parametrize("name", COMMANDS)
def test_every_command_accepts_the_flags(name, tmp_path, onion_tree):
    args = _command(name, tmp_path, onion_tree)

    def fresh(*extra):
        (tmp_path / "b.jsonl").unlink(missing_ok=True)  # batch: a new results file each time
        return run(*args, *extra)

    def fine(*extra, codes=(0,)):
        result = fresh(*extra)
        assert result.exit_code in codes, result.output + repr(result.exception)
        return result

    # without substitutes the onion dish cannot be made: check says invalid (exit status 1)
    fine("--level", "2", "--normalize", "--synonyms", SMOOTHIE_DIR / "synonyms.txt", codes=(0, 1))
    fine("--level", "1", codes=(0, 1))
    substitutes = ["--substitutes", ONION / "substitutes.txt", "--max-substitutions", "1"]
    if name in ("merge", "export"):  # a FOON file, a PDDL task: no tree counts substitutions there
        one_line_error(fresh(*substitutes), "--substitutes")
        return
    result = fine(*substitutes)
    if name in WITH_SUBSTITUTES:
        assert WITH_SUBSTITUTES[name] in result.stdout
    if name in ("solve", "check", "missing", "consolidate", "reachable"):
        plain = fresh()  # without the substitutes the onion dish cannot be made
        assert WITH_SUBSTITUTES[name] not in plain.stdout
    one_line_error(fresh("--level", "4"), "--level")
    one_line_error(fresh("--max-substitutions", "1"), "--max-substitutions needs --substitutes")


# --- levels: the FOON rewritten at the level is the reference --------------------------------


def test_cli_level_2_on_the_universal_foon_matches_the_rewritten_foon(shared_foon_dir):
    data = Dataset.load(shared_foon_dir)
    text = (shared_foon_dir / "FOON.txt").read_text(encoding="utf-8")
    reference = Problem(parse_lines(rewrite_foon(text, 2), "rewritten"), [rewrite_object(o, 2) for o in data.kitchen])
    reference.motion, reference.utensils = data.motion, data.utensils
    want = optimum(reference, [rewrite_object(g, 2) for g, _ in data.goals])
    result = ok("solve", "--data", shared_foon_dir, "--level", "2", "--goals", "all", "--format", "json")
    got = [len(r["units"]) if r["status"] == "optimal" else None for r in json.loads(result.stdout)]
    assert got == want and sum(x is not None for x in got) >= 23
    # the goals print as level 2 sees them: no ingredients
    assert all(r["goal"]["ingredients"] == [] for r in json.loads(result.stdout))


def test_library_level_1_on_the_universal_foon_matches_the_rewritten_foon(shared_foon_dir):
    data = Dataset.load(shared_foon_dir)
    text = (shared_foon_dir / "FOON.txt").read_text(encoding="utf-8")
    reference = Problem(
        parse_lines(rewrite_foon(text, 1), "rewritten"), [rewrite_object(o, 1) for o in data.kitchen], data.motion
    )
    reference.utensils = data.utensils
    want = optimum(reference, [rewrite_object(g, 1) for g, _ in data.goals])
    kb = foon2asp.load(shared_foon_dir, level=1)
    trees = kb.solve("all")
    assert [len(t.unit_ids) if t.status == "optimal" else None for t in trees] == want
    assert all(not g.states and not g.ingredients and g.container is None for g in kb.goals)


def test_worked_example_level_2_on_the_command_line():
    plain = ok("solve", "--data", SALAD, "--format", "json")
    assert json.loads(plain.stdout)[0]["status"] == "unreachable"
    level2 = json.loads(ok("solve", "--data", SALAD, "--level", "2", "--format", "json").stdout)[0]
    assert level2["status"] == "optimal" and len(level2["units"]) == 4
    assert level2["goal"] == {"label": "salad", "states": ["tossed"], "ingredients": [], "container": "bowl"}
    # a goal named with its level-3 text is the object level 2 sees
    named = ok("solve", "--data", SALAD, "--level", "2", "--goal", "salad, tossed, contains {dressing}, in [bowl]")
    assert "Status: optimal" in named.stdout


def test_check_at_a_level_reads_the_tree_as_the_level_sees_it(tmp_path):
    tree = tmp_path / "tree.json"
    tree.write_text(ok("solve", "--data", SALAD, "--level", "2", "--format", "json").stdout, encoding="utf-8")
    assert "Verdict: VALID" in ok("check", tree, "--data", SALAD, "--level", "2").stdout
    # at level 3 the tree's units are not in the FOON (the dressing has no ingredients)
    plain = run("check", tree, "--data", SALAD, "--goal", "salad")
    assert plain.exit_code == 1 and "Verdict: INVALID" in plain.stdout and "unknown unit" in plain.stdout


# --- normalisation and synonyms on files with mixed spellings --------------------------------

MIXED = """//
O\tBlueberries
S\twhole
O\tKnife
M\tslice
O\tblueberry
S\tSliced
O\tknife
//
O\tblender
S\tempty
O\tblue berries
S\tsliced
O\tliquidmilk
M\tblend
O\tsmoothies
S\tblended
S\tcontains\t{blueberries,liquidmilk}
S\tin\t[blender]
//
O\tsmoothie
S\tblended
S\tcontains\t{blueberry,milk}
S\tin\t[blenders]
O\tglass
S\tempty
M\tpour
O\tglass
S\tfull
S\tcontains\t{smoothie}
//
"""


def _mixed(tmp_path: Path) -> Path:
    (tmp_path / "FOON.txt").write_text(MIXED, encoding="utf-8")
    kitchen = [
        {"label": "blueberry", "states": ["Whole"], "ingredients": [], "container": None},
        {"label": "knives", "states": [], "ingredients": [], "container": None},
        {"label": "Blenders", "states": ["empty"], "ingredients": [], "container": None},
        {"label": "MILK", "states": [], "ingredients": [], "container": None},
        {"label": "glasses", "states": ["empty"], "ingredients": [], "container": None},
    ]
    (tmp_path / "kitchen.json").write_text(json.dumps(kitchen), encoding="utf-8")
    goal = {"label": "glass", "states": ["full"], "ingredients": ["smoothie"], "container": None}
    (tmp_path / "goal_nodes.json").write_text(json.dumps([goal]), encoding="utf-8")
    (tmp_path / "synonyms.txt").write_text(
        "# mixed spellings\nliquidmilk = milk\nblue berries = blueberries\n", encoding="utf-8"
    )
    return tmp_path


def test_normalize_and_synonyms_on_the_command_line(tmp_path):
    data = _mixed(tmp_path)
    assert json.loads(ok("solve", "--data", data, "--format", "json").stdout)[0]["status"] == "unreachable"
    normalized = json.loads(ok("solve", "--data", data, "--normalize", "--format", "json").stdout)[0]
    assert normalized["status"] == "unreachable"  # "liquidmilk" and "blue berries" are other words
    both = ["--normalize", "--synonyms", data / "synonyms.txt"]
    tree = json.loads(ok("solve", "--data", data, *both, "--format", "json").stdout)[0]
    assert tree["status"] == "optimal" and [u["motion"] for u in tree["units"]] == ["slice", "blend", "pour"]
    # the first spelling seen is kept: the FOON's, before the kitchen's
    first = tree["units"][0]["inputs"]
    assert first[0]["label"] == "blueberries" and first[1]["label"] == "knife"
    assert tree["units"][1]["outputs"][0]["label"] == "smoothies"
    # objects says which spellings were joined, in text and JSON
    listing = ok("objects", "--data", data, *both)
    assert "joined 'blueberry', 'blue berries' as 'blueberries'" in listing.stderr
    assert "joined 'milk' as 'liquidmilk'" in listing.stderr
    infos = json.loads(ok("objects", "--data", data, *both, "--format", "json").stdout)
    sliced = next(i for i in infos if i["text"] == "blueberries, sliced")
    assert sliced["joined"] == ["blueberry, sliced", "blue berries, sliced"]
    assert "joins blueberry, sliced | blue berries, sliced" in listing.stdout
    # the JSON listing is still a goals file
    goals = tmp_path / "goals.json"
    goals.write_text(json.dumps([i for i in infos if i["label"] == "glass" and i["states"] == ["full"]]))
    assert ok("solve", "--data", data, *both, "--goals", goals).stdout.count("Status: optimal") == 1
    # merge writes the units as the comparison sees them and names the joined spellings
    out = tmp_path / "merged.txt"
    merged = ok("merge", data / "FOON.txt", "-o", out, *both)
    assert "joined 'blueberry', 'blue berries' as 'blueberries'" in merged.stderr
    text = out.read_text(encoding="utf-8")
    assert "blue berries" not in text and "liquidmilk" in text and "\tmilk" not in text


def test_normalize_and_synonyms_in_the_library(tmp_path):
    data = _mixed(tmp_path)
    kb = api.load(data, normalize=True, synonyms={"liquidmilk": "milk", "blue berries": "blueberries"})
    tree = kb.solve("glass")  # the goals file's entry
    assert tree.status == "optimal" and tree.cost["units"] == 3
    assert kb.joined["blueberries"] == ["blueberries", "blueberry", "blue berries"]
    assert kb.joined["liquidmilk"] == ["liquidmilk", "milk"]
    assert kb.joined["knife"] == ["knife", "knives"]
    # goals may be named in any spelling the comparison joins
    assert kb.solve("Smoothie, blended, contains {blueberry,milk}, in [blender]").status == "optimal"
    assert kb.object_id("smoothie") == kb.object_id("smoothies")
    # the same from a synonyms file; without normalisation the plural stays apart
    assert api.load(data, normalize=True, synonyms=data / "synonyms.txt").solve("glass").status == "optimal"
    assert api.load(data, synonyms=data / "synonyms.txt").solve("glass").status == "unreachable"
    with pytest.raises(InputError, match="--level must be 1, 2 or 3"):
        api.load(data, level=0)
    with pytest.raises(InputError, match="synonyms.txt:2"):
        (data / "synonyms.txt").write_text("a = b\na = c\n", encoding="utf-8")
        api.load(data, synonyms=data / "synonyms.txt")


# --- substitutes: brute force through the command line ---------------------------------------


def _write_problem(problem: Problem, where: Path) -> tuple[Path, Path]:
    foon = where / "FOON.txt"
    api.write_foon(problem.foon, foon, "foon")
    kitchen = where / "kitchen.json"
    kitchen.write_text(json.dumps([o.to_json() for o in problem.kitchen_items]), encoding="utf-8")
    return foon, kitchen


def test_cli_substitutes_against_brute_force(tmp_path):
    rng = random.Random(2121)
    subs_file = tmp_path / "subs.txt"
    subs_file.write_text(SUBS, encoding="utf-8")
    subs = parse_substitutes(SUBS)
    checked = used = 0
    for trial in range(12):
        problem = _random_problem(rng)
        where = tmp_path / str(trial)
        where.mkdir()
        foon, kitchen = _write_problem(problem, where)
        data = ["--foon", foon, "--kitchen", kitchen, "--goals", "all-objects"]
        limit = [None, 1, 0][trial % 3]
        bound = [] if limit is None else ["--max-substitutions", limit]
        result = ok("solve", *data, "--substitutes", subs_file, *bound, "--format", "json")
        results = json.loads(result.stdout)
        ids = {key(o.to_json()): i for i, o in enumerate(problem.objects)}
        costs = {(problem.objects[c.needed].text, c.used.text): c.cost for c in candidates(problem, subs)}
        relying = []
        for r in results:
            want = _brute_force(problem, ids[key(r["goal"])], subs, limit)
            if want is None:
                assert r["status"] == "unreachable", (trial, r["goal"])
                continue
            assert r["status"] == "optimal"
            cost = sum(costs[(s["needed"], s["used"])] for s in r["substitutions"])
            assert (cost, len(r["units"])) == want, (trial, r["goal"])
            assert limit is None or len(r["substitutions"]) <= limit
            checked += 1
            if r["substitutions"]:
                used += 1
                relying.append(r)
        if relying:
            trees = where / "trees.json"
            trees.write_text(json.dumps(relying), encoding="utf-8")
            check = ["check", trees, "--foon", foon, "--kitchen", kitchen]
            # accepted with the same substitutes (each using the ones solve named), rejected without
            verdicts = json.loads(ok(*check, "--substitutes", subs_file, "--format", "json").stdout)
            assert [v["substitutions"] for v in verdicts] == [r["substitutions"] for r in relying]
            assert run(*check).exit_code == 1
    assert checked > 15 and used > 4


def test_the_fewest_substitutions_then_the_cheapest(tmp_path):
    lines = tmp_path / "subs.txt"
    lines.write_text("onion: shallot, red onion =2\n", encoding="utf-8")
    result = ok("solve", "--data", ONION, "--substitutes", lines, "--format", "json")
    assert json.loads(result.stdout)[0]["substitutions"] == [{"needed": "onion, whole", "used": "shallot, whole"}]
    for form in ("substitutes.txt", "substitutes.json"):  # red onion costs 1, shallot 2
        result = ok("solve", "--data", ONION, "--substitutes", ONION / form, "--format", "json")
        assert json.loads(result.stdout)[0]["substitutions"] == [{"needed": "onion, whole", "used": "red onion, whole"}]
    zero = ok("solve", "--data", ONION, "--substitutes", ONION / "substitutes.txt", "--max-substitutions", "0")
    assert "Status: unreachable" in zero.stdout and "uses" not in zero.stdout


def test_substitutes_in_the_library():
    kb = api.load(ONION)
    assert kb.solve("onion, fried, in [pan]").status == "unreachable"
    tree = kb.solve("onion, fried, in [pan]", substitutes=ONION / "substitutes.json")
    assert tree.status == "optimal" and tree.to_dict()["substitutions"] == [
        {"needed": "onion, whole", "used": "red onion, whole"}
    ]
    mapping = {"onion": ["shallot"]}
    tree = kb.solve("onion, fried, in [pan]", options=api.Options(substitutes=mapping, max_substitutions=1))
    assert tree.to_dict()["substitutions"] == [{"needed": "onion, whole", "used": "shallot, whole"}]
    report = kb.check(tree, substitutes=mapping)
    assert report.valid and report.raw.substitutions == [{"needed": "onion, whole", "used": "shallot, whole"}]
    assert not kb.check(tree).valid
    assert kb.reachable("all", options=api.Options(substitutes=mapping)) == {
        FoonObject.make("onion", ["fried"], (), "pan"): True
    }
    assert kb.reachable("all") == {FoonObject.make("onion", ["fried"], (), "pan"): False}


@pytest.mark.parametrize("method", ["ids", "gbfs-h1", "gbfs-h2", "asp-greedy-h1", "asp-greedy-h2", "asp-depth"])
def test_methods_that_cannot_honour_substitutes_refuse(method):
    result = run("solve", "--data", ONION, "--substitutes", ONION / "substitutes.txt", "--method", method)
    one_line_error(result, method, "substitutes")
    one_line_error(run("compare", "--data", ONION, "--substitutes", ONION / "substitutes.txt"), "substitutes")
    with pytest.raises(InputError, match="substitutes"):
        api.load(ONION).solve("onion, fried, in [pan]", method=method, substitutes={"onion": ["red onion"]})


def test_max_depth_and_substitutes_refuse():
    args = ["solve", "--data", ONION, "--substitutes", ONION / "substitutes.txt"]
    one_line_error(run(*args, "--max-depth", "3"), "substitutes")
    one_line_error(run(*args, "--objective", "depth"), "substitutes")


# --- labels stay data ------------------------------------------------------------------------

SPECIAL = ['qu"ote', "back\\slash", "50% fat", "end.", "a :- b", "x). #show y", "it's"]


@pytest.mark.parametrize("label", SPECIAL)
def test_special_labels_stay_data_on_the_command_line(tmp_path, label):
    foon = "//\nO\tonion\nS\tchopped\nO\tpan\nM\tcook\nO\tsoup\nS\tcooked\nS\tin\t[pan]\n//\n"
    (tmp_path / "FOON.txt").write_text(foon, encoding="utf-8")
    kitchen = [FoonObject.make(label, ["chopped"]).to_json(), FoonObject.make("pan").to_json()]
    (tmp_path / "kitchen.json").write_text(json.dumps(kitchen), encoding="utf-8")
    subs = tmp_path / "subs.json"
    subs.write_text(json.dumps({"onion": [label]}), encoding="utf-8")
    data = ["--data", tmp_path, "--goal", "soup"]
    result = ok("solve", *data, "--substitutes", subs, "--format", "json")
    assert json.loads(result.stdout)[0]["substitutions"] == [
        {"needed": "onion, chopped", "used": f"{label.lower()}, chopped"}
    ]
    # the facts, with the substitutes, are plain facts: the label is one string
    facts = ok("facts", "--data", tmp_path, "--substitutes", subs).stdout
    ctl = clingo.Control(["--warn=none"])
    ctl.add("base", [], facts)
    ctl.ground([("base", [])])
    assert [a.symbol for a in ctl.symbolic_atoms.by_signature("substitute", 3)] != []
    assert not any(a.symbol.name in ("y", "b") for a in ctl.symbolic_atoms)
    # a synonym with the label joins it with the onion: no substitute needed
    synonyms = tmp_path / "synonyms.txt"
    synonyms.write_text(f"{label} = onion\n", encoding="utf-8")
    joined = json.loads(ok("solve", *data, "--synonyms", synonyms, "--format", "json").stdout)[0]
    assert joined["status"] == "optimal" and "substitutions" not in joined


def test_line_breaks_in_labels_are_refused(tmp_path):
    subs = tmp_path / "subs.json"
    subs.write_text(json.dumps({"onion": ["red\nonion"]}), encoding="utf-8")
    one_line_error(run("solve", "--data", ONION, "--substitutes", subs), "line break", "subs.json")
    with pytest.raises(InputError, match="line breaks"):
        api.load(ONION, synonyms={"red\nonion": "onion"})
    with pytest.raises(InputError, match="line break"):
        api.load(ONION).solve("onion, fried, in [pan]", substitutes={"onion": ["red\ronion"]})
