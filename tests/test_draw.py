"""Drawings of task trees (Graphviz) and the HTML report, checked in headless Chromium."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys

import pytest
from click.testing import CliRunner

from foon2asp.asp.options import AspOptions
from foon2asp.cli.main import main
from foon2asp.foon import goals
from foon2asp.methods.plan import session_of as Session
from foon2asp.report import draw
from test_pictures import CHROMIUM, chromium

needs_dot = pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' is not installed")


def cli(*args):
    return CliRunner().invoke(main, list(args))


def svg_nodes(svg: str) -> dict[str, int]:
    """Node counts of a Graphviz SVG by class (object, unit, goal, kitchen, cycle, human)."""
    counts: dict[str, int] = {}
    for cls in re.findall(r'<g id="[^"]*" class="node ([^"]*)"', svg):
        for c in cls.split():
            counts[c] = counts.get(c, 0) + 1
    return counts


def solve(problem_pair, label, method="asp"):
    data, problem = problem_pair
    from foon2asp import methods

    g = goals.resolve_label(data, problem, label)
    if method == "asp":
        return Session(problem, AspOptions(units=problem.units_for([g]))).solve(g)
    return methods.runner(method, problem, AspOptions())(g)


def test_dot_source_has_one_node_per_unit_and_object(shared_problem):
    _, problem = shared_problem
    tree = solve(shared_problem, "greek salad")
    graph = draw.trees_graph(problem, [tree])
    units = len(tree.units)
    objects = len({o for u in tree.units for o in problem.units[u].inputs + problem.units[u].outputs})
    assert units == 25
    src = graph.source
    assert len(re.findall(r"^\s*u\d+ \[", src, re.M)) == units
    assert len(re.findall(r"^\s*o\d+ \[", src, re.M)) == objects
    edges = sum(len(set(problem.units[u].inputs)) + len(set(problem.units[u].outputs)) for u in tree.units)
    assert len(re.findall(r"^\s*[ou]\d+ -> [ou]\d+", src, re.M)) == edges


@needs_dot
def test_svg_of_every_reachable_goal(shared_foon_dir, shared_problem, tmp_path):
    _, problem = shared_problem
    res = cli("solve", "--data", str(shared_foon_dir), "--goals", "all", "--format", "svg", "--output", str(tmp_path))
    assert res.exit_code == 0, res.output
    jsonres = cli("solve", "--data", str(shared_foon_dir), "--goals", "all", "--format", "json")
    import json

    results = json.loads(jsonres.output)
    files = sorted(tmp_path.glob("*.svg"))
    assert len(files) == 25
    for f, r in zip(files, results):
        counts = svg_nodes(f.read_text())
        units = [tuple(o.values()) for u in r["units"] for o in u["inputs"] + u["outputs"]]
        distinct = len(
            {
                (o["label"], tuple(o["states"]), tuple(o["ingredients"]), o["container"])
                for u in r["units"]
                for o in u["inputs"] + u["outputs"]
            }
        )
        assert counts.get("unit", 0) == len(r["units"]), f
        assert counts.get("object", 0) == distinct, f
        if r["units"]:
            assert counts["goal"] == 1 and counts.get("kitchen", 0) >= 1 and "cycle" not in counts
        del units


@needs_dot
def test_invalid_tree_shows_its_cycle_in_red(shared_foon_dir, tmp_path):
    out = tmp_path / "wc.txt"
    out.write_text(
        cli(
            "solve",
            "--data",
            str(shared_foon_dir),
            "--goal",
            "whipped cream",
            "--method",
            "gbfs-h1",
            "--format",
            "foon",
        ).output
    )
    svg = tmp_path / "wc.svg"
    res = cli("draw", str(out), "--data", str(shared_foon_dir), "-o", str(svg))
    assert res.exit_code == 0, res.output
    text = svg.read_text()
    counts = svg_nodes(text)
    assert counts["unit"] == 10 and counts["cycle"] == 4  # two objects and two units (stir, pour)
    assert "circular support" in text and "INVALID" in text
    assert text.count('stroke="#cc0000"') >= 8  # the red nodes and edges
    # without --data: the same nodes, nothing judged
    plain = tmp_path / "plain.svg"
    assert cli("draw", str(out), "-o", str(plain)).exit_code == 0
    assert svg_nodes(plain.read_text()).get("cycle") is None
    assert svg_nodes(plain.read_text())["unit"] == 10


@needs_dot
def test_draw_reads_every_tree_format_and_writes_png_pdf(shared_foon_dir, tmp_path):
    base = ["solve", "--data", str(shared_foon_dir), "--goal", "macaroni"]
    for fmt in ("foon", "foon-plain", "foon-json", "json"):
        src = tmp_path / f"t.{fmt}"
        src.write_text(cli(*base, "--format", fmt).output)
        svg = tmp_path / f"{fmt}.svg"
        assert cli("draw", str(src), "-o", str(svg)).exit_code == 0
        assert svg_nodes(svg.read_text())["unit"] == 5
    for ext, magic in (("png", b"\x89PNG"), ("pdf", b"%PDF")):
        pic = tmp_path / f"m.{ext}"
        assert cli("draw", str(tmp_path / "t.foon"), "-o", str(pic)).exit_code == 0
        assert pic.read_bytes()[:4] == magic
    res = cli(*base, "--format", "png", "--output", str(tmp_path / "pngs"))
    assert res.exit_code == 0 and (tmp_path / "pngs" / "001-macaroni.png").read_bytes()[:4] == b"\x89PNG"
    bad = cli("draw", str(tmp_path / "t.foon"), "-o", str(tmp_path / "m.jpg"))
    assert bad.exit_code == 2 and "cannot tell the drawing format" in bad.output


def test_missing_dot_is_one_line(shared_foon_dir, tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))
    res = subprocess.run(
        [sys.executable, "-m", "foon2asp", "solve", "--data", str(shared_foon_dir), "--goal", "ice", "--format", "svg"],
        capture_output=True,
        text=True,
    )
    assert res.returncode == 2
    assert res.stderr.strip().splitlines() == [
        "foon2asp: error: Graphviz 'dot' is not installed: install it (Debian: apt-get install graphviz) to draw task trees"
    ]
    dot = cli("solve", "--data", str(shared_foon_dir), "--goal", "ice", "--format", "dot")
    assert dot.exit_code == 0 and dot.output.startswith("digraph")


@needs_dot
def test_library_functions(demo_problem, tmp_path):
    data, problem = demo_problem
    g = goals.resolve_label(data, problem, "scrambled egg")
    tree = Session(problem, AspOptions()).solve(g)
    svg = draw.tree_svg(problem, tree)
    assert svg_nodes(svg)["unit"] == 4
    path = draw.draw_tree(problem, tree, tmp_path / "egg.pdf")
    assert path.read_bytes()[:4] == b"%PDF"


@needs_dot
def test_human_steps_are_marked(demo_problem):
    data, problem = demo_problem
    g = goals.resolve_label(data, problem, "tomato salad")
    tree = Session(problem, AspOptions(objective=("success",), human_steps=1)).solve(g)
    assert tree.human_steps
    counts = svg_nodes(draw.tree_svg(problem, tree))
    assert counts["human"] == len(tree.human_steps)


@pytest.fixture(scope="module")
def html_report(shared_foon_dir, tmp_path_factory):
    if shutil.which("dot") is None:
        pytest.skip("Graphviz 'dot' is not installed")
    res = cli("compare", "--data", str(shared_foon_dir), "--format", "html")
    assert res.exit_code == 1, res.output  # some greedy trees are invalid: exit 1
    path = tmp_path_factory.mktemp("report") / "report.html"
    path.write_text(res.output, encoding="utf-8")
    return path


def test_html_report_has_the_table_and_every_drawing(html_report, shared_foon_dir):
    text = html_report.read_text()
    assert text.count('<tr><td><a href="#goal-') == 25
    figures = re.findall(
        r'<figure class="tree (valid|invalid)" data-method="([^"]+)" data-units="(\d+)" id="[^"]+">', text
    )
    csv = cli("compare", "--data", str(shared_foon_dir), "--format", "csv").output.splitlines()[1:]
    with_tree = [
        line
        for line in csv
        if line.split(",")[-6:-5] != [""] and ",not-found," not in line and ",unreachable," not in line
    ]
    assert len(figures) == len(with_tree) == 96
    assert text.count("<svg") == 96
    assert sum(1 for f in figures if f[0] == "invalid") == 16  # 10 gbfs-h1 + 6 gbfs-h2
    assert "<script" not in text and "http" not in text.split("<body>")[1].split("<svg")[0]


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium installed")
def test_html_report_in_headless_chromium(html_report, tmp_path):
    def browse(path):
        res = chromium(tmp_path, "--enable-logging=stderr", "--v=0", "--dump-dom", path.as_uri(), timeout=180)
        return res.stdout, [line for line in res.stderr.splitlines() if ":CONSOLE" in line]

    # the console check can fail: a page that logs an error is caught
    bad = tmp_path / "bad.html"
    bad.write_text('<html><body><script>console.error("broken")</script></body></html>')
    assert any("broken" in line for line in browse(bad)[1])
    dom, console = browse(html_report)
    assert console == []
    assert dom.count('<tr><td><a href="#goal-') == 25
    assert len(re.findall(r"<svg\b", dom)) == 96
    assert 'id="units"' in dom


@needs_dot
def test_batch_summary_html(tmp_path):
    out = tmp_path / "r.jsonl"
    res = cli(
        "batch",
        "--data",
        "demo",
        "--goals",
        "all",
        "--methods",
        "asp,gbfs-h1",
        "--output",
        str(out),
        "--summary",
        "html",
        "--no-progress",
    )
    assert res.exit_code == 1, res.output  # the greedy scrambled egg tree is invalid: exit 1
    from foon2asp.batch.results_file import read_results

    records = read_results(out)
    with_tree = [r for r in records if r["status"] in ("optimal", "found") and r["units"]]
    text = res.output
    assert '<table id="summary">' in text
    assert text.count("<svg") == len(with_tree) == 5
    units = sorted(int(u) for u in re.findall(r'data-units="(\d+)"', text))
    assert units == sorted(len(r["units"]) for r in with_tree)


@needs_dot
def test_huge_labels_are_clipped_and_drawn(tmp_path):
    # a generated tree whose texts exceed Graphviz's 16,384-character strings is still drawn
    import json

    long = "x" * 990
    unit = {
        "input_nodes": [{"label": f"{long}{i}", "states": [f"s{j}" for j in range(200)]} for i in range(20)],
        "motion_node": "peel",
        "output_nodes": [{"label": "banana", "states": ["peeled"]}],
    }
    src = tmp_path / "long.json"
    src.write_text(json.dumps([unit]))
    out = tmp_path / "long.svg"
    res = subprocess.run(
        [sys.executable, "-m", "foon2asp", "draw", str(src), "-o", str(out)], capture_output=True, text=True
    )
    assert res.returncode == 0, res.stderr
    assert "Error" not in res.stderr
    counts = svg_nodes(out.read_text())
    assert counts["unit"] == 1 and counts["object"] == 21
    assert "188 more states" in out.read_text()
