"""Reading agents, durations, capabilities and resources: values, exactness, one-line errors."""

from __future__ import annotations

import json

import pytest

from foon2asp.errors import InputError
from foon2asp.schedule.spec import (
    ScheduleSpec,
    load_capabilities,
    load_durations,
    load_resources,
    parse_agents,
)


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text if isinstance(text, str) else json.dumps(text, indent=1), encoding="utf-8")
    return path


def test_agents():
    assert parse_agents(None) == parse_agents("") == (("robot", 1),)
    assert parse_agents(" arm = 2 , human=1") == (("arm", 2), ("human", 1))
    spec = ScheduleSpec(parse_agents("arm=2,human=1"))
    assert spec.agent_list() == [("arm-1", "arm"), ("arm-2", "arm"), ("human-1", "human")]
    assert spec.has_human()


@pytest.mark.parametrize(
    "text, words",
    [
        ("arm", "is not KIND=N"),
        ("arm=0", "whole number 1..64"),
        ("arm=two", "whole number"),
        ("arm=2,arm=1", "given twice"),
        ('ar"m=1', "must be a letter"),
        ("2x=1", "must be a letter"),
    ],
)
def test_bad_agents(text, words):
    with pytest.raises(InputError) as err:
        parse_agents(text)
    assert words in str(err.value) and "\n" not in str(err.value)


def test_durations_flat_and_per_kind(tmp_path):
    table = {"*": 2, "Chop": 1.5, "arm": {"pour": 0.25, "*": 3}, "human": {"chop": 0}}
    d = load_durations(write(tmp_path, "d.json", table))
    assert d.of("arm", "pour") == 250  # the kind's own entry
    assert d.of("arm", "mix") == 3000  # the kind's default
    assert d.of("human", "chop") == 0
    assert d.of("human", "mix") == 2000  # the top-level default
    assert d.of("robot", "chop") == 1500  # motions are compared case-folded
    kinds = load_durations(write(tmp_path, "k.json", {"*": {"*": 4}, "arm": {"chop": 1}}))
    assert kinds.of("robot", "anything") == 4000 and kinds.of("arm", "chop") == 1000 and kinds.of("arm", "x") == 1000


def test_durations_are_exact_decimals(tmp_path):
    d = load_durations(write(tmp_path, "d.json", '{"a": 0.1, "b": 0.7, "c": 1e2, "d": 100000}'))
    assert (d.of("k", "a"), d.of("k", "b"), d.of("k", "c"), d.of("k", "d")) == (100, 700, 100000, 100000000)


@pytest.mark.parametrize(
    "text, words, line",
    [
        ('{\n"chop": 0.0005\n}', 'duration "chop" is 0.0005 s: finer than the precision of 0.001 s', 2),
        ('{\n"arm": {\n "chop": -1\n}}', 'duration "arm" / "chop" must be at least 0', 3),
        ('{"chop": "fast"}', "must be a number of seconds", 1),
        ('{"chop": true}', "must be a number of seconds", 1),
        ('{"chop": 100001}', "above the limit", 1),
        ('{"a-b": {"chop": 1}}', "must be a letter", 1),
        ("[1, 2]", "a durations file is a JSON object", 1),
        ('{"chop": 1', "bad JSON", 1),
    ],
)
def test_bad_durations(tmp_path, text, words, line):
    path = write(tmp_path, "durations.json", text)
    with pytest.raises(InputError) as err:
        load_durations(path)
    msg = str(err.value)
    assert msg.startswith(f"{path}:{line}") and words in msg and "\n" not in msg


def test_capabilities_and_resources(tmp_path):
    caps = load_capabilities(write(tmp_path, "c.json", {"arm": ["Pour", "chop  it"], "human": []}))
    assert caps == {"arm": frozenset({"pour", "chop it"}), "human": frozenset()}
    spec = ScheduleSpec((("arm", 1), ("robot", 1), ("human", 1)), capabilities=caps)
    assert spec.can("arm", "POUR") and not spec.can("arm", "mix") and spec.can("robot", "mix")
    res = load_resources(write(tmp_path, "r.json", {"Knife": 1, "stove": 2}))
    assert res == {"knife": 1, "stove": 2}


