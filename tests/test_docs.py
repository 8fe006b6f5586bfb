"""Every example in README.md and docs/*.md, run and compared with the output it shows (Sybil).

* ```console blocks: each ``$ command`` line (a trailing ``\\`` continues it) runs in bash from
  a working folder that looks like the repository root (``data``, ``docs``, ``foon2asp`` and
  ``bench`` linked in, ``../shared`` beside it), with this Python's ``bin`` first on PATH;
  stdout and stderr together must match the lines that follow, ``...`` standing for any text
  (times, paths). One folder per page, so a later example sees the files an earlier one wrote.
* ```python blocks: run in the page's namespace from that folder; ``>>>`` blocks are doctests
  (ELLIPSIS, NORMALIZE_WHITESPACE), others plain code whose assertions must hold.
* ``<!-- skip: next if(not SLOW, reason="...") -->`` before an example that takes minutes:
  skipped unless FOON2ASP_DOCS_SLOW=1. An example that reads ``../shared`` is skipped when
  ../shared/foon is not beside the checkout, and so are the Python examples after it on its page.

The console commands of all pages are run once, the pages side by side (each page's commands
in order), before the first one is compared; a test run alone runs its page's commands itself.
"""

from __future__ import annotations

import atexit
import contextlib
import doctest
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from sybil import Example, Sybil
from sybil.evaluators.doctest import DocTestEvaluator
from sybil.evaluators.python import PythonEvaluator
from sybil.parsers.abstract.doctest import DocTestStringParser
from sybil.parsers.markdown import CodeBlockParser, PythonCodeBlockParser, SkipParser

REPO = Path(__file__).resolve().parent.parent
SHARED = REPO.parent / "shared"
HAS_SHARED = (SHARED / "foon" / "FOON.txt").is_file()
SLOW = os.environ.get("FOON2ASP_DOCS_SLOW") == "1"
PAGES = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
#: what the working folder of a page links in from the repository
LINKED = ("data", "docs", "encodings", "foon2asp", "bench")
COMMAND_TIMEOUT_S = 600
CHECKER = doctest.OutputChecker()
NO_SHARED = "../shared/foon is not beside the checkout"


def workdir() -> Path:
    """A fresh folder that looks like the repository root, ../shared beside it (removed at exit)."""
    top = Path(tempfile.mkdtemp(prefix="foon2asp-docs-"))
    atexit.register(shutil.rmtree, top, ignore_errors=True)
    root = top / "main"
    root.mkdir()
    for name in LINKED:
        (root / name).symlink_to(REPO / name)
    if SHARED.is_dir():
        (top / "shared").symlink_to(SHARED)
    return root


def commands(block: str) -> list[tuple[str, str]]:
    """``(command, expected output)`` pairs of a console block."""
    pairs: list[tuple[str, list[str]]] = []
    continued = False
    for line in block.splitlines():
        if continued:
            command, out = pairs[-1]
            pairs[-1] = (command + "\n" + line, out)
            continued = line.endswith("\\")
        elif line.startswith("$ "):
            pairs.append((line[2:], []))
            continued = line.endswith("\\")
        elif pairs:
            pairs[-1][1].append(line)
        elif line.strip():
            raise ValueError(f"console block: output before any '$ ' command: {line!r}")
    return [(command, "\n".join(out)) for command, out in pairs]


def tidy(text: str) -> str:
    """Trailing white space of each line and trailing blank lines dropped."""
    return "\n".join(line.rstrip() for line in text.rstrip().splitlines()) + "\n"


ENV = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}")
ENV.update(COLUMNS="200", NO_COLOR="1", PYTHONHASHSEED="0")


def execute(block: str, cwd: Path) -> list[tuple[str, str, str, int]]:
    """Run a console block's commands in order: ``(command, expected, output, exit status)``."""
    runs = []
    for command, expected in commands(block):
        proc = subprocess.run(
            ["bash", "-c", "exec 2>&1\n" + command],  # stderr where it is written, as on a terminal
            cwd=cwd,
            env=ENV,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            timeout=COMMAND_TIMEOUT_S,
        )
        runs.append((command, expected, proc.stdout, proc.returncode))
    return runs


#: (page, start of the example) -> the runs of its commands, filled by prefetch()
RAN: dict[tuple[str, int], list[tuple[str, str, str, int]]] = {}
#: page -> its working folder
FOLDERS: dict[str, Path] = {}


def run_console(example: Example) -> str | None:
    runs = RAN.pop((example.path, example.start), None)
    if runs is None:
        runs = execute(str(example.parsed), example.namespace["WORKDIR"])
    for command, expected, output, status in runs:
        want, got = tidy(expected), tidy(output)
        if not CHECKER.check_output(want, got, doctest.ELLIPSIS):
            diff = CHECKER.output_difference(doctest.Example(command, want), got, doctest.ELLIPSIS)
            return f"$ {command}\n(exit status {status})\n{diff}"
    return None


@contextlib.contextmanager
def page_folder(example: Example):
    old = os.getcwd()
    os.chdir(example.namespace["WORKDIR"])
    try:
        yield
    finally:
        os.chdir(old)


PLAIN_PYTHON = PythonEvaluator()
DOCTEST = DocTestEvaluator(doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)


