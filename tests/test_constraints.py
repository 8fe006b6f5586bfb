"""User constraints: flags, files and rules; optimality under constraints vs brute force."""

from __future__ import annotations

import io
import itertools
import json
import os
import random
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from foon2asp.asp import constraints
from foon2asp.asp.options import AspOptions
from foon2asp.cli.main import main
from foon2asp.errors import InputError
from foon2asp.methods.plan import session_of as Session
from foon2asp.tree.validate import validate
from helpers import REPO, best, brute_force, build, file_error, goal_id, obj

MOTIONS = ("cut", "mix", "heat")
LABELS = "abcdefg"


def random_foon(seed: int):
    """A small random FOON (7-10 units over 7 labels) with a made goal, or None."""
    rng = random.Random(seed)
    units = []
    for _ in range(rng.randint(7, 10)):
        ins = rng.sample(LABELS, rng.randint(1, 2))
        out = rng.choice([x for x in LABELS if x not in ins])
        units.append((rng.choice(MOTIONS), ins, [out]))
    kitchen = rng.sample(LABELS[:4], 2)
    problem = build(units, kitchen)
    made = sorted({o for u in range(len(problem.units)) for o in problem.products[u]} - problem.kitchen)
    return (problem, made[-1]) if made else None


def candidates(problem, goal) -> set[int]:
    """Units that can be part of a tree (viable producers of relevant objects), computed
    independently of the encoding: derivable objects by the validator, then a backward walk."""
    fired = validate(problem, goal, list(range(len(problem.units)))).order
    viable = set(fired)
    seen, stack, out = {goal}, [goal], set()
    while stack:
        o = stack.pop()
        if o in problem.kitchen:
            continue
        for u in problem.producers.get(o, ()):
            if u in viable and u not in out:
                out.add(u)
                for i in problem.required[u]:
                    if i not in seen:
                        seen.add(i)
                        stack.append(i)
    return out


def motions_of(problem, units) -> set[str]:
    return {problem.units[u].motion for u in units}


def labels_of(problem, units) -> set[str]:
    return {o.label for u in units for o in problem.units[u].inputs + problem.units[u].outputs}


def solve_with(problem, goal, programs):
    return Session(problem, AspOptions(programs=programs)).solve(goal)


CASES = [c for c in (random_foon(s) for s in range(40)) if c is not None][:25]


def check_against(problem, goal, programs, allowed) -> None:
    """The solver's tree under ``programs`` is valid, allowed, and as small as the
    smallest brute-force tree that ``allowed`` accepts (unreachable when none)."""
    trees = [t for t in brute_force(problem, goal) if allowed(t)]
    tree = solve_with(problem, goal, programs)
    if not trees:
        assert tree.status == "unreachable"
        return
    assert tree.status == "optimal"
    assert validate(problem, goal, tree.units).valid
    assert allowed(tuple(tree.units))
    assert len(tree.units) == min(len(t) for t in trees)


def test_random_cases_are_interesting():
    assert len(CASES) >= 20
    assert sum(1 for p, g in CASES if brute_force(p, g)) >= 10


@pytest.mark.parametrize("case", range(len(CASES)))
def test_forbid_motion_is_optimal_vs_brute_force(case):
    problem, goal = CASES[case]
    for m in MOTIONS:
        check_against(problem, goal, [("f", constraints.forbid_motion(m))], lambda t: m not in motions_of(problem, t))


@pytest.mark.parametrize("case", range(len(CASES)))
def test_forbid_object_and_max_units_vs_brute_force(case):
    problem, goal = CASES[case]
    for lab in LABELS[:4]:
        if lab == problem.objects[goal].label:
            continue
        check_against(
            problem, goal, [("f", constraints.forbid_object(lab))], lambda t: lab not in labels_of(problem, t)
        )
    for n in range(4):
        check_against(problem, goal, [("m", constraints.max_units(n))], lambda t: len(t) <= n)


@pytest.mark.parametrize("case", range(len(CASES)))
def test_require_motion_and_object_vs_brute_force(case):
    # a required unit must still belong to the tree: brute force over candidate units only
    problem, goal = CASES[case]
    cand = candidates(problem, goal)
    for m in MOTIONS:
        check_against(
            problem,
            goal,
            [("r", constraints.require_motion(m))],
            lambda t: set(t) <= cand and m in motions_of(problem, t),
        )
    for lab in LABELS[:3]:
        check_against(
            problem,
            goal,
            [("r", constraints.require_object(lab))],
            lambda t: set(t) <= cand and lab in labels_of(problem, t),
        )


