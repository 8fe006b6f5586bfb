"""One request's settings: what to optimise, the constraints, how to solve and for how long.

The keyword arguments of the answers are mapped onto :class:`Options` by :meth:`Options.of`,
the one place that knows them."""

from __future__ import annotations

import difflib
import json
import math
from collections.abc import Callable, Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from foon2asp.asp.constraints import ConstraintSpec
from foon2asp.asp.options import AspOptions, check_objectives, clingo_options
from foon2asp.batch.pool import AUTO
from foon2asp.errors import InputError
from foon2asp.foon.model import FoonObject
from foon2asp.foon.motioncost import MotionCosts, parse_motion_costs, read_motion_costs
from foon2asp.foon.substitutes import Substitute, parse_substitutes, read_substitutes
from foon2asp.schedule import DEFAULT_ENCODING, ScheduleSpec

#: user constraints: an ASP file, rule texts, the forbid/require/max-units conveniences
Constraints = ConstraintSpec

#: a motion-cost table: a file (JSON object or motion<TAB>cost lines), a table read already, or motion -> cost
MotionCostLike = str | Path | MotionCosts | Mapping[str, object]

#: substitutes: a file, a mapping needed -> list of labels (or label -> cost), or Substitute values
SubstitutesLike = str | Path | Mapping[str, object] | Sequence[Substitute]

#: the constraint keywords of the answers -> field of :data:`Constraints`
CONSTRAINT_KEYWORDS = {
    "constraint_files": "files",
    "rules": "rules",
    "forbid_motions": "forbid_motion",
    "forbid_objects": "forbid_object",
    "require_motions": "require_motion",
    "require_objects": "require_object",
    "max_units": "max_units",
}

#: the keywords of a schedule request that name its agents and tables (:func:`schedule_request`)
SPEC_KEYWORDS = ("agents", "durations", "capabilities", "resources")

#: why a value is not a time limit, in the words the command line's ``--time-limit`` uses too
NOT_A_TIME_LIMIT = "is not a finite number of seconds > 0"


def check_keywords(given: Iterable[str], known: Collection[str], where: str = "") -> None:
    """Raise a TypeError naming the keywords of ``given`` not in ``known``, each with the closest known one."""
    unknown = sorted(set(given) - set(known))
    if not unknown:
        return
    names = sorted(known)
    close = {name: difflib.get_close_matches(name, names, n=1) for name in unknown}
    parts = [f"{name!r} (did you mean {found[0]!r}?)" if found else repr(name) for name, found in close.items()]
    word = "argument" if len(parts) == 1 else "arguments"
    known_ones = "" if all(close.values()) else f"; the keywords are {', '.join(names)}"
    raise TypeError(f"{where}unexpected keyword {word} {', '.join(parts)}{known_ones}")