@pytest.mark.parametrize(
    "loader, text, words",
    [
        (load_capabilities, '{"arm": "pour"}', 'capabilities of "arm" must be a list of motion names'),
        (load_capabilities, '{"arm": [1]}', "must be a list of motion names"),
        (load_capabilities, '{"a m": ["pour"]}', "must be a letter"),
        (load_capabilities, "[]", "a capabilities file is a JSON object"),
        (load_resources, '{"knife": 0}', 'capacity of "knife" must be a whole number of at least 1'),
        (load_resources, '{"knife": 1.5}', "whole number"),
        (load_resources, '{"knife": "one"}', "whole number"),
        (load_resources, '{" ": 1}', "must not be empty"),
        (load_resources, '"knife"', "a resources file is a JSON object"),
    ],
)
def test_bad_capabilities_and_resources(tmp_path, loader, text, words):
    path = write(tmp_path, "f.json", text)
    with pytest.raises(InputError) as err:
        loader(path)
    msg = str(err.value)
    assert msg.startswith(str(path)) and words in msg and "\n" not in msg


@pytest.mark.parametrize("kind", ["durations", "capabilities", "resources"])
def test_missing_file_is_one_line(tmp_path, kind):
    with pytest.raises(InputError) as err:
        ScheduleSpec.from_files("arm=1", **{kind: tmp_path / "nope.json"})
    text = str(err.value)
    assert "nope.json" in text and "\n" not in text
    assert f"{kind} file not found" in text and "file file" not in text


def test_a_kind_a_file_names_that_no_agent_has_is_an_error_naming_the_file_and_the_kind(tmp_path):
    caps = write(tmp_path, "caps.json", {"arm": ["crack", "beat", "fry"]})
    with pytest.raises(InputError) as err:
        ScheduleSpec.from_files("arms=2", capabilities=caps)
    assert str(err.value) == f'{caps}:2: no agent has the kind "arm" (the agents: arms=2); did you mean arms?'
    table = write(tmp_path, "d.json", {"*": 2, "human": {"peel": 3}})
    with pytest.raises(InputError) as err:
        ScheduleSpec.from_files("arm=2", durations=table)
    assert str(err.value) == f'{table}:3: no agent has the kind "human" (the agents: arm=2)'
    # a spec built in Python is checked as well
    with pytest.raises(InputError, match=r'^capabilities: no agent has the kind "arm" .*did you mean arms\?$'):
        ScheduleSpec((("arms", 2),), capabilities={"arm": frozenset({"fry"})})


def test_a_misspelt_agent_kind_is_an_error_with_the_closest_kinds(tmp_path):
    with pytest.raises(InputError) as err:
        ScheduleSpec.from_files("arm=1,humann=1")
    assert str(err.value) == (
        'agents \'arm=1,humann=1\': the kind "humann" is named in no file and is not "human" (a person);'
        " did you mean human?"
    )
    caps = write(tmp_path, "caps.json", {"gripper": ["pour"]})
    with pytest.raises(InputError, match=r'the kind "grippers" is named in no file; did you mean gripper\?$'):
        ScheduleSpec.from_files("gripper=1,grippers=1", capabilities=caps)
    assert ScheduleSpec.from_files("robot=1,arm=2").warnings == ()  # no file: every kind takes the defaults


def test_an_agent_kind_no_file_names_takes_the_defaults_with_a_note(tmp_path):
    caps = write(tmp_path, "caps.json", {"arm": ["pour"]})
    table = write(tmp_path, "d.json", {"pour": 2, "arm": {"pour": 1}})
    spec = ScheduleSpec.from_files("arm=2,gripper=1", capabilities=caps)
    assert spec.warnings == (
        "agents 'arm=2,gripper=1': no capabilities file names the kind \"gripper\": it can do every motion",
    )
    assert spec.can("gripper", "mix") and not spec.can("arm", "mix")
    both = ScheduleSpec.from_files("arm=2,gripper=1", durations=table, capabilities=caps)
    assert both.warnings == (
        "agents 'arm=2,gripper=1': no durations or capabilities file names the kind \"gripper\": it takes the"
        " default durations and can do every motion",
    )
    assert both.durations.of("gripper", "pour") == 2000 and both.durations.of("arm", "pour") == 1000
    # a durations file of motions only names no kind: every kind takes it, nothing to note
    flat = write(tmp_path, "flat.json", {"pour": 2})
    assert ScheduleSpec.from_files("arm=2,human=1", durations=flat).warnings == ()
