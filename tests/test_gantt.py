"""Gantt charts of schedules: lanes, boxes, colours, fixed positions, every format."""

from __future__ import annotations

import re
import shutil

import pytest

from foon2asp import report
from foon2asp.report import gantt
from foon2asp.report.draw import HUMAN_FILL, UNIT_FILL
from foon2asp.schedule import ScheduleSpec, schedule
from foon2asp.schedule.spec import Durations
from foon2asp.tree.tasktree import TaskTree, executable_order
from helpers import build, goal_id

needs_dot = pytest.mark.skipif(shutil.which("neato") is None, reason="Graphviz is not installed")


@pytest.fixture
def record():
    problem = build([("cut <&>", ["k"], ["a"]), ("cut <&>", ["k"], ["b"]), ("mix", ["a", "b"], ["g"])], ["k"])
    spec = ScheduleSpec((("arm", 1), ("human", 1)), Durations({"cut <&>": 2000, "mix": 1000}))
    tree = TaskTree(
        goal=goal_id(problem, "g"), method="given", status="optimal", units=executable_order(problem, [0, 1, 2])
    )
    return schedule(problem, tree, spec).to_dict()


def test_dot_places_one_box_per_unit_in_its_lane(record):
    src = gantt.gantt_graph(record).source
    boxes = re.findall(r'\bu\d+ \[label=(<[^>]*>|""|\S+) .*?fillcolor="([^"]+)".*?pos="([\d.]+),([\d.-]+)!"', src)
    assert len(boxes) == 3
    lanes = {e["agent"] for e in record["schedule"]}
    assert lanes == {"arm-1", "human-1"}
    colours = sorted(c for _, c, _, _ in boxes)
    assert colours == sorted([UNIT_FILL if e["agent"] == "arm-1" else HUMAN_FILL for e in record["schedule"]])
    assert "label=<cut &lt;&amp;&gt;>" in src  # labels are escaped
    # the two cuts run at once, in different lanes: same x, different y
    cuts = [(x, y) for label, _, x, y in boxes if "cut" in label]
    assert len(cuts) == 2 and cuts[0][0] == cuts[1][0] and cuts[0][1] != cuts[1][1]


@needs_dot
def test_every_format(record, tmp_path):
    svg = gantt.gantt_svg(record)
    assert svg.lstrip().startswith("<?xml") and ">arm&#45;1<" in svg and ">human&#45;1<" in svg and ">mix<" in svg
    for ext, magic in (("png", b"\x89PNG"), ("pdf", b"%PDF"), ("svg", b"<?xml")):
        path = gantt.draw_gantt(record, tmp_path / f"chart.{ext}")
        assert path.read_bytes().startswith(magic)
    both = report.render("schedule", "svg", [record, record])
    assert both.count(">mix<") == 2
    assert report.render_bytes("schedule", "png", [record]).startswith(b"\x89PNG")
    assert report.names("schedule") == ["dot", "svg", "png", "pdf", "html"]


def test_a_schedule_without_units_still_draws(record):
    empty = dict(record, schedule=[], status="unschedulable", makespan=None, baseline={})
    assert "unschedulable" in gantt.gantt_graph(empty).source


@pytest.fixture
def short_units():
    """A schedule with units far shorter than the others: too narrow for their labels."""
    chain = [("cut", ["k"], ["a"]), ("sprinkle", ["a"], ["b"]), ("stir", ["b"], ["c"]), ("pour", ["c"], ["d"])]
    rest = [("mix", ["d", "k"], ["g"]), ("chop", ["k"], ["e"]), ("fold", ["e", "g"], ["h"])]
    problem = build(chain + rest, ["k"])
    durations = {"cut": 8000, "sprinkle": 200, "stir": 300, "pour": 250, "mix": 6000, "chop": 100, "fold": 5000}
    spec = ScheduleSpec((("arm", 1), ("human", 1)), Durations(durations))
    units = executable_order(problem, list(range(7)))
    tree = TaskTree(goal=goal_id(problem, "h"), method="given", status="optimal", units=units)
    return schedule(problem, tree, spec).to_dict()


def test_every_box_has_a_label_inside_beside_or_under_it(short_units):
    src = gantt.gantt_graph(short_units).source
    where = {}
    for i, e in enumerate(short_units["schedule"]):
        motion = e["unit"]["motion"]
        box = re.search(rf"^\s*u{i} \[label=(<[^>]*>|\"\")", src, re.M)
        assert box, i
        if box.group(1) == f"<{motion}>":
            where[motion] = "in"
            continue
        side = re.search(rf'^\s*u{i}label \[label=<.*?<TD ALIGN="LEFT">([^<]*)</TD>.*? class="label (\w+)"', src, re.M)
        assert side, (i, motion)
        assert side.group(1) in (motion, f"^ {motion}")
        where[motion] = side.group(2)
    # chop (0.1 s) has the arm's lane free after it; sprinkle, stir and pour follow each other
    assert where == {
        "cut": "in",
        "mix": "in",
        "fold": "in",
        "chop": "beside",
        "sprinkle": "under",
        "stir": "under",
        "pour": "under",
    }


def test_charts_drawn_together_share_one_time_scale(record, short_units):
    src = gantt.charts([record, short_units]).source

    def x(node):
        return float(re.search(rf"^\s*{node} \[.*?pos=\"([\d.-]+),", src, re.M).group(1))

    assert x("s0_t1") - x("s0_t0") == x("s1_t1") - x("s1_t0")
    assert re.search(r"^\s*s0_t1 \[label=<(\S+)>", src, re.M).group(1) == re.search(
        r"^\s*s1_t1 \[label=<(\S+)>", src, re.M
    ).group(1)
