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


#: the shipped encodings each encoding needs loaded with it (tree.lp defines use/1, reach/1, ...)
DEPENDS: dict[str, tuple[str, ...]] = {
    "reachable": ("tree",),
    "dominance": ("tree",),
    "units": ("tree",),
    "success": ("tree",),
    "inputs": ("tree",),
    "cost": ("tree",),
    "human": ("tree",),
    "greedy": ("tree",),
    "greedy_h1": ("greedy",),
    "greedy_h2": ("greedy",),
    "substitutes": ("tree",),
}


def with_dependencies(wanted: list[str] | tuple[str, ...]) -> list[str]:
    """``wanted`` with what each needs (:data:`DEPENDS`), each name once, needed ones first."""
    out: list[str] = []

    def visit(name: str) -> None:
        for dep in DEPENDS.get(name, ()):
            visit(dep)
        if name not in out:
            out.append(name)

    for name in wanted:
        visit(name)
    return out
