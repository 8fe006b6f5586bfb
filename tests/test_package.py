"""The wheel ships the encodings and the demo data (a non-editable install works)."""

from __future__ import annotations

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


def test_installed_package_finds_its_resources():
    from foon2asp.asp import encodings
    from foon2asp.foon.demo import demo_dir

    assert "tree" in encodings.names() and "units" in encodings.names()
    assert "use(U)" in encodings.encoding("tree")
    assert (demo_dir() / "FOON.txt").is_file()


def test_readme_layout_lists_every_module_and_none_is_too_long():
    root = Path(__file__).resolve().parent.parent
    package = root / "foon2asp"
    readme = (root / "README.md").read_text(encoding="utf-8")
    layout = readme[readme.index("## Layout") :]
    listed = {line.split()[0] for line in layout.splitlines() if line.startswith("  ") and line.split()}
    modules = {p.relative_to(package).as_posix() for p in package.rglob("*.py")}
    assert modules - listed == set(), "modules missing from the README's Layout"
    assert {m for m in listed if m.endswith(".py")} - modules == set(), "the Layout lists modules that do not exist"
    long = {m: n for m in modules if (n := len((package / m).read_text(encoding="utf-8").splitlines())) > 450}
    assert long == {}
