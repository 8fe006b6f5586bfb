"""The explorer (foon2asp explore) on ../shared/foon: the server as the command starts it, its
one-line errors, its limits, 1,000 random requests, and the page in a real browser (Playwright
driving the system Chromium), whose screenshots are docs/explore.md's pictures."""

from __future__ import annotations

import json
import os
import random
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from urllib.parse import urlencode

import pytest

from conftest import REPO

CHROMIUM = os.environ.get("FOON2ASP_CHROMIUM", "/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
DOCS = REPO / "docs"
#: an optimal tree proven by clingo's search or by its landmarks (the bounds route)
PROVEN_OPTIMAL = ("optimal (proven by clingo)", "optimal (proven by bounds)")
#: the schedule's tables the server is started with (data/schedule/)
SCHEDULE_TABLES = ("durations", "capabilities", "resources")
#: a rule whose search clingo cannot finish soon: 11 pigeons in 10 holes
PIGEONS = "h(1..11). p(1..10). 1 { at(H,P) : p(P) } 1 :- h(H). :- at(H1,P), at(H2,P), H1 < H2."


def _missing_extra() -> str | None:
    for name in ("starlette", "uvicorn", "httpx2"):
        try:
            __import__(name)
        except ImportError:
            return f"the 'explore' extra is not installed ({name}): pip install 'foon2asp[explore]' httpx2"
    return None


def _no_browser() -> str | None:
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "Playwright is not installed (pip install playwright)"
    if not Path(CHROMIUM).is_file():
        return f"no Chromium at {CHROMIUM} (Debian: apt-get install chromium)"
    if shutil.which("dot") is None:
        return "Graphviz 'dot' is not installed"
    return None


needs_extra = pytest.mark.skipif(_missing_extra() is not None, reason=str(_missing_extra()))
needs_browser = pytest.mark.skipif(_no_browser() is not None, reason=str(_no_browser()))


def cli(*args: str, timeout: float = 120, **kw) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "foon2asp", *args], capture_output=True, text=True, timeout=timeout, **kw
    )


# ---------------------------------------------------------------- starting it


def test_without_the_extra_the_command_says_how_to_install_it(tmp_path):
    """Starlette and uvicorn hidden from the import system: exit status 2 and one line."""
    script = "import sys; sys.modules['uvicorn'] = None; sys.modules['starlette'] = None\n"
    script += "from foon2asp.cli.main import run; run()"
    res = subprocess.run(
        [sys.executable, "-c", script, "explore", "--data", "demo"], capture_output=True, text=True, timeout=60
    )
    assert res.returncode == 2, res.stderr
    assert res.stderr == (
        "foon2asp: error: the explorer needs the 'explore' extra (Starlette and uvicorn):"
        " pip install 'foon2asp[explore]'\n"
    )


@needs_extra
def test_a_host_other_than_loopback_is_warned_about_and_a_busy_port_is_one_line():
    with socket.socket() as busy:
        busy.bind(("0.0.0.0", 0))
        busy.listen(1)
        port = busy.getsockname()[1]
        res = cli("explore", "--data", "demo", "--host", "0.0.0.0", "--port", str(port), timeout=60)
    assert res.returncode == 2, res.stderr
    warning, error = res.stderr.splitlines()
    assert warning.startswith("foon2asp: warning: listening on 0.0.0.0: anyone who can reach this machine")
    assert error == f"foon2asp: error: cannot listen on 0.0.0.0 port {port}: Address already in use"
    assert "Traceback" not in res.stderr


