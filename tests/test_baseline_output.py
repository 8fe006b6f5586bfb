"""What the search baselines' trees look like in every output: text says INVALID and never None."""

from __future__ import annotations

import html
import json
import re
import shutil
import time

import pytest
from click.testing import CliRunner

from conftest import DEMO
from foon2asp.cli.main import main


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_text_of_an_invalid_greedy_tree_says_invalid():
    res = cli("solve", "--data", "demo", "--goal", "scrambled egg", "--method", "gbfs-h1")
    assert res.exit_code == 1  # an invalid tree
    lines = res.stdout.splitlines()
    assert lines[1] == "Method: gbfs-h1  Status: found  (units 4, success 0.1458, inputs 8, depth -)"
    assert lines[2] == (
        "INVALID: circular support: [egg, beaten, in [bowl]] is made by unit 8 (pour), which needs"
        " [egg, beaten, in [jar]]; [egg, beaten, in [jar]] is made by unit 9 (pour), which needs [egg, beaten, in [bowl]]"
    )
    assert "None" not in res.stdout
    valid = cli("solve", "--data", "demo", "--goal", "tomato salad", "--method", "gbfs-h1")
    assert valid.exit_code == 0 and "INVALID" not in valid.stdout and "None" not in valid.stdout


def test_text_and_json_agree_on_every_shared_goal(shared_foon_dir):
    for method in ("gbfs-h1", "gbfs-h2"):
        args = ("solve", "--data", shared_foon_dir, "--goals", "all", "--method", method)
        answers = json.loads(cli(*args, "--format", "json").stdout)
        text = cli(*args).stdout
        assert "None" not in text
        invalid = [a for a in answers if a.get("valid") is False]
        assert invalid  # the greedy trees for whipped cream and fried rice, at least
        assert text.count("\nINVALID: ") == len(invalid)
        for a in invalid:
            assert f"\nINVALID: {a['problem']}\n" in text


# ---------------------------------------------------------------- HTML pages

needs_dot = pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' is not installed")
TIME = re.compile(r'<p class="time">Time: ([\d.]+) s in all: solving ([\d.]+) s, drawing this page ([\d.]+) s \(')


def figures(page: str) -> dict[str, str]:
    """Each figure of an HTML page by its id."""
    return dict(re.findall(r'<figure [^>]*id="([^"]+)">(.*?)</figure>', page, re.S))


def node_classes(svg: str) -> list[str]:
    return re.findall(r'<g id="[^"]*" class="node ([^"]*)"', svg)


@needs_dot
def test_batch_summary_html_marks_invalid_trees_their_cycle_the_kitchen_and_the_goal(tmp_path):
    out = tmp_path / "r.jsonl"
    args = ("--goals", "all", "--methods", "asp,gbfs-h1", "--output", out, "--summary", "html", "--no-progress")
    res = cli("batch", "--data", "demo", *args)
    assert res.exit_code == 1  # the greedy trees for scrambled egg and whipped cream are invalid
    page = res.stdout
    heads = re.findall(r'<figure class="tree (\w+)" data-method="([^"]+)" data-units="(\d+)" id="(r\d)">', page)
    assert heads == [
        ("valid", "asp", "4", "r1"),
        ("valid", "gbfs-h1", "5", "r2"),
        ("valid", "asp", "4", "r3"),
        ("invalid", "gbfs-h1", "4", "r4"),
        ("invalid", "gbfs-h1", "3", "r5"),
    ]
    records = [json.loads(line) for line in out.read_text().splitlines()[1:]]
    invalid = [r for r in records if r.get("valid") is False and r["units"]]
    drawn = figures(page)
    for fig, record in zip(("r4", "r5"), invalid):
        assert "<b>INVALID</b>" in drawn[fig]
        assert f'<p class="problem">{html.escape(record["problem"], quote=True)}</p>' in drawn[fig]
        classes = node_classes(drawn[fig])
        assert sum("cycle" in c.split() for c in classes) == 4  # two objects and the two units making them
    for fig, svg in drawn.items():
        classes = [c.split() for c in node_classes(svg)]
        assert sum("goal" in c for c in classes) == 1, fig
        assert any("kitchen" in c for c in classes), fig
    assert "INVALID" not in drawn["r1"] + drawn["r2"] + drawn["r3"]


@needs_dot
def test_batch_summary_html_counts_the_time_spent_drawing(tmp_path, monkeypatch):
    from foon2asp.report import draw

    slow = draw.svg_text

    def svg_text(graph):
        time.sleep(0.2)
        return slow(graph)

    monkeypatch.setattr(draw, "svg_text", svg_text)
    out = tmp_path / "r.jsonl"
    args = ("--goals", "all", "--methods", "asp", "--output", out, "--summary", "html", "--no-progress")
    res = cli("batch", "--data", "demo", *args)
    assert res.exit_code == 0, res.output
    total, solving, drawing = map(float, TIME.search(res.stdout).groups())
    assert drawing >= 0.4  # two trees drawn, 0.2 s each
    assert solving < drawing and abs(total - solving - drawing) <= 0.011
    assert "with 1 worker(s)" in res.stdout.split("<table")[0]


@needs_dot
def test_compare_and_consolidate_pages_say_how_long_they_took():
    page = cli("compare", "--data", "demo", "--format", "html").stdout
    found = re.search(
        r'<p class="time">Time: ([\d.]+) s in all: solving ([\d.]+) s, drawing this page ([\d.]+) s'
        r" \(solving: each method&#x27;s times per goal, summed: ids [\d.]+ s, gbfs-h1 [\d.]+ s, gbfs-h2 [\d.]+ s,"
        r" asp optimum [\d.]+ s; loading the data is not counted\)\.</p>",
        page,
    )
    assert found
    smoothies = sorted(str(p) for p in (DEMO / "llm").glob("smoothie-*.json"))
    page = cli("consolidate", *smoothies, "--format", "html").stdout
    assert re.search(r'<p class="time">Time: [\d.]+ s in all: solving [\d.]+ s, drawing this page [\d.]+ s \(', page)
    assert '<a class="zoom" href="#c1">full size</a>' in page
