"""The package as shipped: the wheel holds the encodings and the demo data, docs/layout.md lists every
module, module names do not repeat, and the library's modules import one way."""

from __future__ import annotations

import ast
import re
import shutil
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest

from conftest import REPO


def test_wheel_contains_encodings_and_demo(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(tmp_path), str(REPO)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    wheel = next(tmp_path.glob("foon2asp-*.whl"))
    names = set(zipfile.ZipFile(wheel).namelist())
    encodings = {str(p.relative_to(REPO / "encodings")) for p in (REPO / "encodings").rglob("*.lp")}
    assert {"solve.lp", "parts/tree.lp", "show/tree.lp"} <= encodings
    assert {f"foon2asp/encodings/{n}" for n in encodings} <= names
    assert {f"foon2asp/demo/{n}" for n in ("FOON.txt", "kitchen.json", "goal_nodes.json")} <= names
    assert {"foon2asp/cli/main.py", "foon2asp/py.typed"} <= names
    assert {f"foon2asp/explore/static/{n}" for n in ("index.html", "explore.js", "explore.css")} <= names


def test_installed_package_finds_its_resources():
    from foon2asp.asp import encoding_files
    from foon2asp.foon.loaders import demo_dir

    assert "tree" in encoding_files.parts() and "units" in encoding_files.parts()
    assert "solve" in encoding_files.entries() and "solve_closed" in encoding_files.entries()
    assert "candidate(U)" in Path(encoding_files.part("tree")).read_text(encoding="utf-8")
    assert (demo_dir() / "FOON.txt").is_file()


def test_layout_page_lists_every_module():
    """docs/layout.md names every module, and only those, each with its docstring's first line."""
    root = Path(__file__).resolve().parent.parent
    package = root / "foon2asp"
    page = (root / "docs" / "layout.md").read_text(encoding="utf-8")
    listed = {
        m: text.replace("\\|", "|") for m, text in re.findall(r"^\| `([\w/]+\.py)` \| (.*) \|$", page, re.MULTILINE)
    }
    modules = {p.relative_to(package).as_posix(): p for p in package.rglob("*.py")}
    assert set(modules) - set(listed) == set(), "modules missing from docs/layout.md"
    assert set(listed) - set(modules) == set(), "docs/layout.md lists modules that do not exist"
    for name, path in modules.items():
        doc = (ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or "").strip()
        first = doc.splitlines()[0] if doc else ""
        assert listed[name] == first, f"docs/layout.md: {name}: {listed[name]!r} is not its docstring's {first!r}"
    entries = dict(re.findall(r"^\| `encodings/(\w+\.lp)` \| (.*) \|$", page, re.MULTILINE))
    for path in (root / "encodings").glob("*.lp"):
        first = path.read_text(encoding="utf-8").splitlines()[0].lstrip("% ")
        assert entries.get(path.name) == first, f"docs/layout.md: encodings/{path.name}: not {first!r}"
    assert set(entries) == {p.name for p in (root / "encodings").glob("*.lp")}


def test_no_module_name_repeats_across_subpackages():
    """Each module's file name says what it does once: no two subpackages hold one of the same name."""
    package = Path(__file__).resolve().parent.parent / "foon2asp"
    seen: dict[str, list[str]] = {}
    for path in package.rglob("*.py"):
        if path.name not in ("__init__.py", "__main__.py"):
            seen.setdefault(path.name, []).append(path.relative_to(package).as_posix())
    assert {name: paths for name, paths in seen.items() if len(paths) > 1} == {}


def _strings(path: Path) -> list[tuple[int, str]]:
    """The string constants of a Python file that are not docstrings, with their lines."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docs = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                docs.add(id(first.value))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
            found.append((node.lineno, node.value))
        elif isinstance(node, ast.JoinedStr):
            text = "".join(v.value if isinstance(v, ast.Constant) else "X" for v in node.values)
            found.append((node.lineno, text))
    return found


#: a rule in a string: ``:-``, a rule head ``p(...) :-``, or a directive that is a rule's business
RULE = re.compile(
    r"(?<!\?):-|(?m:^\s*)#(show|external|project|minimize|maximize|heuristic|program|include|edge|const|defined)\b"
)


def test_no_python_module_holds_asp_rules():
    """ASP lives in encodings/*.lp: no string in the package holds a rule, a constraint or a
    directive at the start of a line (docstrings and examples shown in help texts are not read)."""
    offenders = []
    for path in sorted((REPO / "foon2asp").rglob("*.py")):
        for line, text in _strings(path):
            if RULE.search(text) and "e.g." not in text:  # an example shown to a person in --help is no rule
                offenders.append(f"{path.relative_to(REPO)}:{line}: {text[:60]!r}")
    assert offenders == []


def test_every_encoding_is_reached_from_an_entry_and_commented():
    """Every part and show file is included by some entry; every rule has a comment above it."""
    root = REPO / "encodings"
    included = set()
    for entry in root.glob("*.lp"):
        todo = [entry]
        while todo:
            path = todo.pop()
            for name in re.findall(r'^#include "([^"]+)"\.', path.read_text(encoding="utf-8"), re.MULTILINE):
                target = (path.parent / name).resolve()
                if target not in included:
                    included.add(target)
                    todo.append(target)
    files = {p.resolve() for p in (root / "parts").glob("*.lp")} | {p.resolve() for p in (root / "show").glob("*.lp")}
    files.discard((root / "show" / "nothing.lp").resolve())  # query loads it beside a program with #show
    assert files - included == set(), "encodings no entry includes"
    for path in root.rglob("*.lp"):
        lines = path.read_text(encoding="utf-8").splitlines()
        for n, line in enumerate(lines):
            starts = line and not line.startswith(("%", " ", "\t"))
            above = lines[n - 1] if n else ""
            grouped = line.startswith("#defined") and above.startswith("#defined")  # one comment for a group
            if starts and not above.startswith("%") and not grouped:
                raise AssertionError(f"{path.relative_to(REPO)}:{n + 1}: no comment above {line!r}")


def test_api_modules_import_one_way():
    """The modules of foon2asp.api import each other one way only: every import counts, also one
    inside a function or under ``TYPE_CHECKING``, so no cycle hides there."""
    api = Path(__file__).resolve().parent.parent / "foon2asp" / "api"
    names = {p.stem for p in api.glob("*.py")}
    graph = {}
    for path in api.glob("*.py"):
        imported = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and node.module == "foon2asp.api":
                imported |= {a.name if a.name in names else "__init__" for a in node.names}
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("foon2asp.api."):
                imported.add(node.module.split(".")[2])
            elif isinstance(node, ast.Import):
                imported |= {
                    a.name.split(".")[2] if a.name.count(".") >= 2 else "__init__"
                    for a in node.names
                    if a.name.startswith("foon2asp.api")
                }
        graph[path.stem] = imported - {path.stem}
    order: list[str] = []  # each module after every module it imports
    while len(order) < len(graph):
        ready = sorted(m for m, deps in graph.items() if m not in order and deps <= set(order))
        assert ready, f"an import cycle among foon2asp.api modules: {sorted(set(graph) - set(order))}"
        order += ready
    assert order[-1] == "__init__"


def test_the_command_line_imports_the_library_only_through_its_api():
    """No module of foon2asp.cli imports a module the import-linter contract forbids it (the
    schedules among them): the command line is a front end of foon2asp.api."""
    config = tomllib.loads((REPO / "pyproject.toml").read_text(encoding="utf-8"))
    contracts = config["tool"]["importlinter"]["contracts"]
    (contract,) = [c for c in contracts if c.get("source_modules") == ["foon2asp.cli"]]
    forbidden = tuple(contract["forbidden_modules"])
    assert "foon2asp.schedule" in forbidden and "foon2asp.asp" in forbidden
    found = []
    for path in (REPO / "foon2asp" / "cli").glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [node.module or ""] if isinstance(node, ast.ImportFrom) else []
            names += [a.name for a in node.names] if isinstance(node, ast.Import) else []
            found += [(path.name, n) for n in names if n.startswith(forbidden)]
    assert found == []


MAKE = shutil.which("make")


def system_deps(tmp_path, uid: int, *args: str) -> str:
    """``make system-deps`` where neither ``dot`` nor ``chromium`` is found, ``id -u`` says ``uid``
    and ``apt-get`` only says how it was called; its output."""
    stubs = tmp_path / "bin"
    stubs.mkdir(exist_ok=True)
    for name, body in (("id", f"echo {uid}"), ("apt-get", 'echo "apt-get $*"')):
        (stubs / name).write_text(f"#!/bin/sh\n{body}\n")
        (stubs / name).chmod(0o755)
    proc = subprocess.run(
        [MAKE, "-s", "-C", str(REPO), "system-deps", *args],
        env={"PATH": str(stubs)},
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


@pytest.mark.skipif(MAKE is None, reason="no make")
def test_make_says_what_it_installs_and_why_before_it_does(tmp_path):
    out = system_deps(tmp_path, 0).splitlines()
    assert out == [
        "make: installing graphviz chromium with apt-get, with their dependencies, for the tests that draw trees",
        "make: (graphviz: 'dot' draws the trees and charts; chromium: measures the HTML pages' drawings)",
        "make: to skip this: make test NO_SYSTEM_INSTALL=1",
        "apt-get update -qq",
        "apt-get install -y -qq graphviz",
        "apt-get install -y -qq chromium",
    ]


@pytest.mark.skipif(MAKE is None, reason="no make")
def test_make_installs_nothing_when_told_or_not_root(tmp_path):
    out = system_deps(tmp_path, 0, "NO_SYSTEM_INSTALL=1")
    assert out == "make: not installing graphviz chromium (NO_SYSTEM_INSTALL is set): the tests that need them skip\n"
    out = system_deps(tmp_path, 1000)
    assert out == "make: not installing graphviz chromium (needs root and apt-get): the tests that need them skip\n"
