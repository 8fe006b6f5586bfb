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
    encodings = {p.name for p in (REPO / "foon2asp" / "asp" / "encodings").glob("*.lp")}
    assert encodings and {f"foon2asp/asp/encodings/{n}" for n in encodings} <= names
    assert {f"foon2asp/demo/{n}" for n in ("FOON.txt", "kitchen.json", "goal_nodes.json")} <= names
    assert {"foon2asp/cli/main.py", "foon2asp/py.typed"} <= names


def test_installed_package_finds_its_resources():
    from foon2asp.asp import encodings
    from foon2asp.foon.loaders import demo_dir

    assert "tree" in encodings.names() and "units" in encodings.names()
    assert "use(U)" in encodings.encoding("tree")
    assert (demo_dir() / "FOON.txt").is_file()


def test_layout_page_lists_every_module_and_none_is_too_long():
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
    long = {m: n for m, p in modules.items() if (n := len(p.read_text(encoding="utf-8").splitlines())) > 450}
    assert long == {}


def test_no_module_name_repeats_across_subpackages():
    """Each module's file name says what it does once: no two subpackages hold one of the same name."""
    package = Path(__file__).resolve().parent.parent / "foon2asp"
    seen: dict[str, list[str]] = {}
    for path in package.rglob("*.py"):
        if path.name not in ("__init__.py", "__main__.py"):
            seen.setdefault(path.name, []).append(path.relative_to(package).as_posix())
    assert {name: paths for name, paths in seen.items() if len(paths) > 1} == {}


def test_readme_and_benchmarks_stay_short():
    """The README is read in minutes and BENCHMARKS holds current tables only."""
    lines = {
        name: len((REPO / name).read_text(encoding="utf-8").splitlines()) for name in ("README.md", "BENCHMARKS.md")
    }
    assert lines["README.md"] <= 250 and lines["BENCHMARKS.md"] <= 300, lines


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
