"""The package as shipped: the wheel holds the encodings and the demo data, docs/layout.md lists every
module, module names do not repeat, and the library's modules import one way."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
import zipfile
from pathlib import Path

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
    assert {f"foon2asp/explore/static/{n}" for n in ("index.html", "explore.js", "explore.css")} <= names


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