def run_python(example: Example) -> str | None:
    with page_folder(example):
        return PLAIN_PYTHON(example)


def run_doctest(example: Example) -> str | None:
    with page_folder(example):
        return DOCTEST(example)


class PythonBlocks(PythonCodeBlockParser):
    """```python blocks: doctests when they start with >>>, else plain code; run from the page's folder."""

    def __init__(self) -> None:
        super().__init__()
        self.doctest_parser = DocTestStringParser(run_doctest)  # type: ignore[arg-type]
        self.codeblock_parser = CodeBlockParser("python", run_python)


SYBIL = Sybil(parsers=[CodeBlockParser("console", run_console), PythonBlocks(), SkipParser()])
RUNNERS = (run_console, run_python, run_doctest)


def collect() -> list[tuple[Path, int, Example]]:
    """Every page's examples in order (skip directives included): (page, index, example)."""
    return [(page, index, example) for page in PAGES for index, example in enumerate(SYBIL.parse(page))]


EXAMPLES = collect()
RUN = [(page, index, example) for page, index, example in EXAMPLES if example.region.evaluator in RUNNERS]
#: page -> how many of its examples have been evaluated
PROGRESS: dict[Path, int] = {}
#: pages one of whose Python examples was skipped (the later ones may depend on it)
SKIPPED_PYTHON: set[Path] = set()
PREFETCHED = False


def folder(page: Path) -> Path:
    if str(page) not in FOLDERS:
        FOLDERS[str(page)] = workdir()
    return FOLDERS[str(page)]


def prefetch() -> None:
    """Run the console blocks of every page, pages side by side, each page's blocks in order
    (not those after a skip directive, nor those that need an absent ../shared)."""
    global PREFETCHED
    PREFETCHED = True

    def page_runs(page: Path) -> None:
        previous = None
        for p, _, example in EXAMPLES:
            if p != page:
                continue
            after_skip = previous is not None and previous.region.evaluator not in RUNNERS
            previous = example
            block = str(example.parsed)
            if example.region.evaluator is not run_console or after_skip:
                continue
            if "../shared" in block and not HAS_SHARED:
                continue
            RAN[(example.path, example.start)] = execute(block, folder(page))

    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        list(pool.map(page_runs, PAGES))


def evaluate(page: Path, example: Example) -> None:
    namespace = example.namespace
    if "WORKDIR" not in namespace:
        namespace.update(WORKDIR=folder(page), SLOW=SLOW, SHARED=HAS_SHARED)
    python = example.region.evaluator in (run_python, run_doctest)
    source = example.parsed.source if isinstance(example.parsed, doctest.Example) else str(example.parsed)
    if python and page in SKIPPED_PYTHON:
        raise unittest.SkipTest("an earlier Python example of this page was skipped")
    try:
        if "../shared" in source and not HAS_SHARED:
            raise unittest.SkipTest(NO_SHARED)
        example.evaluate()
    except unittest.SkipTest:
        if python:
            SKIPPED_PYTHON.add(page)
        raise


@pytest.mark.parametrize(
    "page,index",
    [(page, index) for page, index, _ in RUN],
    ids=[f"{page.relative_to(REPO)}:{example.line}" for page, _, example in RUN],
)
def test_example(page: Path, index: int, request):
    if not PREFETCHED and len(request.session.items) > 20:  # a whole run: every page at once
        prefetch()
    examples = [example for p, _, example in EXAMPLES if p == page]
    for earlier in range(PROGRESS.get(page, 0), index):  # a page's examples run in order
        try:
            evaluate(page, examples[earlier])
        except Exception:  # reported by its own test
            pass
    PROGRESS[page] = index + 1
    try:
        evaluate(page, examples[index])
    except unittest.SkipTest as skip:
        pytest.skip(str(skip))


def test_every_block_names_its_language():
    """An opening fence names its language: console and python blocks run, the others
    (text, json, prolog, sh for the set-up commands) are shown as they are."""
    for page in PAGES:
        inside = False
        for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
            if line.lstrip().startswith("```"):
                if not inside:
                    language = line.strip()[3:].strip()
                    assert language, f"{page.name}:{number}: a code block without a language"
                    assert language not in ("shell-session", "pycon", "bash"), f"{page.name}:{number}: use console"
                inside = not inside


def test_pages_are_found():
    assert (REPO / "README.md") in PAGES and len(PAGES) > 5
    assert len(RUN) > 50


def test_no_two_pages_write_the_same_results_file():
    """A reader who runs the pages one after the other in one folder never meets "results file
    exists": each results file a page's `batch` writes is written by no other page."""
    writers: dict[str, set[str]] = {}
    for page, _, example in EXAMPLES:
        if example.region.evaluator is not run_console:
            continue
        for command, _ in commands(str(example.parsed)):
            for line in command.split("|")[0].split("&&"):
                words = line.split()
                if "batch" in words and "--resume" not in words:
                    for flag in ("--output", "-o"):
                        if flag in words:
                            writers.setdefault(words[words.index(flag) + 1].rstrip(";"), set()).add(page.name)
    shared = {name: sorted(pages) for name, pages in writers.items() if len(pages) > 1}
    assert shared == {}
    assert len(writers) >= 5  # the check sees the batches of the pages
