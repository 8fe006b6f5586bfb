"""The explorer (foon2asp explore) on ../shared/foon: the server as the command starts it, its
one-line errors, its limits, 1,000 random requests, and the page in a real browser (Playwright
driving the system Chromium), whose screenshots are docs/explore.md's pictures."""

from __future__ import annotations

import json
import os
import random
import re
import shutil
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
#: a rule whose search clingo cannot finish soon: 11 pigeons in 10 holes
PIGEONS = "h(1..11). p(1..10). 1 { at(H,P) : p(P) } 1 :- h(H). :- at(H1,P), at(H2,P), H1 < H2."


def _missing_extra() -> str | None:
    for name in ("starlette", "uvicorn", "httpx"):
        try:
            __import__(name)
        except ImportError:
            return f"the 'explore' extra is not installed ({name}): pip install 'foon2asp[explore]' httpx"
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
        out: set[int] = set()
        for task in Path(f"/proc/{self.proc.pid}/task").iterdir():
            out |= {int(p) for p in (task / "children").read_text().split()}
        return out

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
    running = Server(shared_foon_dir)
    yield running
    running.stop()
    assert running.proc.returncode in (0, 143), running.errors()
    assert "Traceback" not in running.errors(), running.errors()


@pytest.fixture(scope="module")
def http(server):
    import httpx

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
    tree = http.get("/api/tree", params={"goal": "greek salad"}).json()
    assert (tree["status"], tree["proven_by"], tree["cost"]["units"], len(tree["steps"])) == (
        "optimal",
        "clingo",
        25,
        25,
    )
    assert tree["svg"].startswith("<svg") and "mixing bowl, empty" in [k["text"] for k in tree["part"]["kitchen"]]
    side = http.get("/api/baselines", params={"goal": "greek salad"}).json()
    by = {m["method"]: m for m in side["methods"]}
    assert by["gbfs-h1"]["distance"]["units"] == 10 and by["gbfs-h1"]["valid"] is True
    assert len(by["gbfs-h1"]["differs"]) >= 10 and side["optimum"]["cost"]["units"] == 25
    plan = http.get("/api/schedule", params={"goal": "greek salad", "agents": "arm=2"}).json()
    assert (plan["status"], plan["makespan"], plan["agents"]) == ("optimal", 15.0, ["arm-1", "arm-2"])
    assert sorted(r["step"] for r in plan["rows"]) == list(range(1, 26))
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
    t0 = time.monotonic()
    asked = http.get("/api/tree", params={"goal": "macaroni", "rule": PIGEONS, "time-limit": "1"})
    took = time.monotonic() - t0
    assert asked.status_code == 504 and error_of(asked) == "no answer within 7 s: stopped (time-limit 1 s)"
    assert took < 7 + 3
    assert http.get("/api/tree", params={"goal": "ice"}).json()["status"] == "optimal"  # a fresh worker answers


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
