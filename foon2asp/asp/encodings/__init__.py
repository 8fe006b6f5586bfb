"""The ASP encodings shipped inside the package (``foon2asp/asp/encodings/*.lp``)."""

from __future__ import annotations

import re
from functools import cache
from importlib import resources

#: an include directive of a shipped encoding: ``#include "NAME.lp".`` alone on its line
INCLUDE = re.compile(r'^#include "(?P<name>[a-z_]+)\.lp"\.[ \t]*$', re.MULTILINE)


def names() -> list[str]:
    """Names (without .lp) of all shipped encodings."""
    root = resources.files(__name__)
    return sorted(p.name[:-3] for p in root.iterdir() if p.name.endswith(".lp"))


def source(name: str) -> str:
    """The text of ``NAME.lp`` as shipped (its ``#include`` directives as written)."""
    path = resources.files(__name__).joinpath(f"{name}.lp")
    if not path.is_file():
        raise KeyError(f"no encoding {name!r}; have {', '.join(names())}")
    return path.read_text(encoding="utf-8")


@cache
def encoding(name: str) -> str:
    """The text of ``NAME.lp`` with each ``#include`` of a shipped encoding replaced by that
    encoding's text (each file once, as clingo includes it), so it can be added as a string."""
    seen: set[str] = set()

    def expand(current: str) -> str:
        seen.add(current)

        def include(match: re.Match) -> str:
            other = match.group("name")
            return "" if other in seen else expand(other)

        return INCLUDE.sub(include, source(current))

    return expand(name)


#: the shipped encodings each encoding needs loaded beside it (tree.lp defines use/1, reach/1, ...;
#: the objectives are loaded with closed.lp or prepared.lp too, so they cannot include it)
DEPENDS: dict[str, tuple[str, ...]] = dict.fromkeys(
    ("reachable", "dominance", "units", "success", "inputs", "cost", "human", "greedy", "substitutes"), ("tree",)
)


def with_dependencies(wanted: list[str] | tuple[str, ...]) -> list[str]:
    """``wanted`` with what each needs beside it (:data:`DEPENDS`, also for the encodings it
    includes), each name once, needed ones first."""
    out: list[str] = []

    def needs(name: str) -> list[str]:
        included = [m.group("name") for m in INCLUDE.finditer(source(name))]
        return [*DEPENDS.get(name, ()), *(dep for other in included for dep in needs(other))]

    def visit(name: str) -> None:
        for dep in needs(name):
            visit(dep)
        if name not in out:
            out.append(name)

    for name in wanted:
        visit(name)
    return out
