"""Access to the ASP encodings shipped with the package (``encodings/*.lp``)."""

from __future__ import annotations

from functools import lru_cache
from importlib import resources
from pathlib import Path

_SOURCE_ROOT = Path(__file__).resolve().parent.parent


def _resource(package: str, folder: str, probe: str):
    """An installed resource folder, or the folder in a source checkout."""
    try:
        root = resources.files(package)
        if root.joinpath(probe).is_file():
            return root
    except ModuleNotFoundError:
        pass
    return _SOURCE_ROOT / folder


def _root():
    return _resource("foon2asp.encodings", "encodings", "tree.lp")


def demo_dir() -> Path:
    """The demo data set (``data/`` in the source tree, shipped in the wheel)."""
    root = _resource("foon2asp.demo", "data", "FOON.txt")
    # an installed namespace package is a MultiplexedPath: go through one of its files
    return Path(str(root.joinpath("FOON.txt"))).parent


def names() -> list[str]:
    """Names (without .lp) of all shipped encodings."""
    return sorted(p.name[:-3] for p in _root().iterdir() if p.name.endswith(".lp"))


@lru_cache(maxsize=None)
def encoding(name: str) -> str:
    """The text of ``encodings/NAME.lp``."""
    path = _root().joinpath(f"{name}.lp")
    if not path.is_file():
        raise KeyError(f"no encoding {name!r}; have {', '.join(names())}")
    return path.read_text(encoding="utf-8")