def tomato():
    """chop (1 unit) or slice + dice (2 units) make a chopped tomato."""
    return build(
        [
            ("chop", ["tomato", "knife"], ["chopped"]),
            ("slice", ["tomato", "knife"], ["sliced"]),
            ("dice", ["sliced", "knife"], ["chopped"]),
        ],
        ["tomato", "knife"],
    )


def test_forbid_motion_takes_the_longer_way():
    p = tomato()
    g = goal_id(p, "chopped")
    assert [p.units[u].motion for u in solve_with(p, g, []).units] == ["chop"]
    tree = solve_with(p, g, [("f", constraints.forbid_motion("  CHOP "))])
    assert tree.status == "optimal"
    assert [p.units[u].motion for u in tree.units] == ["slice", "dice"]


def test_constraints_that_make_the_goal_impossible_give_unreachable():
    p = tomato()
    g = goal_id(p, "chopped")
    assert solve_with(p, g, [("f", constraints.forbid_object("knife"))]).status == "unreachable"
    both = constraints.forbid_motion("chop") + constraints.max_units(1)
    assert solve_with(p, g, [("f", both)]).status == "unreachable"
    assert solve_with(p, g, [("r", constraints.require_motion("boil"))]).status == "unreachable"


def test_labels_are_data_in_generated_rules():
    evil = 'x"). #show y/0. y. :- use(U'
    p = build(
        [
            ("chop", ["tomato", obj(evil)], ["chopped"]),
            ("slice", ["tomato", "knife"], ["sliced"]),
            ("dice", ["sliced", "knife"], ["chopped"]),
        ],
        ["tomato", "knife", obj(evil)],
    )
    g = goal_id(p, "chopped")
    assert len(solve_with(p, g, []).units) == 1
    text = constraints.forbid_object(evil)
    constraints.check_syntax("generated", text)  # a well-formed program
    tree = solve_with(p, g, [("f", text)])
    assert tree.status == "optimal" and len(tree.units) == 2
    assert evil not in labels_of(p, tree.units)


def test_user_rule_and_file(tmp_path):
    p = tomato()
    g = goal_id(p, "chopped")
    f = tmp_path / "no-chop.lp"
    f.write_text('% my rules\n:- use(U), motion(U,"chop").\n')
    progs = constraints.ConstraintSpec(files=(str(f),), rules=(":- #count { U : use(U) } > 5.",)).programs()
    assert [name for name, _ in progs] == [str(f), "--rule #1"]
    tree = solve_with(p, g, progs)
    assert [p.units[u].motion for u in tree.units] == ["slice", "dice"]


@pytest.mark.parametrize(
    "text, line, words",
    [
        ('ok.\n:- use(U), motion(U,"chop").\np(X :- use(X).\n', 3, "syntax error"),
        ("a.\n\np(X) :- use(U).\n", 3, "'X' is unsafe"),
        (":- use(U)", 1, "'.' missing"),
    ],
)
def test_errors_in_user_files_are_located(tmp_path, text, line, words):
    f = tmp_path / "mine.lp"
    message = str(file_error(f, text, lambda p: constraints.ConstraintSpec(files=(str(p),)).programs()))
    assert message.startswith(f"{f}:{line}: ")
    assert words in message and "\n" not in message and "<block>" not in message


def test_rule_error_names_the_rule():
    with pytest.raises(InputError) as err:
        constraints.ConstraintSpec(rules=("a.", "b :- c(")).programs()
    assert str(err.value).startswith("--rule #2:1: syntax error")


def test_session_locates_errors_of_unchecked_programs():
    p = tomato()
    with pytest.raises(InputError) as err:
        Session(p, AspOptions(programs=[("mine.lp", "ok.\np(X) :- q.\n")]))
    assert str(err.value).startswith("mine.lp:2: unsafe variables")
    with pytest.raises(InputError) as err:
        Session(p, AspOptions(programs=[("other.lp", "p(.\n")]))
    assert str(err.value).startswith("other.lp:1: syntax error")


def test_missing_file_and_bad_max_units():
    with pytest.raises(InputError, match="constraint file not found"):
        constraints.ConstraintSpec(files=("/nonexistent/rules.lp",)).programs()
    with pytest.raises(InputError):
        constraints.max_units(-1)


def test_spec_collects_everything(tmp_path):
    spec = constraints.ConstraintSpec(forbid_motion=("Chop*",), require_object=("Bowl",), max_units=3)
    assert bool(spec) and not constraints.ConstraintSpec()
    names = [n for n, _ in spec.programs()]
    assert names == ["--forbid-motion Chop*", "--require-object Bowl", "--max-units"]
    assert spec.names() == (["chop"], ["bowl"])
    assert constraints.unknown_names(tomato(), spec) == ["no object is labelled 'bowl'"]


