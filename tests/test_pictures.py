"""Pictures in HTML pages, measured in headless Chromium: readable text, the page's width, full size
on demand, one time scale for the Gantt charts of a page."""

from __future__ import annotations

import html
import json
import re
import shutil
import subprocess

import pytest
from click.testing import CliRunner

from foon2asp.cli.main import main

CHROMIUM = next((shutil.which(b) for b in ("chromium", "chromium-browser", "google-chrome") if shutil.which(b)), None)
needs_dot = pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' is not installed")
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="no Chromium installed (chromium, chromium-browser)")

#: the browser window of the measurements (CSS pixels)
WIDTH = 1400

#: what the measuring script reports: the page's content width, and per figure its width, its
#: drawing's width, viewBox width, the rendered size (px) of the text of its first node (units
#: and objects are drawn at 10 points) and of its smallest text, its scrolling and visible
#: widths and whether it is the one the URL's fragment targets; for a Gantt chart also the x (px)
#: of its first two time ticks (nodes t0, t1) and the second's seconds
MEASURE = """<script>
function centre(svg, name) {
  for (const g of svg.querySelectorAll('g.node')) {
    const title = g.querySelector('title');
    if (title && title.textContent === name) {
      const r = g.querySelector('text').getBoundingClientRect();
      return r.left + r.width / 2;
    }
  }
  return null;
}
function label(svg, name) {
  for (const g of svg.querySelectorAll('g.node')) {
    const title = g.querySelector('title');
    if (title && title.textContent === name) return g.querySelector('text').textContent;
  }
  return null;
}
function measure() {
  const out = {content: document.body.clientWidth, figures: []};
  for (const f of document.querySelectorAll('figure.tree')) {
    const svg = f.querySelector('svg');
    if (!svg) continue;
    const text = svg.querySelector('g.node text');
    out.figures.push({
      id: f.id, units: f.dataset.units ? parseInt(f.dataset.units) : null, target: f.matches(':target'),
      figure: f.getBoundingClientRect().width, svg: svg.getBoundingClientRect().width,
      viewbox: svg.viewBox.baseVal.width,
      font: parseFloat(text.getAttribute('font-size')) * text.getScreenCTM().a,
      tick0: centre(svg, 't0'), tick1: centre(svg, 't1'), step: label(svg, 't1'),
      zoom: !!f.querySelector('a.zoom[href="#' + f.id + '"]'),
      min_font: Math.min(...Array.from(svg.querySelectorAll('text'),
        t => parseFloat(t.getAttribute('font-size')) * t.getScreenCTM().a)),
      scroll: f.scrollWidth, client: f.clientWidth,
    });
  }
  const pre = document.createElement('pre');
  pre.id = 'measured';
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
}
window.addEventListener('load', () => setTimeout(measure, 0));
</script>"""


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def chromium(tmp_path, *args: str, timeout: int) -> subprocess.CompletedProcess:
    """Run headless Chromium with ``args`` and a fresh profile under ``tmp_path``."""
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"]
    flags += ["--disable-component-update", "--disable-sync", f"--user-data-dir={tmp_path / 'profile'}"]
    return subprocess.run([CHROMIUM, *flags, *args], capture_output=True, text=True, timeout=timeout)


def measure(page: str, tmp_path, fragment: str = "") -> dict:
    """Open ``page`` (HTML text) in headless Chromium, WIDTH px wide, and measure its figures."""
    path = tmp_path / "measured.html"
    path.write_text(page.replace("</body>", MEASURE + "</body>"), encoding="utf-8")
    args = ["--hide-scrollbars", f"--window-size={WIDTH},1000", "--virtual-time-budget=10000"]
    res = chromium(tmp_path, *args, "--dump-dom", path.as_uri() + fragment, timeout=300)
    found = re.search(r'<pre id="measured">(.*?)</pre>', res.stdout, re.S)
    assert found, res.stderr[-2000:]
    return json.loads(html.unescape(found.group(1)))


@pytest.fixture(scope="module")
def compare_page(shared_foon_dir):
    if shutil.which("dot") is None:
        pytest.skip("Graphviz 'dot' is not installed")
    res = cli("compare", "--data", shared_foon_dir, "--format", "html")
    assert res.exit_code == 1, res.output  # some greedy trees are invalid
    return res.stdout


def test_every_drawing_can_be_opened_full_size(compare_page):
    assert "48em" not in compare_page
    figures = re.findall(r'<figure class="tree (?:valid|invalid)"[^>]* id="([^"]+)">', compare_page)
    assert len(figures) == 96
    for fig in figures:
        assert f'<a class="zoom" href="#{fig}">full size</a>' in compare_page


