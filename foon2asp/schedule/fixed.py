"""A fixed tree's schedule: the shortest makespan, proven, then the fewest units done by a
``human`` agent (:func:`schedule_fixed`).

Statuses: ``optimal`` (makespan proven minimal), ``feasible`` (the time limit ended the
search), ``unschedulable`` (a unit of the tree no agent can do), ``unreachable`` (no tree
makes the goal), ``unknown`` (no tree was found in time).  A list schedule that meets the
lower bound (and the fewest human units) is optimal without a solver; otherwise the solver
starts from the best list schedule.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

from foon2asp.asp import objectives
from foon2asp.asp.options import AspOptions, solver_args
from foon2asp.foon.problem import Problem
from foon2asp.schedule import encode
from foon2asp.schedule.baseline import TRIES, known_schedule, list_schedule
from foon2asp.schedule.bounds import bounds, human_lower
from foon2asp.schedule.model import (
    Entry,
    Instance,
    compact,
    designate,
    divisor,
    earliest,
    human_units,
    instance,
    makespan,
    tails,
)
from foon2asp.schedule.result import ScheduleResult
from foon2asp.schedule.spec import HUMAN, ScheduleSpec
from foon2asp.tree.tasktree import TaskTree

#: the encoding chosen by measurement (BENCHMARKS.md, "Schedules")
DEFAULT_ENCODING = "steps"

#: clasp's optimisation strategy for schedules when the options set none (BENCHMARKS.md)
OPT_STRATEGY = "bb"

#: perturbed list-scheduling runs for each tree a joint search schedules (a fixed tree: TRIES)
JOINT_TRIES = 4


def solver_arguments(options: AspOptions) -> list[str]:
    return solver_args(options.opt_strategy or OPT_STRATEGY, options.threads, options.portfolio)


def forced_human(inst: Instance) -> int:
    """Units only a person can do (every schedule gives them to one)."""
    return sum(1 for u in inst.units if inst.durations[u] and set(inst.durations[u]) == {HUMAN})


def solve_encoded(
    inst: Instance,
    head: dict[int, int],
    tail: dict[int, int],
    horizon: int | None,
    floor: int,
    options: AspOptions,
    encoding: str,
    time_limit: float | None,
    tree_parts: list[tuple[str, str]] | None = None,
    ties: bool = True,
    known: list[Entry] | None = None,
    progress: Callable[[dict], None] | None = None,
) -> encode.Solution:
    """Solve with ``encoding`` (:class:`foon2asp.schedule.encode.Job` says what the values are)."""
    job = encode.Job(
        inst,
        head,
        tail,
        horizon,
        floor,
        solver_arguments(options),
        tree_parts or (),
        len(objectives.ranked(options)) if tree_parts else 0,
        [name for name, _ in options.programs] if tree_parts else [],
        ties,
        known,
        progress,
    )
    return encode.solve(job, encoding, time_limit)


def schedule_fixed(
    problem: Problem,
    tree: TaskTree,
    spec: ScheduleSpec,
    options: AspOptions,
    encoding: str = DEFAULT_ENCODING,
    time_limit: float | None = None,
    shortcut: bool = True,
    within: int | None = None,
    progress: Callable[[dict], None] | None = None,
    first: Sequence[tuple[int, int]] = (),
) -> ScheduleResult:
    """The optimal schedule of ``tree``'s units.

    ``within`` (ms; joint scheduling): only a schedule of at most that makespan matters; when
    there is none the status is ``unschedulable``.  ``progress``: as for
    :class:`foon2asp.schedule.encode.Job`.  ``first`` (joint scheduling): (object, maker)
    pairs, :func:`foon2asp.schedule.model.designate`."""
    t0 = time.perf_counter()

    def none(status: str, reason: str | None) -> ScheduleResult:
        agents = [name for name, _ in spec.agent_list()]
        return ScheduleResult(problem, tree, status, agents, reason=reason, time_s=time.perf_counter() - t0)

    if not tree.has_tree:
        return none(
            "unreachable" if tree.status in ("unreachable", "not-found") else "unknown", tree.extra.get("reason")
        )
    inst = designate(instance(problem, tree.units, spec), first)
    agents = [name for name, _ in inst.agents]
    bad = inst.incapable()
    if bad:
        return none("unschedulable", f"no agent can do unit {bad[0]} ({problem.units[bad[0]].motion})")
    if len(earliest(inst)) < len(inst.units):
        return none("unschedulable", "some unit of the tree never has its inputs")
    b = bounds(inst)
    base = list_schedule(inst)
    ub = makespan(base)
    late = f"no schedule within {within} ms"
    if within is not None and b.lower > within:
        return none("unschedulable", late)
    # the baseline, or a shorter list schedule, or one with fewer human units; a tree of a
    # joint search tries a few only
    least = max(forced_human(inst), human_lower(inst, b.lower)) if spec.has_human() else 0
    done = ub <= b.lower and human_units(base) <= least
    tries = TRIES if within is None else JOINT_TRIES
    known, which = (base, "baseline") if done else known_schedule(inst, b.lower, tries)
    over = within is not None and makespan(known) > within
    stats: dict = {"encoding": encoding}
    if not over and shortcut and makespan(known) == b.lower and human_units(known) <= least:
        stats["shortcut"] = f"{which} meets the lower bound"
        return ScheduleResult(
            problem, tree, "optimal", agents, known, b, ub, time_s=time.perf_counter() - t0, stats=stats
        )
    if over:  # is there a schedule within ``within`` at all (dl asks below its horizon first)?
        assert within is not None
        horizon = within + divisor(inst) if encoding == "dl" else within
    else:
        horizon = makespan(known) if encoding == "steps" else ub
    start = known if encoding == "steps" and not over else None
    sol = solve_encoded(
        inst,
        earliest(inst),
        tails(inst),
        horizon,
        b.lower,
        options,
        encoding,
        time_limit,
        ties=spec.has_human(),
        known=start,
        progress=progress,
    )
    stats.update(sol.stats)
    if over and sol.entries is None:
        return none("unschedulable" if sol.proven or sol.unsatisfiable else "unknown", late)
    entries = known
    if sol.entries is not None and (over or makespan(sol.entries) <= makespan(known)):
        entries = compact(inst, sol.entries)
    # without tie-breakers a schedule at the lower bound is optimal, however the search ended
    met = not over and makespan(entries) <= b.lower and not spec.has_human()
    status = "optimal" if sol.proven or met else "feasible"
    return ScheduleResult(problem, tree, status, agents, entries, b, ub, time_s=time.perf_counter() - t0, stats=stats)