# ---------------------------------------------------------------- command line (demo data)


def run(*args):
    return CliRunner().invoke(main, list(args))


def test_cli_solve_forbid_motion_demo():
    r = run("solve", "--data", "demo", "--goal", "tomato salad", "--forbid-motion", "chop", "--format", "json")
    assert r.exit_code == 0, r.output
    (tree,) = json.loads(r.stdout)
    assert tree["status"] == "optimal"
    motions = [u["motion"] for u in tree["units"]]
    assert "chop" not in motions and {"slice", "dice"} <= set(motions)
    base = json.loads(run("solve", "--data", "demo", "--goal", "tomato salad", "--format", "json").stdout)[0]
    assert tree["cost"]["units"] == base["cost"]["units"] + 1


def test_cli_max_units_makes_infeasible_and_rule_file(tmp_path):
    """Trees exist, but the constraints rule them all out: infeasible (not unreachable), the
    constraint named when it alone does it."""
    r = run("solve", "--data", "demo", "--goal", "tomato salad", "--max-units", "3", "--format", "json")
    (answer,) = json.loads(r.stdout)
    assert answer["status"] == "infeasible" and answer["proven_by"] == "clingo"
    assert answer["infeasible_by"] == ["--max-units"], answer
    assert r.exit_code == 0
    f = tmp_path / "c.lp"
    f.write_text(':- use(U), motion(U,"slice").\n')
    r = run(
        "solve",
        "--data",
        "demo",
        "--goal",
        "tomato salad",
        "--constraint",
        str(f),
        "--forbid-motion",
        "chop",
        "--format",
        "json",
    )
    (answer,) = json.loads(r.stdout)
    assert answer["status"] == "infeasible" and "constraints rule them all out" in answer["reason"]
    text = run("solve", "--data", "demo", "--goal", "tomato salad", "--max-units", "3").stdout
    assert "Status: infeasible (proven by clingo)" in text


def test_cli_syntax_error_is_one_clean_line(tmp_path):
    f = tmp_path / "bad.lp"
    f.write_text('% comment\n\n:- use(U) motion(U,"chop").\n')
    r = run("solve", "--data", "demo", "--goal", "tomato salad", "--constraint", str(f))
    assert r.exit_code == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"foon2asp: error: {f}:3: syntax error")
    assert "Traceback" not in r.output
    r = run("solve", "--data", "demo", "--goal", "tomato salad", "--rule", "p(X) :- q.")
    assert r.exit_code == 2 and r.stderr.startswith("foon2asp: error: --rule #1:1: unsafe variables")


def test_cli_constraints_need_an_asp_method_and_warn_on_unknown_names():
    r = run("solve", "--data", "demo", "--goal", "tomato salad", "--method", "ids", "--forbid-motion", "chop")
    assert r.exit_code == 2 and "ASP methods only" in r.stderr
    r = run("solve", "--data", "demo", "--goal", "tomato salad", "--forbid-motion", "flambe")
    assert r.exit_code == 0 and "no unit has motion 'flambe'" in r.stderr


def test_shared_forbidding_a_used_motion(shared_problem):
    from foon2asp.foon import goals

    data, problem = shared_problem
    g = goals.resolve_label(data, problem, "macaroni")
    session = Session(problem, AspOptions())
    base = session.solve(g)
    assert base.status == "optimal"
    used = sorted(motions_of(problem, base.units))
    for m in used[:2]:
        tree = solve_with(problem, g, [("f", constraints.forbid_motion(m))])
        assert tree.status in ("optimal", "unreachable")
        if tree.status == "optimal":
            assert m not in motions_of(problem, tree.units)
            assert validate(problem, g, tree.units).valid
            assert len(tree.units) >= len(base.units)


def test_combinations_are_conjunctions():
    # forbidding two motions = forbidding each: checked on all random cases at once
    for problem, goal in CASES[:8]:
        for m1, m2 in itertools.combinations(MOTIONS, 2):
            progs = [("a", constraints.forbid_motion(m1)), ("b", constraints.forbid_motion(m2))]
            check_against(problem, goal, progs, lambda t: not ({m1, m2} & motions_of(problem, t)))


