"""Where the shipped encodings are: the entry files of each task, their parts and show files.

The encodings live in ``encodings/`` at the top of the repository (``foon2asp.encodings``
when installed): an entry file per task (``solve.lp``, ``solve_closed.lp``, ...) that
includes its parts (``parts/*.lp``) and its show file (``show/*.lp``).  clingo loads
an entry by its path and resolves the includes itself; Python only finds the files.
"""

from __future__ import annotations

from functools import cache
from importlib import resources
from pathlib import Path

#: the encodings in the source tree (``foon2asp.encodings`` when installed)
_SOURCE = Path(__file__).resolve().parents[2] / "encodings"


@cache
def root() -> Path:
    """The folder holding the entry files (``parts/`` and ``show/`` inside it)."""
    try:
        # an installed namespace package is a MultiplexedPath: go through one of its files
        probe = Path(str(resources.files("foon2asp.encodings").joinpath("solve.lp")))
        if probe.is_file():
            return probe.parent
    except ModuleNotFoundError:
        pass
    return _SOURCE


def entry(name: str) -> str:
    """The path of the entry file ``NAME.lp`` (a task: ``solve``, ``find_missing``, ...)."""
    path = root() / f"{name}.lp"
    if not path.is_file():
        raise KeyError(f"no entry encoding {name!r}; have {', '.join(entries())}")
    return str(path)


def entries() -> list[str]:
    """The names (without .lp) of the entry files."""
    return sorted(p.stem for p in root().glob("*.lp"))


def part(name: str) -> str:
    """The path of the part ``parts/NAME.lp`` (``tree``, ``success``, ...)."""
    path = root() / "parts" / f"{name}.lp"
    if not path.is_file():
        raise KeyError(f"no encoding {name!r}; have {', '.join(parts())}")
    return str(path)


def parts() -> list[str]:
    """The names (without .lp) of the parts."""
    return sorted(p.stem for p in (root() / "parts").glob("*.lp"))


def show(name: str) -> str:
    """The path of the show file ``show/NAME.lp``."""
    return str(root() / "show" / f"{name}.lp")


def shows() -> list[str]:
    """The names (without .lp) of the show files."""
    return sorted(p.stem for p in (root() / "show").glob("*.lp"))
