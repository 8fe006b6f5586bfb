"""Property-based fuzzing of everything that reads user input.

Each property holds for random and mutated input: the reader returns a
result or raises one :class:`InputError` whose message is one line (the
command line turns it into exit status 2) -- never another exception.  The
injection property: a label round-trips exactly through the ASP facts and
never changes the program.

The number of examples per test is ``FUZZ_EXAMPLES`` (default 25: the suite
stays fast); ``make fuzz`` runs 2,000 per test (over 10,000 inputs in all).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import click
import clingo
import pytest
from click.testing import CliRunner

from helpers import build

pytest.importorskip("hypothesis")

from hypothesis import HealthCheck, assume, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from foon2asp.asp.facts import facts  # noqa: E402
from foon2asp.cli.flags import SECONDS, int32  # noqa: E402
from foon2asp.cli.goal_commands import SCHEDULER  # noqa: E402
from foon2asp.cli.main import main  # noqa: E402
from foon2asp.errors import BAD_CHAR, InputError  # noqa: E402
from foon2asp.foon.loaders import read_goals, read_kitchen, read_motion, read_utensils  # noqa: E402
from foon2asp.foon.model import Foon  # noqa: E402
from foon2asp.foon.parser import format_units, parse_lines, read_foon  # noqa: E402
from foon2asp.foon.treefiles import read_trees  # noqa: E402

EXAMPLES = int(os.environ.get("FUZZ_EXAMPLES", "25"))
FUZZ = settings(
    max_examples=EXAMPLES,
    deadline=None,
    derandomize=EXAMPLES <= 25,  # the quick run is the same every time
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture, HealthCheck.data_too_large],
)
DEMO = Path(__file__).resolve().parent.parent / "data"
SEEDS = {name: (DEMO / name).read_bytes() for name in ("FOON.txt", "kitchen.json", "goal_nodes.json", "motion.txt")}
SEEDS["utensils.txt"] = (DEMO / "utensils.txt").read_bytes()
TREE = json.dumps(
    {
        "goal": {"label": "tomato", "states": ["chopped"]},
        "units": [
            {
                "motion": "chop",
                "inputs": [{"label": "tomato", "states": ["whole"]}, {"label": "knife"}],
                "outputs": [{"label": "tomato", "states": ["chopped"]}, {"label": "knife"}],
            }
        ],
    },
    indent=1,
).encode()

HOSTILE = [
    b"\x00",
    b"\xff",
    b"\xc3",
    b"\xed\xa0\x80",
    b"\r\n",
    b"\r",
    b"\x0b",
    b"\xc2\x85",
    b"\xe2\x80\xa8",
    b"\xef\xbb\xbf",
    b"[" * 300,
    b"{" * 300,
    b"9" * 5000,
    b'"\\ud800"',
    b'"\\u0000"',
    b"//",
    b"#",
    b"O\t",
    b"S\t",
    b"M\t",
    b"\t",
    b'")). #show. :- a("',
    b"1e999999",
]


@st.composite
def mutated(draw, seed: bytes) -> bytes:
    """``seed`` with lines deleted, duplicated, swapped, or bytes inserted, flipped or cut."""
    lines = seed.split(b"\n")
    for _ in range(draw(st.integers(0, 4))):
        if not lines:
            break
        i = draw(st.integers(0, len(lines) - 1))
        op = draw(st.sampled_from(["delete", "duplicate", "swap", "insert", "flip", "cut", "hostile"]))
        if op == "delete":
            del lines[i]
        elif op == "duplicate":
            lines.insert(i, lines[i])
        elif op == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == "insert":
            lines.insert(i, draw(st.binary(max_size=40)))
        elif op == "flip" and lines[i]:
            k = draw(st.integers(0, len(lines[i]) - 1))
            lines[i] = lines[i][:k] + bytes([draw(st.integers(0, 255))]) + lines[i][k + 1 :]
        elif op == "cut":
            lines[i] = lines[i][: draw(st.integers(0, len(lines[i])))]
        else:
            k = draw(st.integers(0, len(lines[i])))
            lines[i] = lines[i][:k] + draw(st.sampled_from(HOSTILE)) + lines[i][k:]
    return b"\n".join(lines)


def outcome(call) -> object:
    """The result of ``call()``, or the one-line InputError it raised."""
    try:
        return call()
    except InputError as exc:
        message = str(exc)
        assert "\n" not in message and "\r" not in message
        assert not BAD_CHAR.search(message), repr(message)  # shown escaped
        return exc


def fuzz_file(tmp_path: Path, name: str, data: bytes) -> Path:
    path = tmp_path / name
    path.write_bytes(data)
    return path


@FUZZ
@given(data=st.one_of(mutated(SEEDS["FOON.txt"]), st.binary(max_size=300)))
def test_foon_parser(tmp_path_factory, data):
    path = fuzz_file(tmp_path_factory.mktemp("f"), "FOON.txt", data)
    outcome(lambda: read_foon(path))


@FUZZ
@given(
    name=st.sampled_from(["kitchen.json", "goal_nodes.json"]),
    data=st.one_of(
        mutated(SEEDS["kitchen.json"]),
        mutated(SEEDS["goal_nodes.json"]),
        st.recursive(
            st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
            lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=4),
            max_leaves=20,
        ).map(lambda v: json.dumps(v).encode()),
    ),
)
def test_json_loaders(tmp_path_factory, name, data):
    path = fuzz_file(tmp_path_factory.mktemp("j"), name, data)
    outcome(lambda: read_kitchen(path) if name == "kitchen.json" else read_goals(path))


@FUZZ
@given(
    name=st.sampled_from(["motion.txt", "utensils.txt"]),
    data=st.one_of(mutated(SEEDS["motion.txt"]), mutated(SEEDS["utensils.txt"]), st.binary(max_size=200)),
)
def test_motion_and_utensil_files(tmp_path_factory, name, data):
    path = fuzz_file(tmp_path_factory.mktemp("m"), name, data)
    warnings: list[str] = []
    result = outcome(lambda: read_motion(path, warnings) if name == "motion.txt" else read_utensils(path, warnings))
    if not isinstance(result, InputError):
        labels = result.keys() if isinstance(result, dict) else result
        assert not any(BAD_CHAR.search(label) for label in labels)


@FUZZ
@given(data=st.one_of(mutated(TREE), mutated(SEEDS["FOON.txt"][:2000]), st.binary(max_size=200)))
def test_tree_reader(tmp_path_factory, data):
    path = fuzz_file(tmp_path_factory.mktemp("t"), "tree.json", data)
    outcome(lambda: read_trees(path))


@FUZZ
@given(value=st.one_of(st.text(max_size=30), st.sampled_from(["nan", "inf", "-1", "1e999", "2147483648", "0x10"])))
def test_option_types(value):
    for kind in (SECONDS, int32(min=0), SCHEDULER):
        try:
            kind.convert(value, None, None)
        except click.BadParameter as exc:
            assert "\n" not in exc.format_message()


@FUZZ
@given(data=st.one_of(mutated(SEEDS["FOON.txt"]), mutated(SEEDS["kitchen.json"])), which=st.booleans())
def test_command_line_end_to_end(tmp_path_factory, data, which):
    """``solve`` on a data directory with one mutated file: exit 0 or one line and exit 2."""
    d = tmp_path_factory.mktemp("d")
    for name, seed in SEEDS.items():
        (d / name).write_bytes(seed)
    (d / ("FOON.txt" if which else "kitchen.json")).write_bytes(data)
    res = CliRunner().invoke(main, ["solve", "--data", str(d), "--goal", "tomato salad", "--time-limit", "5"])
    assert res.exit_code in (0, 2), (res.exit_code, res.stderr)
    if res.exit_code == 2:
        lines = res.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("foon2asp: error: "), res.stderr


def pairs_up(text: str) -> bool:
    """Do the brackets of ``text`` pair up (``[`` with ``]``, ``{`` with ``}``)?  Said without the
    parser: pairs ``[]``/``{}`` are taken out until none is left."""
    kept = "".join(c for c in text if c in "[]{}")
    while "[]" in kept or "{}" in kept:
        kept = kept.replace("[]", "").replace("{}", "")
    return not kept


def one_list(arg: str) -> bool:
    """Is ``arg`` what ``in`` and ``contains`` take: a label or list, in one pair of brackets or none?"""
    arg = arg.strip()
    if arg[:1] in ("[", "{") and arg[-1:] in ("]", "}"):
        arg = arg[1:-1]
    return not any(c in arg for c in "[]{}")


@FUZZ
@given(
    relation=st.sampled_from(["", "in", "contains", "on", "attached to"]),
    arg=st.text(alphabet="ab ,[]{}", max_size=12),
    official=st.booleans(),
)
def test_state_brackets_pair_up_or_the_line_is_named(relation, arg, official):
    """A state line's brackets that do not pair up (``in [bowl``) are an error naming the
    line and column; those that do are read, and written back the same."""
    assume(relation or arg.strip())
    fields = f"{relation}\t{arg}" if relation else arg
    text = f"O\tbowl\nS\tempty\nM\tpour\nO\tbowl\nS{'5' if official else ''}\t{fields}\n//\n"
    result = outcome(lambda: parse_lines(text, "f.txt"))
    if not pairs_up(arg) or (relation in ("in", "contains") and not one_list(arg)):
        assert isinstance(result, InputError), (text, result)
        assert (result.path, result.line) == ("f.txt", 5) and result.column is not None, str(result)
        assert str(result).startswith(f"f.txt:5:{result.column}: ")
        return
    assert isinstance(result, Foon), (text, str(result))
    (out,) = result.units[0].outputs
    assert not any(c in label for label in (*out.ingredients, out.container or "") for c in "[]{}")
    assert parse_lines(format_units(result.units), "again.txt").units == result.units


LABEL = st.text(
    alphabet=st.characters(blacklist_categories=("Cs", "Cc", "Zl", "Zp")) | st.sampled_from('"\\.():-#%{}'),
    min_size=1,
    max_size=30,
).filter(lambda s: s.strip() and s == " ".join(s.split()))


@FUZZ
@given(label=LABEL)
def test_labels_round_trip_and_never_change_the_program(label):
    assume(" ".join(label.split()).lower() not in ("b", "c"))  # another object of the FOON
    problem = build([("mix", [label, "b"], ["c"])], [label, "b"])
    text = facts(problem)
    ctl = clingo.Control(["--warn=none"])
    ctl.add("base", [], text)
    ctl.ground([("base", [])])
    got = {str(a.symbol.arguments[1].string) for a in ctl.symbolic_atoms.by_signature("label", 2)}
    assert " ".join(label.split()).lower() in got  # exactly the (normalised) label
    plain = build([("mix", ["a", "b"], ["c"])], ["a", "b"])
    clean = clingo.Control(["--warn=none"])
    clean.add("base", [], facts(plain))
    clean.ground([("base", [])])

    signatures = sorted(ctl.symbolic_atoms.signatures)
    assert signatures == sorted(clean.symbolic_atoms.signatures)
    for name, arity, _ in signatures:
        assert sum(1 for _ in ctl.symbolic_atoms.by_signature(name, arity)) == sum(
            1 for _ in clean.symbolic_atoms.by_signature(name, arity)
        )
