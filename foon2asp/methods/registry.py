"""The one registry of methods: ASP objectives and the search baselines.

An ASP method adjusts the caller's options (the objective, the greedy heuristic); a search
baseline has a factory turning (problem, options) into a function from a goal object id to a
:class:`TaskTree`.  ``solve``, ``compare`` and ``batch`` all look methods up here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import partial

from foon2asp.asp.options import HEURISTICS, OBJECTIVES, AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem
from foon2asp.search import IDS, gbfs, h1, h2
from foon2asp.tree.tasktree import Goals, TaskTree

Runner = Callable[[Goals], TaskTree]
#: a search baseline's runner: one goal object id at a time
SearchRunner = Callable[[int], TaskTree]
Factory = Callable[[Problem, AspOptions], SearchRunner]


@dataclass(frozen=True)
class Method:
    name: str
    kind: str  # "asp" or "search"
    description: str
    #: for search baselines: (problem, options) -> the runner of one goal at a time
    factory: Factory | None = None
    #: for ASP methods: the options the method's sessions solve with, from the caller's
    adjust: Callable[[AspOptions], AspOptions] | None = None


METHODS: dict[str, Method] = {}


def register(name: str, kind: str, description: str) -> Callable[[Factory], Factory]:
    """Decorator: register the search baseline ``factory`` under ``name`` (ASP methods: :func:`register_asp`)."""
    if kind == "asp":
        raise ValueError(f"register the ASP method {name!r} with register_asp")

    def deco(factory: Factory) -> Factory:
        METHODS[name] = Method(name, kind, description, factory)
        return factory

    return deco


def register_asp(name: str, description: str, adjust: Callable[[AspOptions], AspOptions] | None = None) -> None:
    """Register an ASP method: the goal runner solves it with ``adjust(options)``."""
    METHODS[name] = Method(name, "asp", description, adjust=adjust)


def effective_options(name: str, options: AspOptions) -> AspOptions:
    """The options an ASP method ``name`` solves with when called with ``options``."""
    adjust = get(name).adjust
    return adjust(options) if adjust is not None else options


def get(name: str) -> Method:
    try:
        return METHODS[name]
    except KeyError:
        raise InputError(f"unknown method {name!r} (have {', '.join(names())})") from None


def names() -> list[str]:
    return list(METHODS)


register_asp("asp", "answer-set programming, proven optimal for --objective (default: units)")
for _name in OBJECTIVES:
    register_asp(
        f"asp-{_name}", f"ASP, proven optimal for the objective {_name!r}", partial(replace, objective=(_name,))
    )
for _h, _words in zip(HEURISTICS, ("highest motion success rate", "fewest input nodes"), strict=True):
    register_asp(
        f"asp-greedy-{_h}",
        f"ASP first model under #heuristic {_h} ({_words}), valid by construction",
        partial(replace, heuristic=_h),
    )

# the search baselines (foon2asp.search knows nothing of this registry); the goal runner
# hands them one goal at a time
register("ids", "search", "iterative deepening search (first producer in FOON order per depth; not optimal)")(
    lambda problem, options: IDS(problem)
)
register("gbfs-h1", "search", "greedy best-first, h1: highest motion success rate (no cycle check)")(
    lambda problem, options: partial(gbfs, problem, score=h1, method="gbfs-h1")
)
register("gbfs-h2", "search", "greedy best-first, h2: fewest input nodes (no cycle check)")(
    lambda problem, options: partial(gbfs, problem, score=h2, method="gbfs-h2")
)