@dataclass(frozen=True)
class Options:
    """The settings of one request; every field has the default of a call without it (docs/api.md)."""

    #: lexicographic, most important first: ``units``, ``success``, ``inputs``, ``depth``, ``cost``
    objective: tuple[str, ...] = ("units",)
    constraints: Constraints = field(default_factory=Constraints)
    #: seconds per goal (a finite number > 0; None: no limit); the best tree so far is then ``feasible``
    time_limit: float | None = None
    #: stop a goal once its relative gap (first objective) is at most this, e.g. 0.05; None (and 0): prove it
    gap: float | None = None
    #: called with ``{"cost": [...], "lower": [...], "gap": g}`` at each better tree and lower bound
    on_progress: Callable[[dict], None] | None = field(default=None, compare=False, repr=False)
    #: the K best distinct trees per goal
    models: int = 1
    #: every optimal tree per goal
    all_optimal: bool = False
    #: only trees of at most this many sequential rounds
    max_depth: int | None = None
    #: at most this many units done by a person (success 1.0)
    human_steps: int | None = None
    #: clingo's optimisation strategy (``bb``, ``usc``, with refinements); None: the default of foon2asp.asp.options.solver_args
    opt_strategy: str | None = None
    #: clingo solver threads; None: one
    threads: int | None = None
    #: more of clingo's own command-line options, e.g. ``("--configuration=crafty",)``; clingo checks them here
    clingo_args: tuple[str, ...] = ()
    #: batch: ``whole``, ``per-goal`` or ``auto`` (foon2asp.methods.parts.choose_grounding)
    grounding: str = "auto"
    #: batch: answer without the solver when the answer is forced
    shortcuts: bool = True
    #: the motion-cost table: the objective ``cost`` needs it, and with it every tree's measures include ``cost``
    motion_cost: MotionCostLike | None = None
    #: labels that may stand in for others: a tree uses the fewest (cheapest) substitutions first
    substitutes: SubstitutesLike | None = None
    #: at most this many substitutions per tree
    max_substitutions: int | None = None

    def __new__(cls, *args: object, **kwargs: object) -> Options:
        check_keywords(kwargs, [f.name for f in fields(cls)], "Options(): ")
        return super().__new__(cls)

    def __post_init__(self) -> None:
        value = self.objective
        parts = [p.strip() for p in value.split(",")] if isinstance(value, str) else [str(p).strip() for p in value]
        object.__setattr__(self, "objective", tuple(p for p in parts if p) or ("units",))
        if self.constraints is None:
            object.__setattr__(self, "constraints", Constraints())
        given = self.clingo_args
        object.__setattr__(
            self, "clingo_args", tuple(clingo_options([given] if isinstance(given, str) else given or ()))
        )
        limit = self.time_limit
        if limit is not None and (isinstance(limit, bool) or not isinstance(limit, int | float)):
            raise InputError(f"time_limit: {limit!r} is not a number of seconds (None: no limit)")
        if limit is not None and (not math.isfinite(limit) or limit <= 0):
            raise InputError(f"time_limit: {limit!r} {NOT_A_TIME_LIMIT} (None: the default)")

    @classmethod
    def of(cls, options: Options | None = None, /, **settings: Any) -> Options:
        """``options`` (default: all defaults) with the keyword ``settings`` (:data:`KEYWORDS`) applied."""
        base = options if options is not None else cls()
        check_keywords(settings, KEYWORDS)
        changes: dict = {k: v for k, v in settings.items() if k not in CONSTRAINT_KEYWORDS}
        spec = {
            CONSTRAINT_KEYWORDS[k]: v if k == "max_units" else tuple(str(x) for x in v)
            for k, v in settings.items()
            if k in CONSTRAINT_KEYWORDS
        }
        if spec:
            changes["constraints"] = replace(changes.get("constraints") or base.constraints, **spec)
        return replace(base, **changes) if changes else base

    def motion_table(self) -> MotionCosts | None:
        """The motion-cost table of the request, read and checked (None without one)."""
        table = self.motion_cost
        if table is None or isinstance(table, MotionCosts):
            return table
        if isinstance(table, Mapping):
            lines = "".join(f"{motion}\t{cost}\n" for motion, cost in table.items())
            return parse_motion_costs(lines, "motion_cost")
        return read_motion_costs(table)

    def substitute_table(self) -> tuple[Substitute, ...]:
        """The request's substitutes, read and checked (empty without any)."""
        given = self.substitutes
        if given is None:
            return ()
        if isinstance(given, str | Path):
            return read_substitutes(given)
        if isinstance(given, Mapping):
            return parse_substitutes(json.dumps(dict(given)), "substitutes")
        found = tuple(given)
        if not all(isinstance(s, Substitute) for s in found):
            raise InputError("substitutes: give a file, a mapping label -> [labels] or Substitute values")
        return found

    @property
    def solver_settings(self) -> dict[str, object]:
        """The settings only the ASP methods use that differ from their defaults."""
        defaults = {"max_depth": None, "human_steps": None, "models": 1, "all_optimal": False, "opt_strategy": None}
        given = {k: getattr(self, k) for k, v in defaults.items() if getattr(self, k) != v}
        if self.threads not in (None, 1):
            given["threads"] = self.threads
        if self.clingo_args:
            given["clingo_args"] = self.clingo_args
        return given

    def solver(self) -> AspOptions:
        """The solver's options: objective names, the human-steps rule, the gap and the constraint programs checked."""
        check_objectives(self.objective)
        if "cost" in self.objective and self.motion_cost is None:
            raise InputError(
                "the objective 'cost' needs a motion-cost table: motion_cost=FILE (a JSON object motion -> cost,"
                " or motion<TAB>cost lines)",
                hint="motion-cost",
            )
        if self.human_steps is not None and "success" not in self.objective:
            suggestion = f"{','.join(self.objective)},success"
            raise InputError(
                "human steps only change the tree when 'success' is an objective (a person's step succeeds"
                f" for sure); rank it among the objectives, e.g. {suggestion}",
                hint=f"human-steps={suggestion}",
            )
        bound = self.max_substitutions
        if bound is not None and (isinstance(bound, bool) or not isinstance(bound, int) or bound < 0):
            raise InputError(f"max_substitutions must be an integer >= 0, not {bound!r}")
        if self.gap is not None and not (isinstance(self.gap, int | float) and 0 <= self.gap < math.inf):
            raise InputError(f"the gap must be a number >= 0 (0.05 stops at 5 %), not {self.gap!r}", hint="gap")
        return AspOptions(
            objective=self.objective,
            shortcuts=self.shortcuts,
            time_limit=self.time_limit,
            gap=self.gap or None,
            progress=self.on_progress,
            programs=self.constraints.programs(),
            max_depth=self.max_depth,
            human_steps=self.human_steps,
            models=self.models,
            all_optimal=self.all_optimal,
            substitutes=self.substitute_table(),
            max_substitutions=self.max_substitutions,
            opt_strategy=self.opt_strategy,
            threads=1 if self.threads is None else self.threads,
            clingo_args=list(self.clingo_args),
        )


