"""The one registry of methods: ASP objectives and the search baselines.

A method turns (problem, options) into a *runner*: a function from a goal
object id (or, for ASP methods, a tuple of them: a meal, one tree for every
goal) to a :class:`TaskTree`.  Runners are made once per problem, so a
runner may keep state (the ASP runner keeps one grounding for all goals).
The CLI's ``solve``, ``compare`` and ``batch`` all look methods up here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

from foon2asp.asp.options import HEURISTICS, OBJECTIVES, AspOptions
from foon2asp.asp.session import Session
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem
from foon2asp.search import IDS, gbfs, h1, h2
from foon2asp.tree.tasktree import Goals, TaskTree, meal_of

Runner = Callable[[Goals], TaskTree]
Factory = Callable[[Problem, AspOptions], Runner]


@dataclass(frozen=True)
class Method:
    name: str
    kind: str  # "asp" or "search"
    description: str
    factory: Factory
    #: for ASP methods: the options the method's sessions solve with, from the caller's
    adjust: Callable[[AspOptions], AspOptions] | None = None


METHODS: dict[str, Method] = {}


def register(
    name: str, kind: str, description: str, adjust: Callable[[AspOptions], AspOptions] | None = None
) -> Callable[[Factory], Factory]:
    """Decorator: register ``factory`` under ``name``."""

    def deco(factory: Factory) -> Factory:
        METHODS[name] = Method(name, kind, description, factory, adjust)
        return factory

    return deco


def effective_options(name: str, options: AspOptions | None = None) -> AspOptions:
    """The options an ASP method ``name`` solves with when called with ``options``."""
    options = options or AspOptions()
    adjust = get(name).adjust
    return adjust(options) if adjust is not None else options


def get(name: str) -> Method:
    try:
        return METHODS[name]
    except KeyError:
        raise InputError(f"unknown method {name!r} (have {', '.join(names())})") from None


def names() -> list[str]:
    return list(METHODS)


def runner(name: str, problem: Problem, options: AspOptions | None = None) -> Runner:
    return get(name).factory(problem, options or AspOptions())


@register("asp", "asp", "answer-set programming, proven optimal for --objective (default: units)")
def _asp(problem: Problem, options: AspOptions) -> Runner:
    return Session(problem, options).solve


def _adjusted(adjust: Callable[[AspOptions], AspOptions]) -> Factory:
    def factory(problem: Problem, options: AspOptions) -> Runner:
        return Session(problem, adjust(options)).solve

    return factory


def _objective_is(objective: str) -> Callable[[AspOptions], AspOptions]:
    return lambda options: replace(options, objective=(objective,))


def _heuristic_is(heuristic: str) -> Callable[[AspOptions], AspOptions]:
    return lambda options: replace(options, heuristic=heuristic)


for _name in list(OBJECTIVES):
    _adjust = _objective_is(_name)
    register(f"asp-{_name}", "asp", f"ASP, proven optimal for the objective {_name!r}", _adjust)(_adjusted(_adjust))


_GREEDY = {"h1": "highest motion success rate", "h2": "fewest input nodes"}
for _h in HEURISTICS:
    _adjust = _heuristic_is(_h)
    register(
        f"asp-greedy-{_h}",
        "asp",
        f"ASP first model under #heuristic {_h} ({_GREEDY[_h]}), valid by construction",
        _adjust,
    )(_adjusted(_adjust))


def _single(name: str, run: Callable[[int], TaskTree]) -> Runner:
    """A search baseline's runner: one goal at a time (meals need an ASP method)."""

    def runner(goal: Goals) -> TaskTree:
        meal = meal_of(goal)
        if len(meal) > 1:
            raise InputError(f"meals (several goals in one tree) need an ASP method; {name!r} is a search baseline")
        return run(meal[0])

    return runner


# the search baselines (foon2asp.search knows nothing of this registry)
register("ids", "search", "iterative deepening search (first producer in FOON order per depth; not optimal)")(
    lambda problem, options: _single("ids", IDS(problem))
)
register("gbfs-h1", "search", "greedy best-first, h1: highest motion success rate (no cycle check)")(
    lambda problem, options: _single("gbfs-h1", lambda goal: gbfs(problem, goal, h1, "gbfs-h1"))
)
register("gbfs-h2", "search", "greedy best-first, h2: fewest input nodes (no cycle check)")(
    lambda problem, options: _single("gbfs-h2", lambda goal: gbfs(problem, goal, h2, "gbfs-h2"))
)
