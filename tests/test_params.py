"""The explorer's question (foon2asp/explore/params.py): parameters named as the command-line
options, one-line errors for anything else, refused rules, the address written back."""

from __future__ import annotations

import pytest

from foon2asp import api
from foon2asp.errors import InputError
from foon2asp.explore.params import MAX_QUERY, MAX_RULE, PARAMETERS, Question


def parse(*items: tuple[str, str], most: float = 30.0) -> Question:
    return Question.parse(list(items), most)


def error(*items: tuple[str, str], most: float = 30.0) -> str:
    with pytest.raises(InputError) as caught:
        parse(*items, most=most)
    text = str(caught.value)
    assert "\n" not in text
    return text


def test_the_parameters_are_the_command_line_options():
    options = {"--objective", "--time-limit", "--max-units", "--max-depth", "--human-steps", "--agents", "--rule"}
    options |= {f"--{what}-{kind}" for what in ("forbid", "require") for kind in ("motion", "object")}
    assert {f"--{p}" for p in PARAMETERS} - {"--goal", "--without"} == options
    q = parse(
        ("goal", "macaroni"),
        ("objective", "success,units"),
        ("forbid-motion", "boil"),
        ("forbid-motion", "cook"),
        ("forbid-motion", "boil"),  # once is enough
        ("rule", ':- use(U), motion(U,"fry").'),
        ("without", "knife"),
        ("max-units", "7"),
        ("human-steps", "2"),
        ("time-limit", "2.5"),
        ("agents", "arm=2,human=1"),
    )
    assert (q.goal, q.objective, q.forbid_motion, q.without) == (
        "macaroni",
        ("success", "units"),
        ("boil", "cook"),
        ("knife",),
    )
    assert (q.max_units, q.human_steps, q.time_limit, q.agents) == (7, 2, 2.5, "arm=2,human=1")
    settings = q.settings(10.0, {"motion_cost": "costs.json"})
    assert settings == {
        "motion_cost": "costs.json",
        "objective": ("success", "units"),
        "time_limit": 2.5,
        "forbid_motions": ("boil", "cook"),
        "rules": (':- use(U), motion(U,"fry").',),
        "max_units": 7,
        "human_steps": 2,
    }
    assert api.Options.of(**settings).constraints.forbid_motion == ("boil", "cook")


def test_the_address_is_written_back_in_a_fixed_order_without_defaults():
    q = parse(("rule", "a."), ("goal", "ice"), ("objective", "units"), ("time-limit", "3"), ("forbid-motion", "x"))
    assert q.items() == [("goal", "ice"), ("time-limit", "3"), ("forbid-motion", "x"), ("rule", "a.")]
    assert Question.parse(q.items()) == q
    assert Question.from_dict(q.to_dict()) == q
    assert parse().items() == [] and parse(("goal", "  "), ("rule", "")) == Question()


def test_each_answer_depends_only_on_what_changes_it():
    q = parse(("goal", "ice"), ("forbid-motion", "pour"), ("agents", "arm=2"), ("without", "knife"))
    assert q.only("baselines") == parse(("goal", "ice"), ("without", "knife"))
    assert q.only("tree") == parse(("goal", "ice"), ("forbid-motion", "pour"), ("without", "knife"))
    assert q.only("schedule") == q


def test_a_rule_that_runs_code_or_reads_files_is_refused():
    assert error(("rule", "a."), ("rule", "#script (python)\nimport os\n#end.")) == (
        "--rule #2: #script is refused here: a rule may not run code"
    )
    assert "may not read files" in error(("rule", '#include "/etc/passwd".'))
    assert "#SCRIPT is refused" in error(("rule", "# SCRIPT (lua) x #end."))


@pytest.mark.parametrize(
    "items, message",
    [
        ([("gaol", "ice")], "unknown parameter 'gaol' (did you mean 'goal'?)"),
        (
            [("x" * 500, "1")],
            "unknown parameter 'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx\u2026'; the parameters are",
        ),
        ([("goal", "ice"), ("goal", "egg")], "goal is given twice"),
        ([("goal", "g" * 1001)], "goal: 1001 characters is too long (at most 1000)"),
        ([("rule", "r" * (MAX_RULE + 1))], f"rule: {MAX_RULE + 1} characters is too long (at most {MAX_RULE})"),
        ([("forbid-motion", str(k)) for k in range(101)], "forbid-motion: more than 100 values"),
        ([("max-units", "-1")], "max-units: '-1' is not a whole number 0..2147483647"),
        ([("max-depth", "0")], "max-depth: '0' is not a whole number 1..2147483647"),
        ([("human-steps", "9" * 12)], "human-steps: '999999999999' is not a whole number"),
        ([("time-limit", "nan")], "time-limit: 'nan' is not a finite number of seconds > 0"),
        ([("time-limit", "abc")], "time-limit: 'abc' is not a number of seconds"),
        ([("time-limit", "31")], "time-limit: at most 30 seconds here (the explorer's --time-limit)"),
        ([("agents", "arm")], "agents 'arm': 'arm' is not KIND=N"),
    ],
)
def test_bad_parameters_are_one_line_errors(items, message):
    assert error(*items).startswith(message)


def test_the_address_limit_leaves_room_for_every_value():
    assert MAX_QUERY >= 4 * MAX_RULE