#: the keywords of a request: the fields of :class:`Options` and the constraint keywords
KEYWORDS = frozenset(f.name for f in fields(Options)) | frozenset(CONSTRAINT_KEYWORDS)


def schedule_request(spec: ScheduleSpec | None, settings: dict[str, Any]) -> dict[str, Any]:
    """The schedule keywords taken out of ``settings``: ``spec`` (or the files that make one), ``joint``, ``encoding``."""
    agents, *files = (settings.pop(k, None) for k in SPEC_KEYWORDS)
    how = {"joint": settings.pop("joint", False), "encoding": settings.pop("encoding", DEFAULT_ENCODING)}
    if spec is not None:
        if agents is not None or any(f is not None for f in files):
            raise InputError("give a ScheduleSpec or agents/durations/capabilities/resources, not both")
        return {"spec": spec, **how}
    if isinstance(agents, Mapping):
        agents = ",".join(f"{kind}={n}" for kind, n in agents.items())
    return {"spec": ScheduleSpec.from_files(agents, *files), **how}


def jobs(ids: Sequence[int], together: bool) -> list[int | tuple[int, ...]]:
    """The goals ``ids`` one by one, or with ``together`` one meal of them (a tuple)."""
    return [tuple(dict.fromkeys(ids))] if together else list(ids)


def one_goal(goals: object) -> bool:
    """Does ``goals`` name one goal (the answer is one value, not a list)?"""
    return isinstance(goals, str | int | FoonObject) and goals not in ("all", "all-objects")


def workers_count(workers: int | str) -> int:
    """``workers`` of a batch as the pool takes it (``"auto"``: :data:`foon2asp.batch.pool.AUTO`)."""
    if isinstance(workers, str) and workers.strip().lower() == "auto":
        return AUTO
    if isinstance(workers, bool) or not isinstance(workers, int) or not 1 <= workers <= 1024:
        raise InputError(f"workers must be 1..1024 or 'auto', not {workers!r}")
    return workers
