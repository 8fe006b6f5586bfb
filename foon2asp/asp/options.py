"""How to solve: objectives, extra programs, bounds and solver settings (:class:`AspOptions`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from foon2asp.asp.settings import solver_args
from foon2asp.foon.substitutes import Substitute

#: objective name -> encoding that defines it (all use objective(Name,Priority))
OBJECTIVES: dict[str, str] = {"units": "units", "success": "success", "inputs": "inputs", "depth": "depth"}
#: the summed motion cost of a motion-cost table (AspOptions.motion_costs, foon2asp.foon.motioncost)
OBJECTIVES["cost"] = "cost"

#: greedy retrieval inside the solver (AspOptions.heuristic -> encodings/greedy_NAME.lp)
HEURISTICS = ("h1", "h2")


@dataclass
class AspOptions:
    """How to solve: objectives (lexicographic, first = most important) and solver settings."""

    objective: tuple[str, ...] = ("units",)
    #: extra ASP programs as (name, text): user constraints and the like
    programs: list[tuple[str, str]] = field(default_factory=list)
    #: extra encodings (names in encodings/) to load
    encodings: list[str] = field(default_factory=list)
    time_limit: float | None = None
    #: clingo's --opt-strategy; None: the default of foon2asp.asp.settings (usc; a portfolio with threads > 1)
    opt_strategy: str | None = None
    threads: int = 1
    #: threads > 1 without opt_strategy: the portfolio (clasp's configuration-file text); None: the default
    portfolio: str | None = None
    clingo_args: list[str] = field(default_factory=list)
    #: ground only these units (e.g. the goals' relevant units); None: all units
    units: tuple[int, ...] | None = None
    #: only trees of at most this many sequential rounds (see foon2asp.asp.multishot.depth)
    max_depth: int | None = None
    #: at most this many units may be done by a person (success 1.0 for those)
    human_steps: int | None = None
    #: the K best distinct trees per goal, best first
    models: int = 1
    #: every optimal tree, at most all_optimal_cap of them
    all_optimal: bool = False
    all_optimal_cap: int = 100
    #: "h1" | "h2": greedy retrieval in the solver (first model under #heuristic)
    heuristic: str | None = None
    #: among several optimal trees, return the lexicographically smallest (foon2asp.asp.canonical)
    canonical: bool = True
    #: the objective "cost": motion -> integer weight, the cost in hundredths (foon2asp.foon.motioncost);
    #: a motion not listed weighs 100 (cost 1); None: no table (the objective "cost" is refused)
    motion_costs: dict[str, int] | None = None
    #: labels that may stand in for others (foon2asp.foon.substitutes): the fewest (cheapest)
    #: substitutions rank above the objectives (foon2asp.asp.substitutes)
    substitutes: tuple[Substitute, ...] = ()
    #: at most this many substitutions per tree
    max_substitutions: int | None = None
    #: stop a goal once its gap (foon2asp.tree.gap) is at most this (0.05: 5 %); None: prove
    gap: float | None = None
    #: called while a goal is solved with ``{"cost": [...], "lower": [...], "gap": g}`` (solver
    #: weights per level; gap None while unknown) at each model and each proven lower bound
    progress: Callable[[dict], None] | None = field(default=None, compare=False, repr=False)

    @property
    def method(self) -> str:
        if self.heuristic:
            return f"asp-greedy-{self.heuristic}"
        return "asp-" + ",".join(self.objective)

    @property
    def driven(self) -> bool:
        """Does solving need foon2asp.asp.multishot.driver (more than one plain optimisation)?"""
        return bool(
            self.heuristic
            or self.max_depth is not None
            or self.human_steps is not None
            or self.models > 1
            or self.all_optimal
            or "depth" in self.objective
        )

    def args(self) -> list[str]:
        args = ["--opt-mode=opt"]
        if self.heuristic:
            args.append("--heuristic=Domain")
        args += solver_args(self.opt_strategy, self.threads, self.portfolio)
        return args + list(self.clingo_args)
