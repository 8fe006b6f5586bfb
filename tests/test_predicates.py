"""A predicate a user program uses that nothing defines -- no shipped encoding, no fact foon2asp
writes, no user program -- is warned about on every command that takes rules, with where it is
and the closest defined predicates; ``query`` names the file each warning is about."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

import foon2asp
from conftest import DEMO
from foon2asp.api import Constraints
from foon2asp.asp import encoding_files
from foon2asp.asp.facts import facts
from foon2asp.asp.predicates import FACTS, known_predicates, predicates, refuse_host_code, rule_warnings
from foon2asp.cli.main import main
from foon2asp.errors import InputError

SMOOTHIES = sorted((DEMO / "llm").glob("smoothie-*.json"))
TYPO = ':- use(U), motoin(U,"fry").'
RIGHT = ':- use(U), motion(U,"fry").'
WARNED = "foon2asp: warning: --rule #1:1:12: motoin/2 is defined nowhere; did you mean motion/2?"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def commands(output: Path) -> dict[str, list]:
    """Each command that takes rules, as arguments before the rules (batch writes ``output``)."""
    salad = ["--data", "demo", "--goal", "tomato salad"]
    return {
        "solve": ["solve", *salad],
        "compare": ["compare", *salad, "--method", "asp"],
        "missing": ["missing", *salad],
        "batch": ["batch", *salad, "--output", output],
        "consolidate": ["consolidate", *SMOOTHIES],
    }


def rule_lines(stderr: str) -> list[str]:
    """The warnings about predicates (not those about the input data)."""
    return [line for line in stderr.splitlines() if "defined nowhere" in line or "no rule head" in line]


@pytest.mark.parametrize("command", ["solve", "compare", "missing", "batch", "consolidate"])
def test_every_command_warns_on_a_misspelt_predicate(command, tmp_path):
    res = run(*commands(tmp_path / "typo.jsonl")[command], "--rule", TYPO)
    assert res.exit_code in (0, 1), res.output
    assert rule_lines(res.stderr) == [WARNED]
    res = run(*commands(tmp_path / "right.jsonl")[command], "--rule", RIGHT)
    assert res.exit_code in (0, 1), res.output
    assert rule_lines(res.stderr) == []


def test_query_warns_on_a_misspelt_predicate_and_names_the_closest(tmp_path):
    prog = tmp_path / "typo.lp"
    prog.write_text('bad(U) :- use(U), motoin(U,"fry").\n#show bad/1.\n')
    res = run("query", prog, "--data", "demo", "--encoding", "tree", "--goal", "tomato salad")
    assert res.exit_code == 0, res.output
    assert rule_lines(res.stderr) == [
        f"foon2asp: warning: {prog}:1:19: motoin/2 is defined nowhere; did you mean motion/2?"
    ]
    prog.write_text('bad(U) :- use(U), motion(U,"fry").\n#show bad/1.\n')
    res = run("query", prog, "--data", "demo", "--encoding", "tree", "--goal", "tomato salad")
    assert res.exit_code == 0 and "warning" not in res.stderr


def test_the_solve_of_the_example_warns(shared_foon_dir):
    res = run("solve", "--data", shared_foon_dir, "--goal", "macaroni", "--rule", ':- use(U), motoin(U,"heat").')
    assert res.exit_code == 0, res.output
    assert rule_lines(res.stderr) == [
        "foon2asp: warning: --rule #1:1:12: motoin/2 is defined nowhere; did you mean motion/2?"
    ]


def test_a_predicate_the_users_own_rules_define_is_no_warning(tmp_path):
    own = tmp_path / "own.lp"
    own.write_text('fried(U) :- motion(U,"fry").\n#external extra(U) : unit(U).\n#defined later/1.\n')
    uses = ":- use(U), fried(U), extra(U), not later(U)."
    base = ["solve", "--data", "demo", "--goal", "tomato salad"]
    res = run(*base, "--constraint", own, "--rule", uses)
    assert res.exit_code == 0, res.output
    assert rule_lines(res.stderr) == []
    # one rule defines what another uses
    res = run(*base, "--rule", ":- use(U), slow(U).", "--rule", 'slow(U) :- motion(U,"mix").')
    assert res.exit_code == 0 and rule_lines(res.stderr) == []
    # without the file that defines it, it is a misspelling; the file names where it is
    wrong = tmp_path / "wrong.lp"
    wrong.write_text("% nothing charred\n:- use(U),\n   charred(U).\n")
    res = run(*base, "--constraint", wrong)
    assert rule_lines(res.stderr) == [f"foon2asp: warning: {wrong}:3:4: charred/1 is defined nowhere"]


def test_query_warnings_name_the_file_they_are_about(tmp_path):
    prog = tmp_path / "mine.lp"
    prog.write_text("% asks nothing\n\n\n\n\nx.\n")
    res = run("query", prog, "--data", "demo", "--encoding", "reachable", "--goal", "tomato salad")
    assert res.exit_code == 0, res.output
    # reachable.lp reads asked/1 on its line 6: the warning is about that file, not the user's
    text = Path(encoding_files.part("reachable")).read_text(encoding="utf-8").splitlines()
    line = next(n for n, t in enumerate(text, 1) if t.startswith("reachable(O) :- asked(O)"))
    assert rule_lines(res.stderr) == [
        f"foon2asp: warning: encodings/parts/reachable.lp:{line}:17: asked/1 occurs in no rule head and no fact"
    ]
    assert str(prog) not in res.stderr
    # a predicate a shipped encoding defines, used without loading it: the encoding that does
    prog.write_text("bad(U) :- use(U).\n#show bad/1.\n")
    res = run("query", prog, "--data", "demo")
    assert rule_lines(res.stderr) == [
        f"foon2asp: warning: {prog}:1:11: use/1 occurs in no rule head and no fact; load the encoding tree (or closed, core, missing, prepared, use), which defines it"
    ]


def test_api_query_warnings_are_in_the_result():
    import foon2asp

    kb = foon2asp.api.load(DEMO)
    result = kb.query("p(O) :- kitchn(O).\n#show p/1.\n", name="p.lp")
    assert result.warnings == ["p.lp:1:9: kitchn/1 is defined nowhere; did you mean kitchen/1?"]


def test_predicates_walks_conditions_aggregates_and_every_statement():
    found = predicates(
        "h(X) :- b1(X), not b2(X), b3(Y) : b4(Y).\n"
        "{ c1(X) : c2(X) } :- c3.\n"
        "d1 ; d2(X) : d3(X) :- d4.\n"
        "1 #sum { X : e1(X) : e2(X) } :- e3.\n"
        "f1 :- #count { X : f2(X), not f3(X) } > 1, X = #sum { Y : f4(Y) }, X > 0.\n"
        "g1 :- { g2(X) : g3(X) } > 0.\n"
        "-n1(X) :- n2(X;Y), n3((1;2)).\n"
        "#external x1(X) : x2(X). #defined x3/2.\n"
        "#show s1/1. #show T : s2(T). #minimize { X : m1(X) }.\n"
    )
    assert found.defined == {("h", 1), ("c1", 1), ("d1", 0), ("d2", 1), ("e1", 1), ("f1", 0), ("g1", 0)} | {
        ("n1", 1),
        ("x1", 1),
        ("x3", 2),
    }
    used = {"b1/1", "b2/1", "b3/1", "b4/1", "c2/1", "c3/0", "d3/1", "d4/0", "e2/1", "e3/0", "f2/1", "f3/1", "f4/1"}
    used |= {"g2/1", "g3/1", "n2/1", "n3/1", "x2/1", "s1/1", "s2/1", "m1/1"}
    assert {f"{n}/{a}" for n, a in found.used} == used
    assert found.used[("b3", 1)] == (1, 27) and found.used[("m1", 1)] == (9, 46)


def test_rule_warnings_leave_syntax_errors_to_the_check_and_name_each_program():
    assert rule_warnings([("--rule #1", ":- use(U) motoin(U).")]) == []  # the syntax check reports it
    warned = rule_warnings([("a.lp", ":- use(U), lable(U,_)."), ("--rule #2", ":- outptu(U,O), goal(O).")])
    assert warned == [
        "a.lp:1:12: lable/2 is defined nowhere; did you mean label/2?",
        "--rule #2:1:4: outptu/2 is defined nowhere; did you mean output/2?",
    ]
    assert rule_warnings([("x", ":- zqx(1).")]) == ["x:1:4: zqx/1 is defined nowhere"]


def test_the_known_predicates_cover_the_facts_and_the_vocabulary(demo_problem):
    _, problem = demo_problem
    written = predicates(facts(problem, goal_nodes=[0], goal=0)).defined
    assert written == set(FACTS)
    table = (Path(__file__).resolve().parents[1] / "docs" / "vocabulary.md").read_text()
    documented = {
        (name, len(args.split(","))) for name, args in re.findall(r"^\| `(\w+)\(([^)]*)\)`", table, re.MULTILINE)
    }
    assert documented and documented <= known_predicates()


# ---------------------------------------------------------------- host code


@pytest.mark.parametrize(
    "text, where, what",
    [
        ('#script (python)\nimport os\n#end.\n:- use(U), motion(U,"chop").', (1, 1), "#script (python) is refused"),
        ("#script(lua) x = 1 #end.", (1, 1), "#script (lua) is refused"),
        ('p(@f(1)).\n:- use(U), motion(U,"chop").', (1, 3), "@f(...) is refused"),
        ("#show @h(1) : use(_).", (1, 7), "@h(...) is refused"),
        ("ok :- #count { X : use(X), X = @n() } > 1.", (1, 32), "@n(...) is refused"),
        # clingo reads on after a syntax error, and would run a script found there
        ("a :- b c.\n#script (python)\nprint(1)\n#end.", (2, 1), "#script (python) is refused"),
    ],
)
def test_host_code_is_refused_where_it_is(text, where, what):
    with pytest.raises(InputError) as err:
        refuse_host_code("--rule #1", text)
    assert (err.value.path, err.value.line, err.value.column) == ("--rule #1", *where)
    assert what in err.value.message and "host code" in err.value.message


@pytest.mark.parametrize(
    "text",
    [
        '% #script (python) print(1) #end.\n:- use(U), motion(U,"chop").',
        '%* #script (python)\n@f(1) *%\n:- use(U), motion(U,"#script (python)").',
        ':- use(U), motion(U,"@f(1)").',
        ":- use(U), #count { O : input(U,O) } > 9.",
    ],
)
def test_comments_and_strings_that_mention_host_code_are_no_host_code(text):
    refuse_host_code("--rule #1", text)  # no error
    assert predicates(text).used  # and the program is read


def test_a_script_in_an_included_file_is_refused_there(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("inner.lp").write_text("%\n#script (python)\nprint(1)\n#end.\n")
    with pytest.raises(InputError) as err:
        refuse_host_code("outer.lp", '#include "inner.lp".\n')
    assert str(err.value).startswith("inner.lp:2:1: #script (python) is refused")
    assert "(in a file outer.lp includes)" in str(err.value)


SCRIPT = '#script (python)\nopen("RAN", "w").write("ran")\n#end.\n:- use(U), motion(U,"chop").\n'


@pytest.mark.parametrize(
    "args",
    [
        ["solve", "--data", "demo", "--goal", "tomato salad", "--rule", SCRIPT],
        ["solve", "--data", "demo", "--goal", "tomato salad", "--constraint", "script.lp"],
        ["compare", "--data", "demo", "--goal", "tomato salad", "--method", "asp", "--constraint", "script.lp"],
        ["missing", "--data", "demo", "--goal", "pancake", "--rule", SCRIPT],
        ["batch", "--data", "demo", "--output", "r.jsonl", "--constraint", "script.lp"],
        ["schedule", "--data", "demo", "--goal", "tomato salad", "--rule", SCRIPT],
        ["consolidate", *SMOOTHIES, "--rule", SCRIPT],
        ["query", "script.lp", "--data", "demo", "--encoding", "tree", "--goal", "tomato salad"],
        ["solve", "--data", "demo", "--goal", "tomato salad", "--rule", ":- use(U), motion(U,@m())."],
    ],
    ids=["solve-rule", "solve-constraint", "compare", "missing", "batch", "schedule", "consolidate", "query", "call"],
)
def test_every_command_refuses_host_code_in_one_line(args, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("script.lp").write_text(SCRIPT)
    res = run(*args)
    assert res.exit_code == 2, res.output
    (line,) = res.stderr.splitlines()
    assert re.fullmatch(
        r"foon2asp: error: (script\.lp|--rule #1):1:\d+: (#script \(python\)|@m\(\.\.\.\)) is refused.*", line
    )
    assert not Path("RAN").exists()


def test_the_library_refuses_host_code_on_every_path():
    kb = foon2asp.load("demo")
    calls = [
        lambda: kb.solve("tomato salad", rules=[SCRIPT]),
        lambda: kb.solve("tomato salad", constraints=Constraints(extra=[("mine", SCRIPT)])),
        lambda: kb.query(SCRIPT, goal="tomato salad", encodings=["tree"]),
        lambda: kb.missing("pancake", rules=[SCRIPT]),
    ]
    for call in calls:
        with pytest.raises(InputError, match=r"#script \(python\) is refused"):
            call()


#: run in a fresh process: clingo with Python scripting switched on, as a clingo build may have it
WITH_PYTHON = """
import sys, clingo, clingo.script
clingo.script.enable_python()
ctl = clingo.Control()
ctl.add("base", [], '#script (python)\\nopen("RAN-CLINGO", "w").write("ran")\\n#end.')
assert open("RAN-CLINGO").read() == "ran"  # this clingo runs scripts ...
import foon2asp
from foon2asp.errors import InputError
kb = foon2asp.load("demo")
for call in (lambda: kb.solve("tomato salad", rules=[sys.argv[1]]), lambda: kb.query(sys.argv[1], goal="tomato salad")):
    try:
        call()
    except InputError as exc:
        print(exc)
