"""The ASP encodings shipped inside the package (``foon2asp/asp/encodings/*.lp``)."""

from __future__ import annotations

from functools import cache
from importlib import resources


def names() -> list[str]:
    """Names (without .lp) of all shipped encodings."""
    root = resources.files(__name__)
    return sorted(p.name[:-3] for p in root.iterdir() if p.name.endswith(".lp"))


@cache
def encoding(name: str) -> str:
    """The text of ``NAME.lp``."""
    path = resources.files(__name__).joinpath(f"{name}.lp")
    if not path.is_file():
        raise KeyError(f"no encoding {name!r}; have {', '.join(names())}")
    return path.read_text(encoding="utf-8")