def test_batch_applies_constraints_like_solve(tmp_path):
    out = tmp_path / "b.jsonl"
    args = ["--goals", "all", "--forbid-motion", "chop"]
    res = CliRunner().invoke(main, ["batch", "--data", "demo", *args, "--output", str(out), "--no-progress"])
    assert res.exit_code == 0, res.output
    batch = {json.loads(l)["goal"]["label"]: json.loads(l) for l in out.read_text().splitlines()[1:]}
    solved = json.loads(CliRunner().invoke(main, ["solve", "--data", "demo", *args, "--format", "json"]).stdout)
    assert len(batch) == len(solved) == 4
    for r in solved:
        b = batch[r["goal"]["label"]]
        assert (b["status"], b["cost"].get("units")) == (r["status"], r["cost"].get("units"))
        assert all(u["motion"] != "chop" for u in b["units"])
    # without chop the tomato salad takes slice + dice: one unit more than the unconstrained optimum
    assert batch["tomato salad"]["cost"]["units"] == 5


def test_constraint_on_labels_still_sees_labels():
    # two producers of the goal: the cheaper one uses "knife"; forbidding that label
    # (a program over label/2 and input/2, left out of lean facts) must take the other
    units = [("cut", ["knife", "k"], ["goal"]), ("pour", ["k"], ["x"]), ("mix", ["x"], ["goal"])]
    problem = build(units, ["knife", "k"])
    goal = goal_id(problem, "goal")
    plain = Session(problem).solve(goal)
    assert plain.status == "optimal" and len(plain.units) == 1
    rule = ':- use(U), input(U,O), label(O,"knife").\n'
    constrained = Session(problem, AspOptions(programs=[("rule", rule)])).solve(goal)
    assert constrained.status == "optimal" and sorted(constrained.units) == [1, 2]
    # brute force agrees: unit 0 alone is the one smallest tree, and it has the knife
    size, trees = best(problem, goal, lambda m: m["units"])
    assert size == 1 and trees == [(0,)]


# ---------------------------------------------------------------- programs from pipes and standard input

FOON2ASP = str(Path(sys.executable).parent / "foon2asp")
NO_CHOP = ':- use(U), motion(U,"chop").'
SALAD = ["solve", "--data", "demo", "--goal", "tomato salad"]


def shell(command: str, stdin: str | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(["bash", "-c", command], input=stdin, capture_output=True, text=True, timeout=120, cwd=REPO)


def test_a_constraint_file_from_a_pipe_is_read():
    res = shell(f"{FOON2ASP} {' '.join(SALAD[:3])} --goal 'tomato salad' --constraint <(echo '{NO_CHOP}')")
    assert res.returncode == 0, res.stderr
    assert "(units 5," in res.stdout  # without chop: slice and dice


@pytest.mark.parametrize("command", [[*SALAD, "--constraint", "-"], ["query", "-", "--data", "demo"]])
def test_a_program_from_standard_input_is_read(command):
    program = NO_CHOP if command[0] == "solve" else "#show count(N) : N = #count { U : unit(U) }."
    res = subprocess.run([FOON2ASP, *command], input=program, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert ("(units 5," in res.stdout) if command[0] == "solve" else ("count(18)" in res.stdout)


def test_standard_input_is_read_once_and_named_in_errors(monkeypatch):
    monkeypatch.setattr(constraints, "_STREAMS", {})
    monkeypatch.setattr("sys.stdin", io.TextIOWrapper(io.BytesIO(b':- use(U), motion(U,"chop") x.\n')))
    spec = constraints.ConstraintSpec(files=("-",))
    with pytest.raises(InputError) as err:
        spec.programs()
    assert str(err.value).startswith("-:1: syntax error")
    assert constraints.read_file("-") == ':- use(U), motion(U,"chop") x.\n'  # read once, remembered


def test_a_pipe_is_read_once_and_remembered(monkeypatch):
    monkeypatch.setattr(constraints, "_STREAMS", {})
    read, write = os.pipe()
    os.write(write, NO_CHOP.encode())
    os.close(write)
    try:
        path = f"/dev/fd/{read}"
        spec = constraints.ConstraintSpec(files=(path,))
        assert spec.programs() == spec.programs() == [(path, NO_CHOP)]
    finally:
        os.close(read)


def test_a_constraint_file_that_is_a_broken_link_is_named_so(tmp_path):
    (tmp_path / "rules.lp").symlink_to(tmp_path / "gone.lp")
    with pytest.raises(InputError) as err:
        constraints.ConstraintSpec(files=(str(tmp_path / "rules.lp"),)).programs()
    assert str(err.value) == f"{tmp_path / 'rules.lp'}: constraint file is a broken link (to {tmp_path / 'gone.lp'})"