"""


def test_a_clingo_with_python_scripting_runs_none_of_a_users_script(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-c", WITH_PYTHON, SCRIPT], cwd=tmp_path, capture_output=True, text=True, timeout=120
    )
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "RAN-CLINGO").exists()  # ... but foon2asp gives it none of the user's
    assert proc.stdout.splitlines() == [
        "--rule #1:1:1: #script (python) is refused: a program may not run host code",
        "<program>:1:1: #script (python) is refused: a program may not run host code",
    ]
    assert not (tmp_path / "RAN").exists()


@pytest.mark.parametrize(
    "command, extra, warning",
    [
        *[(name, ["--rule", TYPO], WARNED) for name in ("solve", "compare", "missing", "batch", "consolidate")],
        ("schedule", ["--rule", TYPO], WARNED),
        ("pddl", ["--forbid-motion", "fly"], "foon2asp: warning: no unit has motion 'fly'"),
        ("query", [], "q.lp:1:9: kitchn/1 is defined nowhere; did you mean kitchen/1?"),
        # an option that is ignored
        ("compare", ["--method", "gbfs-h1", "--forbid-motion", "chop"], "constraints apply to ASP methods only"),
    ],
)
def test_strict_makes_every_warning_about_the_request_an_error(command, extra, warning, tmp_path):
    """Without --strict the warning is a line on stderr and the command answers; with it the warning
    is a one-line error (exit 2) before any answer or file."""
    (tmp_path / "q.lp").write_text("p(O) :- kitchn(O).\n#show p/1.\n")
    salad = ["--data", "demo", "--goal", "tomato salad"]
    more = {
        "schedule": ["schedule", *salad, "--agents", "arm=2"],
        "pddl": ["export", "pddl", *salad, "--output", tmp_path / "pddl"],
        "query": ["query", tmp_path / "q.lp", "--data", "demo"],
        # smoothie-3.json skips a unit (an error with --strict)
        "consolidate": ["consolidate", *[path for path in SMOOTHIES if path.name != "smoothie-3.json"]],
    }
    args = [*{**commands(tmp_path / "r.jsonl"), **more}[command], *extra]
    res = run(*args)
    assert res.exit_code in (0, 1), res.output
    assert any(warning in line and "warning" in line for line in res.stderr.splitlines()), res.stderr
    (tmp_path / "r.jsonl").unlink(missing_ok=True)
    res = run(*args, "--strict")
    assert res.exit_code == 2, res.output
    (line,) = res.stderr.splitlines()
    assert line.startswith("foon2asp: error: ") and warning.removeprefix("foon2asp: warning: ") in line
    assert line.endswith("(--strict: warnings are errors)") or line.endswith("(strict: warnings are errors)")
    assert res.stdout == "" and not (tmp_path / "r.jsonl").exists()


@pytest.mark.parametrize(
    "rule, column",
    [('a("é', 4), ("a(é).", 3), ('ok :- use(U).\nb("x", é).', 8)],
)
def test_a_character_clingo_cannot_report_is_one_located_line(rule, column):
    """Outside a closed string, a character that is not ASCII made clingo's parser echo a byte of
    it, which ended in a traceback and clingo's PANIC; now it is one line naming the rule."""
    res = run("solve", "--data", "demo", "--goal", "tomato salad", "--rule", rule)
    line = rule.count("\n") + 1
    assert res.exit_code == 2 and res.stderr.strip() == (
        f"foon2asp: error: --rule #1:{line}:{column}: the character 'é' is not ASCII and stands outside a string"
    )
    assert "PANIC" not in res.output and "Traceback" not in res.output


def test_a_character_that_is_not_ascii_in_a_string_or_a_comment_is_read():
    res = run("solve", "--data", "demo", "--goal", "tomato salad", "--rule", ':- use(U), motion(U,"é"). % é\n%* é *%')
    assert res.exit_code == 0, res.output