@needs_extra
def test_open_opens_the_printed_address_in_the_browser(tmp_path):
    opener = tmp_path / "opener"
    opener.write_text('#!/bin/sh\necho "$1" > "$(dirname "$0")/opened"\n')
    opener.chmod(0o755)
    env = dict(os.environ, BROWSER=f"{opener} %s")
    proc = subprocess.Popen(
        [sys.executable, "-m", "foon2asp", "explore", "--data", "demo", "--open"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=REPO,
    )
    try:
        line = proc.stdout.readline() if proc.stdout else ""
        url = re.match(r"foon2asp explore: (http://127\.0\.0\.1:\d+/) \(Ctrl\+C stops it\)$", line.strip())
        assert url is not None, line
        opened = tmp_path / "opened"
        deadline = time.monotonic() + 30
        while not (opened.exists() and opened.read_text().strip()) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert opened.read_text().strip() == url.group(1)
    finally:
        proc.terminate()
        proc.wait(timeout=30)


def _children(pid: int) -> set[int]:
    return {int(p) for task in Path(f"/proc/{pid}/task").iterdir() for p in (task / "children").read_text().split()}


@needs_extra
@pytest.mark.parametrize(
    "signals, code, said", [((signal.SIGTERM,), 143, "terminated"), ((signal.SIGINT,) * 2, 130, "interrupted")]
)
def test_a_signal_stops_the_server_and_its_workers_in_one_line(signals, code, said):
    proc = subprocess.Popen(
        [sys.executable, "-m", "foon2asp", "explore", "--data", "demo"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=REPO,
    )
    assert proc.stdout is not None and proc.stdout.readline().startswith("foon2asp explore: http://127.0.0.1:")
    workers = _children(proc.pid)
    assert len(workers) == 2
    for sig in signals:  # Ctrl+C twice, or what timeout(1) sends: the process and then its group
        proc.send_signal(sig)
    assert proc.wait(timeout=30) == code
    assert proc.stderr is not None and proc.stderr.read() == f"foon2asp: {said}\n"
    deadline = time.monotonic() + 5  # killed; reaped once the server is gone
    while any(Path(f"/proc/{pid}").exists() for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(Path(f"/proc/{pid}").exists() for pid in workers)


@needs_extra
def test_a_bad_data_folder_is_one_line_before_anything_is_served(tmp_path):
    res = cli("explore", "--data", str(tmp_path / "nowhere"), timeout=60)
    assert res.returncode == 2
    assert res.stderr.startswith("foon2asp: error: ") and len(res.stderr.splitlines()) == 1, res.stderr


class Server:
    """``foon2asp explore --data ../shared/foon`` in a process of its own."""

    def __init__(self, data: Path, *args: str) -> None:
        self.log = tempfile.TemporaryFile("w+", encoding="utf-8")  # the server's stderr
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "foon2asp", "explore", "--data", str(data), *args],
            stdout=subprocess.PIPE,
            stderr=self.log,
            text=True,
        )
        line = self.proc.stdout.readline() if self.proc.stdout else ""
        found = re.match(r"foon2asp explore: (http://127\.0\.0\.1:\d+/) \(Ctrl\+C stops it\)$", line.strip())
        if found is None:
            self.stop()
            raise AssertionError(f"no address: {line!r} {self.errors()}")
        self.url = found.group(1)

    def errors(self) -> str:
        self.log.seek(0)
        return self.log.read()

    def workers(self) -> set[int]:
        """The ids of the server's child processes."""
        return _children(self.proc.pid)

    def memory(self, settled: bool = False) -> int:
        """The resident memory (kB) of the server and its workers (``settled``: once a worker
        replaced after the last answer has started)."""
        if settled:
            time.sleep(2.0)
        total = 0
        for pid in {self.proc.pid, *self.workers()}:
            with open(f"/proc/{pid}/status", encoding="utf-8") as status:
                total += next(int(line.split()[1]) for line in status if line.startswith("VmRSS:"))
        return total

    def stop(self) -> None:
        self.proc.terminate()
        try:
            self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.proc.kill()


@pytest.fixture(scope="module")
def server(shared_foon_dir):
    if _missing_extra():
        pytest.skip(_missing_extra())
    tables = [(f"--{name}", str(REPO / "data" / "schedule" / f"{name}.json")) for name in SCHEDULE_TABLES]
    # the tables name the kinds arm and human: the agents have both (a kind no agent has is an error)
    running = Server(shared_foon_dir, "--agents", "arm=2,human=1", *(a for pair in tables for a in pair))
    yield running
    running.stop()
    assert running.proc.returncode in (0, 143), running.errors()
    assert "Traceback" not in running.errors(), running.errors()


@pytest.fixture(scope="module")
def http(server):
    import httpx2 as httpx

    with httpx.Client(base_url=server.url, timeout=120) as client:
        yield client


def error_of(response) -> str:
    body = response.json()
    assert set(body) == {"error"}, body
    assert "\n" not in body["error"] and "Traceback" not in body["error"]
    return body["error"]


# ---------------------------------------------------------------- answers and errors over HTTP


def test_an_unknown_goal_and_a_bad_rule_are_the_command_lines_one_line_errors(http, shared_foon_dir):
    for goal, rule in [("scrambld eg", None), ("macaroni", ":- use(U), motion(U,"), ("#99999", None)]:
        args = ["solve", "--data", str(shared_foon_dir), "--goal", goal] + (["--rule", rule] if rule else [])
        res = cli(*args)
        assert res.returncode == 2
        expected = res.stderr.strip().removeprefix("foon2asp: error: ")
        asked = http.get("/api/tree", params={"goal": goal, **({"rule": rule} if rule else {})})
        assert asked.status_code == 400
        assert error_of(asked) == expected


def test_the_page_is_served_with_what_it_offers(http):
    page = http.get("/?goal=ice&forbid-motion=pour")
    assert page.status_code == 200 and page.headers["content-type"].startswith("text/html")
    offer = json.loads(re.search(r'<script id="info" type="application/json">(.*?)</script>', page.text).group(1))
    assert offer["objectives"] == ["units", "success", "inputs", "depth"]  # no motion costs: no 'cost'
    assert len(offer["goals"]) == 25 and offer["baselines"] == ["ids", "gbfs-h1", "gbfs-h2"]
    for name in ("explore.js", "explore.css"):
        assert http.get(f"/static/{name}").status_code == 200
    assert http.get("/", headers={"host": "evil.example"}).status_code == 400  # a rebound name is refused


def test_suggestions_match_as_goal_does(http):
    found = http.get("/api/suggest", params={"q": "scrambled egg"}).json()
    assert found["count"] == 15 and all(o["label"] == "scrambled egg" for o in found["objects"])
    assert found["objects"][0]["made"] > 0  # made objects first
    assert http.get("/api/suggest", params={"q": ""}).json()["count"] == 25  # the goals file
    assert error_of(http.get("/api/suggest", params={"q": "scrambld"})).startswith(
        "no object matches 'scrambld'; closest labels: scrambled egg"
    )


def test_answers_of_the_page(http):
    cached = http.get("/api/status").json()["cached"]
    t0 = time.monotonic()
    tree = http.get("/api/tree", params={"goal": "greek salad"}).json()
    first = time.monotonic() - t0
    t0 = time.monotonic()
    assert (
        http.get("/api/tree", params={"goal": "greek salad", "objective": "units"}).json() == tree
    )  # the same question
    assert time.monotonic() - t0 < first and http.get("/api/status").json()["cached"] == cached + 1
    assert (tree["status"], tree["proven_by"], tree["cost"]["units"], len(tree["steps"])) == (
        "optimal",
        "clingo",
        25,
        25,
    )
    assert tree["svg"].startswith("<svg") and "mixing bowl, empty" in [k["text"] for k in tree["part"]["kitchen"]]
    bowl = {"goal": "greek salad", "without": "mixing bowl, empty"}
    assert http.get("/api/tree", params=bowl).json()["status"] == "unreachable"
    assert http.get("/api/missing", params=bowl).json() == {"status": "optimal", "items": ["mixing bowl, empty"]}
    side = http.get("/api/baselines", params={"goal": "greek salad"}).json()
    by = {m["method"]: m for m in side["methods"]}
    assert by["gbfs-h1"]["distance"]["units"] == 10 and by["gbfs-h1"]["valid"] is True
    assert len(by["gbfs-h1"]["differs"]) >= 10 and side["optimum"]["cost"]["units"] == 25
    plan = http.get("/api/schedule", params={"goal": "greek salad", "agents": "arm=2,human=1"}).json()
    assert (plan["status"], plan["makespan"], plan["baseline"]) == ("optimal", 60.0, 71.0)  # as docs/api.md has it
    assert plan["agents"] == ["arm-1", "arm-2", "human-1"]
    assert sorted(r["step"] for r in plan["rows"]) == list(range(1, 26))
    # the tables name a person's durations: agents without a person are one line naming the kind
    alone = http.get("/api/schedule", params={"goal": "greek salad", "agents": "arm=2"})
    assert alone.status_code == 400 and 'no agent has the kind "human"' in error_of(alone)
    assert error_of(http.get("/api/export/pddl-domain", params={"goal": "ice", "rule": "a."})).startswith(
        "--rule cannot be exported to PDDL"
    )


def test_two_pages_asking_at_once_get_their_own_answers(http):
    goals = ["greek salad", "macaroni", "ice", "sweet potato"] * 2
    got: dict[int, dict] = {}

    def ask(k: int) -> None:
        got[k] = http.get("/api/tree", params={"goal": goals[k], "time-limit": str(5 + k)}).json()

    threads = [threading.Thread(target=ask, args=(k,)) for k in range(len(goals))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert [got[k]["goal"]["label"] for k in range(len(goals))] == goals


def test_a_long_solve_honours_the_time_limit(http):
    """Answered unproven at the limit, or stopped past twice the limit and 5 s (the library's check of
    the rules against the only tree takes no time limit)."""
    t0 = time.monotonic()
    asked = http.get("/api/tree", params={"goal": "macaroni", "rule": PIGEONS, "time-limit": "1"})
    took = time.monotonic() - t0
    if asked.status_code == 200:
        assert asked.json()["status"] in ("unknown", "feasible")
    else:
        assert asked.status_code == 504 and error_of(asked) == "no answer within 7 s: stopped (time-limit 1 s)"
    assert took < 7 + 3
    assert http.get("/api/tree", params={"goal": "ice"}).json()["status"] == "optimal"  # a worker answers


def _random_text(rng: random.Random, longest: int) -> str:
    alphabet = "abcdefghij egg salad,[]{}#%&=+?/\\\"'():-.\t\n\x00\x7f\u2028\ud7ff\u00e9\u4e2d\U0001f600"
    return "".join(rng.choice(alphabet) for _ in range(rng.randint(0, longest)))


def _random_request(rng: random.Random, goals: list[str], motions: list[str]) -> str:
    """A request a careless or hostile page could send: bad goals, bad rules, huge inputs, unknown
    parameters and paths, bad numbers; one in ten a fair question."""
    kind = rng.randrange(10)
    if kind == 0:
        params = [("goal", rng.choice(goals[:4])), ("objective", rng.choice(["units", "success,units"]))]
        params += [("forbid-motion", m) for m in rng.sample(motions, rng.randint(0, 1))]
        return "/api/tree?" + urlencode(params)
    if kind == 1:
        return "/api/tree?" + urlencode({"goal": _random_text(rng, 60)})
    if kind == 2:
        rule = rng.choice(
            [
                _random_text(rng, 80),
                ":- use(U), motoin(U," + _random_text(rng, 5),
                '#script (python)\nimport os\nos.system("true")\n#end.',
                '#include "/etc/passwd".',
                "p(X) :- X = 1..3. :- not q.",
                ":- use(U)." * rng.choice([1, 300]),
            ]
        )
        return "/api/tree?" + urlencode({"goal": rng.choice(goals[:4]), "rule": rule})
    if kind == 3:
        return "/api/tree?" + urlencode({"goal": "x" * rng.choice([2_000, 20_000, 200_000])})
    if kind == 4:
        key = rng.choice(["gaol", "max-units", "time-limit", "human-steps", "objective", "agents", "forbid-motion"])
        value = rng.choice(
            ["-1", "1e999", "nan", "0", "99999999999", "units,units", "fly", "arm=0", _random_text(rng, 20)]
        )
        return "/api/tree?" + urlencode([("goal", rng.choice(goals[:4])), (key, value), (key, value)])
    if kind == 5:
        return (
            rng.choice(["/api/nothing", "/api/export/exe", "/static/../../etc/passwd", "/%00", "/api/"]) + "?goal=ice"
        )
    if kind == 6:
        return "/api/suggest?" + urlencode({"q": _random_text(rng, 40)})
    if kind == 7:
        return (
            "/api/export/"
            + rng.choice(["foon", "json", "pddl-problem"])
            + "?"
            + urlencode({"goal": _random_text(rng, 12)})
        )
    if kind == 8:
        return "/?" + urlencode({"goal": _random_text(rng, 100), "rule": _random_text(rng, 100)})
    return "/api/" + rng.choice(["baselines", "schedule"]) + "?" + urlencode({"goal": _random_text(rng, 15)})


class _Raw:
    """A response read with the standard library (httpx refuses addresses over 64 KiB)."""

    def __init__(self, status: int, headers: dict, text: str) -> None:
        self.status_code, self.headers, self.text = status, headers, text

    def json(self):
        return json.loads(self.text)


def _raw_get(base: str, target: str) -> _Raw:
    import http.client
    from urllib.parse import urlsplit

    where = urlsplit(base)
    conn = http.client.HTTPConnection(where.hostname, where.port, timeout=60)
    try:
        conn.request("GET", target)
        got = conn.getresponse()
        headers = {k.lower(): v for k, v in got.getheaders()}
        return _Raw(got.status, headers, got.read().decode("utf-8", "replace"))
    finally:
        conn.close()


def _judge(response) -> str:
    """What a response is: ``page``, ``answer`` or ``error``; anything else fails the test."""
    text = response.text
    assert "Traceback" not in text and "internal error" not in text, text[:500]
    kind = response.headers.get("content-type", "")
    if response.status_code == 200:
        if kind.startswith("text/html"):
            assert "<h1>foon2asp explore</h1>" in text
            return "page"
        return "answer"
    if kind.startswith("application/json"):
        error_of(response)
    else:
        assert len(text.strip().splitlines()) == 1, text[:500]
    return "error"


def test_a_thousand_random_requests_leave_it_alive_its_memory_flat(server, http):
    rng = random.Random(50)
    offer = json.loads(re.search(r'id="info" type="application/json">(.*?)</script>', http.get("/").text).group(1))
    goals = ["greek salad", "ice", "macaroni", "sweet potato"] + [g["text"] for g in offer["goals"]]
    motions = ["boil", "pour", "mix"]
    seen: dict[str, int] = {}
    before = 0
    for k in range(1000):
        if k == 10:
            before = server.memory(settled=True)
        target = _random_request(rng, goals, motions)
        response = http.get(target) if len(target) < 60_000 else _raw_get(server.url, target)
        kind = _judge(response)
        seen[kind] = seen.get(kind, 0) + 1
    after = server.memory(settled=True)
    assert seen["error"] > 500 and seen["answer"] > 100 and seen["page"] > 50, seen
    assert http.get("/api/tree", params={"goal": "greek salad"}).json()["cost"]["units"] == 25  # alive
    assert abs(after - before) <= 0.10 * before, (before, after)


# ---------------------------------------------------------------- the page in a real browser


@pytest.fixture(scope="module")
def browser(server):
    if _no_browser():
        pytest.skip(_no_browser())
    from playwright.sync_api import sync_playwright

    with sync_playwright() as driver:
        launched = driver.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield launched
        launched.close()


@pytest.fixture
def page(browser):
    context = browser.new_context(viewport={"width": 1400, "height": 1000}, accept_downloads=True)
    opened = context.new_page()
    opened.set_default_timeout(30_000)
    failures: list[str] = []
    opened.on("pageerror", lambda exc: failures.append(str(exc)))
    yield opened
    context.close()
    assert failures == []


def open_goal(page, server, query: str) -> None:
    """Open the page at ``?query`` and wait for its answer."""
    page.goto(server.url + "?" + query)
    shown(page)


def shown(page) -> None:
    """Wait until the answer on screen is the one to the question in the address."""
    page.wait_for_function("document.body.dataset.shown === location.search.replace(/^\\?/, '')")


def complete(page) -> None:
    """Wait until every answer on screen (what to buy, the baselines, the schedule) is the address's."""
    page.wait_for_function("document.body.dataset.complete === location.search.replace(/^\\?/, '')")


def status(page) -> str:
    return page.inner_text("#status strong")


def steps(page) -> list[str]:
    return page.locator("#steps > li").all_inner_texts()


#: the least rendered size (px) of the text in the drawing inside ``holder``
SMALLEST_TEXT = """holder => Math.min(...[...document.querySelectorAll(holder + ' svg text')].map(
  t => parseFloat(t.getAttribute('font-size')) * t.getScreenCTM().a))"""
#: the least computed font size (px) of any element of the page that shows text outside a drawing
SMALLEST_PAGE_TEXT = """() => Math.min(...[...document.querySelectorAll('body *')].filter(e =>
  !e.closest('svg') && e.offsetParent !== null && [...e.childNodes].some(n => n.nodeType === 3 && n.textContent.trim())
).map(e => parseFloat(getComputedStyle(e).fontSize)))"""


def screenshot(page, name: str, selector: str | None = None) -> None:
    """docs/NAME.png: the page (or the element ``selector``), the solving time hidden (it varies)."""
    page.add_style_tag(content="#time { visibility: hidden; } #working { display: none !important; }")
    page.evaluate("() => document.querySelectorAll('.drawing').forEach(centre)")  # as laid out now
    target = page.locator(selector) if selector else page
    target.screenshot(path=str(DOCS / f"{name}.png"))


@needs_browser
def test_search_a_goal_and_see_its_tree_beside_the_baselines_and_its_schedule(page, server, shared_foon_dir):
    page.goto(server.url)
    page.fill("#goal", "scrambld eg")
    page.press("#goal", "Escape")
    page.press("#goal", "Enter")
    cli_error = cli("solve", "--data", str(shared_foon_dir), "--goal", "scrambld eg").stderr.strip()
    shown(page)
    assert page.inner_text("#error") == cli_error.replace("foon2asp: error: ", "error: ")

    page.fill("#goal", "greek")
    page.wait_for_selector("#suggestions li")
    offered = page.locator("#suggestions li").all_inner_texts()
    assert offered and all(t.startswith("greek salad") for t in offered)
    page.locator("#suggestions li").first.dispatch_event("mousedown")
    shown(page)
    assert "goal=greek+salad%2C+mixed" in page.url
    assert status(page) in PROVEN_OPTIMAL
    assert page.inner_text("#costs").split("\n")[0].split("\t")[:2] == ["units", "25"]
    assert len(steps(page)) == 25
    assert page.evaluate(SMALLEST_TEXT, "#tree") >= 12 - 0.01  # the legend: 9 points = 12 px
    assert page.locator("#motions input").count() == 13 and page.locator("#kitchen input").count() == 32

    page.wait_for_selector("#baselines .card >> nth=2")
    cards = {c.get_attribute("data-method"): c for c in page.locator("#baselines .card").all()}
    assert list(cards) == ["ids", "gbfs-h1", "gbfs-h2"]
    assert "distance to the optimum: units +10" in cards["gbfs-h1"].inner_text()
    assert cards["gbfs-h1"].locator("g.node.differs").count() >= 10  # its steps the optimum does not take
    assert page.evaluate(SMALLEST_TEXT, "#baselines .card") >= 12 - 0.01
    page.wait_for_selector("#gantt svg")
    assert page.locator("#durations tr").count() == 1 + 25
    assert page.inner_text("#schedule-summary").startswith("optimal · makespan 60 s on arm-1, arm-2, human-1")
    assert page.evaluate(SMALLEST_TEXT, "#gantt") >= 12 - 0.01  # drawn larger than its own size
    assert page.evaluate(SMALLEST_PAGE_TEXT) >= 12
    screenshot(page, "explore-tree")

    page.fill("#agents", "arm=2,human=1")
    page.click("#schedule-form button")
    shown(page)
    page.wait_for_function("document.querySelector('#schedule-summary').textContent.includes('human-1')")
    assert "agents=arm%3D2%2Chuman%3D1" in page.url
    assert page.inner_text("#schedule-summary") == (
        "optimal · makespan 60 s on arm-1, arm-2, human-1 · list scheduling 71 s · lower bound 55 s"
    )
    assert set(page.locator("#durations td:nth-child(3)").all_inner_texts()) == {"arm-1", "arm-2", "human-1"}
    screenshot(page, "explore-schedule", "#schedule")


@needs_browser
def test_untick_a_motion_and_see_the_tree_change_or_infeasible_with_the_reason(page, server):
    open_goal(page, server, "goal=macaroni")
    before = steps(page)
    assert len(before) == 5
    page.wait_for_selector("#baselines .card >> nth=2")
    h1 = page.locator("#baselines .card[data-method='gbfs-h1']")
    assert (
        h1.locator("strong.invalid").inner_text().startswith("INVALID: circular support: [pot, hot, contains {water}")
    )
    assert page.locator("#baselines .card[data-method='ids'] g.node.differs").count() == 0  # the optimum's steps
    screenshot(page, "explore-baselines", "#baselines")
    page.uncheck("#motions input[value='heat']")
    shown(page)
    assert len(steps(page)) == 6
    assert "forbid-motion=heat" in page.url and status(page) in PROVEN_OPTIMAL
    assert not any(s.startswith("heat") for s in steps(page))

    page.check("#motions input[value='heat']")
    shown(page)
    page.uncheck("#motions input[value='boil']")
    shown(page)
    assert "forbid-motion=boil" in page.url and "heat" not in page.url
    assert page.inner_text("#reason") == (
        "infeasible: trees exist, but the constraints rule them all out; --forbid-motion boil alone does"
    )
    complete(page)
    assert page.inner_text("#missing").startswith("missing: no item to buy gives a tree")
    assert page.locator("#tree svg").count() == 0 and steps(page) == []
    screenshot(page, "explore-infeasible")


@needs_browser
def test_untick_a_kitchen_item_and_see_what_to_buy(page, server):
    open_goal(page, server, "goal=greek+salad")
    page.uncheck("#kitchen input[value='mixing bowl, empty']")
    shown(page)
    assert status(page) == "unreachable (proven by fixpoint)"
    assert "without=mixing+bowl%2C+empty" in page.url
    complete(page)
    assert page.inner_text("#missing") == "missing: buy mixing bowl, empty"
    assert not page.is_checked("#kitchen input[value='mixing bowl, empty']")  # the item stays offered
    page.uncheck("#kitchen input[value='spoon, empty']")
    shown(page)
    page.check("#kitchen input[value='mixing bowl, empty']")
    shown(page)
    assert status(page) in PROVEN_OPTIMAL
    assert len(steps(page)) == 30  # without a spoon: five more steps


@needs_browser
def test_a_misspelt_rule_shows_its_warning_and_a_bad_one_its_error(page, server, shared_foon_dir):
    open_goal(page, server, "goal=macaroni")
    page.fill("#rule", ':- use(U), motoin(U,"fry").')
    page.click("#question button[type=submit]")
    shown(page)
    assert page.inner_text("#rule-warnings") == (
        "warning: --rule #1:1:12: motoin/2 is defined nowhere; did you mean motion/2?"
    )
    assert "rule=%3A-+use%28U%29%2C+motoin" in page.url and status(page) in PROVEN_OPTIMAL
    page.fill("#rule", ":- use(U), motion(U,")
    page.click("#question button[type=submit]")
    shown(page)
    res = cli("solve", "--data", str(shared_foon_dir), "--goal", "macaroni", "--rule", ":- use(U), motion(U,")
    assert page.inner_text("#error") == res.stderr.strip().replace("foon2asp: error: ", "error: ")
    page.fill("#rule", "#script (python)\nimport os\n#end.")
    page.click("#question button[type=submit]")
    shown(page)
    assert page.inner_text("#error") == "error: --rule #1: #script is refused here: a rule may not run code"


@needs_browser
def test_objects_and_human_steps_change_the_tree(page, server):
    open_goal(page, server, "goal=macaroni")
    page.fill("#forbid-object", "shaker")
    page.press("#forbid-object", "Enter")
    shown(page)
    assert "forbid-object=shaker" in page.url and status(page) == "infeasible (proven by clingo)"
    assert page.inner_text("#reason").endswith("--forbid-object shaker alone does")
    page.fill("#forbid-object", "")
    page.select_option("#objective-1", "success")
    shown(page)
    page.fill("#human-steps", "2")
    page.press("#human-steps", "Enter")
    shown(page)
    assert "human-steps=2" in page.url and page.inner_text("#costs").split("\n")[1].split("\t")[:2] == [
        "success",
        "0.3645",
    ]
    marked = [k for k, step in enumerate(steps(page), 1) if "[human]" in step.split("\n")[0]]
    assert marked == [4, 6]
    assert page.locator("#tree g.node.human").count() == 2  # drawn orange, as draw marks them


@needs_browser
def test_reload_back_and_a_shared_link_show_the_same_page(page, server, browser):
    open_goal(page, server, "goal=macaroni")
    first_url, first_steps = page.url, steps(page)
    page.select_option("#objective-1", "success")
    shown(page)
    page.select_option("#objective-2", "units")
    shown(page)
    assert "objective=success%2Cunits" in page.url
    page.uncheck("#motions input[value='heat']")
    shown(page)
    assert "forbid-motion=heat" in page.url
    seen = (page.url, status(page), steps(page), page.input_value("#objective-1"), page.input_value("#objective-2"))
    assert seen[2] != first_steps

    page.reload()
    shown(page)
    again = (page.url, status(page), steps(page), page.input_value("#objective-1"), page.input_value("#objective-2"))
    assert again == seen and not page.is_checked("#motions input[value='heat']")

    page.go_back()
    shown(page)
    assert "forbid-motion" not in page.url and page.is_checked("#motions input[value='heat']")
    for _ in range(2):
        page.go_back()
        shown(page)
    assert page.url == first_url and steps(page) == first_steps and page.input_value("#objective-1") == "units"

    shared = browser.new_page()
    shared.goto(seen[0])
    shown(shared)
    assert shared.locator("#steps > li").all_inner_texts() == seen[2]
    shared.close()


@needs_browser
def test_each_export_downloads_and_the_foon_text_loads_back_with_check(page, server, shared_foon_dir, tmp_path):
    open_goal(page, server, "goal=macaroni&forbid-motion=heat")
    files = {}
    for fmt in ("foon", "json", "pddl-domain", "pddl-problem", "svg"):
        with page.expect_download() as caught:
            page.click(f"[data-export='{fmt}']")
        download = caught.value
        files[fmt] = tmp_path / download.suggested_filename
        download.save_as(files[fmt])
    assert sorted(p.name for p in files.values()) == sorted(
        f"macaroni-{n}" for n in ("task-tree.txt", "task-tree.json", "domain.pddl", "problem.pddl", "task-tree.svg")
    )
    res = cli("check", str(files["foon"]), "--data", str(shared_foon_dir))
    assert res.returncode == 0, res.stdout + res.stderr
    assert "Verdict: VALID" in res.stdout and "(asp-units, optimal, 6 units)" in files["foon"].read_text()
    tree = json.loads(files["json"].read_text())[0]
    assert (tree["status"], len(tree["units"])) == ("optimal", 6)
    assert all(u["motion"] != "heat" for u in tree["units"])
    parser = pytest.importorskip("pddl")
    domain = parser.parse_domain(files["pddl-domain"])
    assert domain.actions and not any(a.name.endswith("-heat") for a in domain.actions)  # forbidden: no action
    assert "have" in str(parser.parse_problem(files["pddl-problem"]).goal)  # one goal: one atom
    assert "<svg" in files["svg"].read_text() and "macaroni" in files["svg"].read_text()

    open_goal(page, server, "goal=macaroni&objective=depth")
    page.click("[data-export='pddl-domain']")
    page.wait_for_selector("#export-error:not([hidden])")
    assert (
        page.inner_text("#export-error")
        == "error: PDDL can state the objectives units, success, inputs, cost, not 'depth'"
    )


def wait_for(http, test, seconds: float = 30.0) -> dict:
    """The workers' status once ``test(status)`` holds (polled)."""
    deadline = time.monotonic() + seconds
    while True:
        found = http.get("/api/status").json()
        if test(found) or time.monotonic() > deadline:
            return found
        time.sleep(0.05)


@needs_browser
def test_a_long_solve_shows_it_is_working_and_cancel_stops_it(page, server, http):
    idle = wait_for(http, lambda s: s["ready"] == s["workers"] and s["busy"] == 0)
    assert idle["workers"] == 2 and idle["busy"] == 0, idle
    page.goto(server.url + "?" + urlencode({"goal": "macaroni", "rule": PIGEONS, "time-limit": "30"}))
    page.wait_for_selector("#working:not([hidden])")
    assert re.fullmatch(r"working… \d+\.\d s \(time limit 30 s\)", page.inner_text("#working-text"))
    assert wait_for(http, lambda s: s["busy"] == 1)["busy"] == 1
    before = server.workers()
    page.click("#cancel")
    assert page.inner_text("#error").startswith("error: cancelled")
    deadline = time.monotonic() + 10
    while server.workers() & before == before and time.monotonic() < deadline:
        time.sleep(0.1)
    assert server.workers() & before != before  # the worker was stopped (and another took its place)
    assert wait_for(http, lambda s: s["busy"] == 0)["busy"] == 0
    open_goal(page, server, "goal=ice")
    assert status(page) in PROVEN_OPTIMAL