@needs_chromium
def test_a_30_unit_tree_is_readable_at_1400_px(compare_page, tmp_path):
    got = measure(compare_page, tmp_path)
    figures = got["figures"]
    assert len(figures) == 96 and all(f["zoom"] for f in figures)
    thirty = [f for f in figures if f["units"] == 30]
    assert thirty  # gbfs-h2's carrot salad, the optimum of french toast, ...
    for f in figures:
        # text at least 8 px high, and no drawing wider than the page unless it scrolls in its frame
        assert f["font"] >= 8.0, f
        assert f["figure"] <= got["content"] + 1, f
    for f in thirty:
        # a drawing wider than the page takes the page's whole width
        assert f["viewbox"] * 4 / 3 > got["content"]
        assert abs(f["figure"] - got["content"]) <= 1, f
    small = [f for f in figures if f["viewbox"] * 4 / 3 < got["content"] / 2]
    assert small and all(abs(f["svg"] - f["viewbox"] * 4 / 3) <= 1 for f in small)  # drawn at their own size


@needs_chromium
def test_full_size_shows_the_drawing_at_its_natural_size(compare_page, tmp_path):
    fig = re.findall(
        r'<figure class="tree (?:valid|invalid)" data-method="[^"]+" data-units="30" id="([^"]+)">', compare_page
    )[0]
    got = measure(compare_page, tmp_path, f"#{fig}")
    (target,) = [f for f in got["figures"] if f["target"]]
    assert target["id"] == fig
    assert abs(target["svg"] - target["viewbox"] * 4 / 3) <= 1  # 1 point = 4/3 px
    assert abs(target["font"] - 10 * 4 / 3) < 0.05


@pytest.fixture(scope="module")
def schedule_page(shared_foon_dir):
    if shutil.which("dot") is None:
        pytest.skip("Graphviz 'dot' is not installed")
    goals = ("greek salad", "macaroni", "ice")
    args = [a for g in goals for a in ("--goal", g)]
    res = cli("schedule", "--data", shared_foon_dir, *args, "--agents", "arm=2,human=1", "--format", "html")
    assert res.exit_code == 0, res.output
    return res.stdout


@needs_chromium
def test_the_gantt_charts_of_a_page_share_one_time_scale_across_its_width(schedule_page, tmp_path):
    got = measure(schedule_page, tmp_path)
    charts = got["figures"]
    assert len(charts) == 3
    makespans = [float(m) for m in re.findall(r"makespan ([\d.]+) s \(list", schedule_page)]
    assert len(set(makespans)) == 3  # three different lengths ...
    per_second = [(c["tick1"] - c["tick0"]) / float(c["step"]) for c in charts]
    assert max(per_second) - min(per_second) < 0.5  # ... on one scale (px per second between two ticks)
    for c in charts:
        assert abs(c["figure"] - got["content"]) <= 1  # the page's width ...
        assert c["figure"] - 16 <= c["svg"] <= c["figure"]  # ... less the frame's border and padding
    # the longest schedule fills the width: its time axis spans most of the page
    assert max(makespans) * per_second[0] > 0.8 * got["content"]


@needs_chromium
def test_every_text_of_a_gantt_chart_is_8_px_and_a_chart_that_fits_does_not_scroll(schedule_page, tmp_path):
    short = cli(
        "schedule", "--data", "demo", "--goal", "scrambled egg", "--agents", "arm=2,human=1", "--format", "html"
    )
    for page in (schedule_page, short.stdout):
        got = measure(page, tmp_path)
        assert got["figures"]
        for c in got["figures"]:
            assert c["min_font"] >= 8.0, c  # box labels, the labels beside and under boxes, the axis, the legend
            assert c["scroll"] <= c["client"], c  # no horizontal scrollbar: the chart fits the page


@needs_chromium
def test_a_gantt_chart_narrower_than_its_8_px_scale_scrolls_in_its_frame(schedule_page, tmp_path):
    path = tmp_path / "narrow.html"
    path.write_text(schedule_page.replace("</body>", MEASURE + "</body>"), encoding="utf-8")
    args = ["--hide-scrollbars", "--window-size=900,1000", "--virtual-time-budget=10000"]
    res = chromium(tmp_path, *args, "--dump-dom", path.as_uri(), timeout=300)
    got = json.loads(html.unescape(re.search(r'<pre id="measured">(.*?)</pre>', res.stdout, re.S).group(1)))
    for c in got["figures"]:
        assert c["min_font"] >= 8.0 and c["scroll"] > c["client"], c
