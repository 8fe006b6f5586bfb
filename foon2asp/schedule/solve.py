"""The library entry point: :func:`schedule` a goal's task tree, or choose tree and schedule together.

Statuses: ``optimal`` (makespan proven minimal), ``feasible`` (the time limit ended the
search), ``unschedulable`` (no agent can do a unit; joint: no valid tree can be scheduled),
``unreachable`` (no tree makes the goal), ``unknown`` (no tree was found in time).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace

from foon2asp.asp import objectives
from foon2asp.asp.options import AspOptions, solver_args, with_clingo_args
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem
from foon2asp.schedule import encode, instances, joint
from foon2asp.schedule.baseline import TRIES, known_schedule, list_schedule
from foon2asp.schedule.instances import Entry, Instance, earliest, human_units, instance, makespan
from foon2asp.schedule.joint import check_options
from foon2asp.schedule.lower_bounds import MakespanBounds, bounds, human_lower
from foon2asp.schedule.result import ScheduleResult
from foon2asp.schedule.spec import HUMAN, ScheduleSpec
from foon2asp.tree.tasktree import TaskTree, executable_order, goal_fields, measures

__all__ = ["DEFAULT_ENCODING", "DEFAULT_TIME_LIMIT", "schedule", "schedule_fixed", "schedule_joint"]

#: seconds per solve (the fixed tree's schedule, the joint search) when no time limit is given
DEFAULT_TIME_LIMIT = 60.0

#: the encoding chosen by measurement (BENCHMARKS.md, "Schedules")
DEFAULT_ENCODING = "steps"

#: clasp's optimisation strategy for schedules when the options set none (BENCHMARKS.md)
OPT_STRATEGY = "bb"

#: perturbed list-scheduling runs for each tree a joint search schedules (a fixed tree: TRIES)
JOINT_TRIES = 4


def solver_arguments(options: AspOptions) -> list[str]:
    return with_clingo_args(
        solver_args(options.opt_strategy or OPT_STRATEGY, options.threads, options.portfolio), options.clingo_args
    )


def forced_human(inst: Instance) -> int:
    """Units only a person can do (every schedule gives them to one)."""
    return sum(1 for u in inst.units if inst.durations[u] and set(inst.durations[u]) == {HUMAN})


@dataclass(frozen=True)
class Request:
    """What every schedule of one call shares: the problem, the agents, the solver's settings."""

    problem: Problem
    spec: ScheduleSpec
    options: AspOptions
    encoding: str
    shortcut: bool


def schedule_fixed(
    req: Request,
    tree: TaskTree,
    time_limit: float | None,
    within: int | None = None,
    progress: Callable[[dict], None] | None = None,
    first: Sequence[tuple[int, int]] = (),
    lower: MakespanBounds | None = None,
) -> ScheduleResult:
    """The optimal schedule of ``tree``'s units.

    Joint scheduling: ``within`` (ms), only a schedule of at most that makespan matters (none:
    ``unschedulable``); ``first``, (object, maker) pairs for :func:`instances.designate`;
    ``lower``, the designated tree's bounds when known."""
    t0 = time.perf_counter()
    problem, spec, encoding = req.problem, req.spec, req.encoding

    def result(status: str, entries: Sequence[Entry] = (), **more) -> ScheduleResult:
        agents = [name for name, _ in spec.agent_list()]
        return ScheduleResult(problem, tree, status, agents, list(entries), time_s=time.perf_counter() - t0, **more)

    if not tree.has_tree:
        missing = "unreachable" if tree.status in ("unreachable", "not-found") else "unknown"
        return result(missing, reason=tree.reason)
    inst = instances.designate(instance(problem, tree.units, spec), first)
    bad = inst.incapable()
    if bad:
        return result("unschedulable", reason=f"no agent can do unit {bad[0]} ({problem.units[bad[0]].motion})")
    head = earliest(inst)
    if len(head) < len(inst.units):
        return result("unschedulable", reason="some unit of the tree never has its inputs")
    b = bounds(inst) if lower is None else lower
    base = list_schedule(inst)
    ub = makespan(base)
    late = f"no schedule within {within} ms"
    if within is not None and b.lower > within:
        return result("unschedulable", reason=late)
    least = max(forced_human(inst), human_lower(inst, b.lower)) if spec.has_human() else 0
    done = ub <= b.lower and human_units(base) <= least
    tries = TRIES if within is None else JOINT_TRIES
    known, which = (base, "baseline") if done else known_schedule(inst, b.lower, tries, least)
    over = within is not None and makespan(known) > within
    stats: dict = {"encoding": encoding}
    if not over and req.shortcut and makespan(known) == b.lower and human_units(known) <= least:
        stats["shortcut"] = f"{which} meets the lower bound"
        return result("optimal", known, bounds=b, baseline=ub, stats=stats)
    if over:  # is there a schedule within ``within`` at all (dl asks below its horizon first)?
        assert within is not None
        horizon = within + instances.divisor(inst) if encoding == "dl" else within
    else:
        horizon = makespan(known) if encoding == "steps" else ub
    start = known if encoding == "steps" and not over else None
    args = solver_arguments(req.options)
    job = encode.Job(inst, head, instances.tails(inst), horizon, b.lower, args, known=start, progress=progress)
    sol = encode.solve(job, encoding, time_limit)
    stats.update(sol.stats)
    if over and sol.entries is None:
        return result("unschedulable" if sol.proven or sol.unsatisfiable else "unknown", reason=late)
    entries = known
    if sol.entries is not None and (over or makespan(sol.entries) <= makespan(known)):
        entries = instances.compact(inst, sol.entries)
    # without tie-breakers a schedule at the lower bound is optimal
    met = not over and makespan(entries) <= b.lower and not spec.has_human()
    return result("optimal" if sol.proven or met else "feasible", entries, bounds=b, baseline=ub, stats=stats)


@dataclass(frozen=True)
class JointRequest(Request):
    """A joint scheduling request: the given tree and its own (``fixed``) schedule;
    ``lower``: the bounds of each designated tree the search has bounded."""

    tree: TaskTree
    fixed: ScheduleResult
    lower: dict[joint.DesignatedTree, MakespanBounds] = field(default_factory=dict, compare=False, repr=False)

    def solve(self, cand: joint.DesignatedTree, limit: float | None, within: int | None) -> ScheduleResult:
        """The schedule of a designated tree (time left ``limit``; only one of at most ``within``
        matters); the given tree's own when it is that tree and proven."""
        units, first = cand
        if units == tuple(sorted(self.tree.units)) and self.fixed.status == "optimal":
            return self.fixed
        return schedule_fixed(
            self, self.tree_of(units, "optimal"), limit, within, first=first, lower=self.lower.get(cand)
        )

    def tree_of(self, units: Sequence[int], status: str) -> TaskTree:
        """The task tree of ``units`` for the goals of the given tree."""
        meal = self.tree.meal
        return TaskTree(
            method=f"{self.tree.method}+schedule",
            status=status,
            units=executable_order(self.problem, list(units)),
            cost=measures(self.problem, meal, list(units)),
            **goal_fields(meal),
        )

    def none(self) -> ScheduleResult:
        """The joint answer when no valid tree of the goal can be scheduled."""
        why = "no valid tree of the goal can be scheduled"
        return ScheduleResult(
            self.problem, self.tree, "unschedulable", self.fixed.agents, joint=True, fixed=self.fixed, reason=why
        )

    def rank(self, r: ScheduleResult) -> tuple:
        """A joint answer's rank: makespan, human units, the tree objective."""
        ranked = objectives.ranked(self.options)
        return (r.makespan, len(r.human), joint.tree_cost(self.problem, r.tree.units, r.human, ranked))


def _by_trees(
    job: JointRequest, listing: encode.Job, left: Callable[[], float | None]
) -> tuple[ScheduleResult | None, bool, ScheduleResult | None]:
    """Joint scheduling tree by tree (:mod:`foon2asp.schedule.joint`): (result, proven, partial).

    The result is None when the trees are too many to look at in time, or when ``listing.ties``
    leaves the tie-breakers to the one encoding (``proven``: the given makespan is the optimum);
    an unproven answer from the trees asked for least work first is ``partial``.  The given
    tree's schedule wins a tie."""
    problem, spec, inst, fixed = job.problem, job.spec, listing.inst, job.fixed
    single = len(inst.agents) == 1
    share = left()
    # one agent: the makespan is the tree's work, so the trees are asked for least work first
    trees, complete = ([], False) if single else joint.candidate_trees(listing, None if share is None else share / 3)
    if not single and not complete and left() == 0.0:
        return None, False, None
    ranked = objectives.ranked(job.options)

    def bound(cand: joint.DesignatedTree) -> tuple:
        """A lower bound on the rank of the designated tree's schedule."""
        units, first = cand
        sub = instances.designate(inst.restrict(units), first)
        if len(earliest(sub)) < len(units):  # the designated makers wait for one another
            return (math.inf, 0, ())
        b = job.lower[cand] = bounds(sub)
        low = b.lower
        if spec.has_human():
            return (low, forced_human(sub), ())
        return (low, 0, joint.tree_cost(problem, units, (), ranked))

    if complete:
        best, proven = joint.JointSearch(job.solve, job.rank, bound, encode.clock(left())).over(trees)
    else:  # too many to list: one at a time, least work first
        share = left()
        if not single and share is not None:
            share /= 4
        first = single and not spec.has_human()  # a person alone: fewest units among equal work
        search = joint.JointSearch(job.solve, job.rank, bound, encode.clock(share))
        best, proven = search.by_work(listing, len(ranked), first)
    if fixed.has_schedule and (best is None or job.rank(fixed) <= job.rank(best)):
        if listing.ties:
            return None, proven and fixed.status == "optimal", None
        best = fixed
    if best is None:
        return (job.none(), True, None) if proven else (None, False, None)
    status = "optimal" if proven and best.status == "optimal" else "feasible"
    way = "tree by tree" if complete else "tree by tree, least work first"
    result = replace(best, status=status, joint=True, fixed=fixed, stats={**best.stats, "joint": way})
    if not single and not complete and not proven:
        return None, False, result
    return result, proven, None


def schedule_joint(job: JointRequest, time_limit: float | None = None) -> ScheduleResult:
    """The tree and schedule chosen together; ``job.fixed`` is ``job.tree``'s own schedule.  An
    answer not proven optimal carries ``joint_bound``, a lower bound on every tree's makespan."""
    t0 = time.perf_counter()
    left = encode.clock(time_limit)
    problem, tree, spec, options, fixed = job.problem, job.tree, job.spec, job.options, job.fixed
    meal = tree.meal
    inst = instance(problem, problem.units_for(meal), spec)
    start = earliest(inst)
    # the earliest every goal can be made: a lower bound on the makespan of every tree
    made = [
        min((start[u] + inst.min_duration(u) for u in start if g in problem.products[u]), default=None)
        for g in meal
        if g not in problem.kitchen
    ]
    made_by = max((t for t in made if t is not None), default=0)
    every = joint.every_tree_bound(inst, meal, problem.products, start, made_by)
    horizon = fixed.makespan if fixed.has_schedule else sum(max(inst.durations[u].values()) for u in start)
    assert horizon is not None
    stats: dict = {"encoding": job.encoding}

    def done(r: ScheduleResult) -> ScheduleResult:
        r = replace(r, stats={**stats, **r.stats}, time_s=time.perf_counter() - t0)
        if r.status == "feasible" and r.makespan is not None:
            r.joint_bound = min(every, r.makespan)
        return r

    def given(status: str) -> ScheduleResult:
        """The given tree's schedule as the answer."""
        return done(replace(fixed, status=status, joint=True, fixed=fixed, stats={}))

    if job.shortcut and fixed.status == tree.status == "optimal" and horizon == every and not spec.has_human():
        stats["shortcut"] = "the given tree's makespan meets the lower bound over every tree"
        return given("optimal")
    tail = instances.joint_tails(inst, meal, problem.products)
    ties = spec.has_human() or tree.status != "optimal"
    parts = joint.tree_parts(problem, meal, inst, options)
    within = horizon if len(inst.agents) == 1 or not fixed.has_schedule else horizon - instances.divisor(inst)
    levels, user = len(objectives.ranked(options)), [name for name, _ in options.programs]
    listing = encode.Job(inst, start, tail, within, 0, solver_arguments(options), parts, levels, user, ties)
    by_trees, proven, partial = _by_trees(job, listing, left)
    if by_trees is not None:
        return done(by_trees)
    # proven: no tree beats the given one's makespan, only the tie-breakers are left
    floor = horizon if proven else every
    if left() == 0.0:  # no time for the one encoding (its grounding alone can take minutes): the given tree's
        stats["joint"] = "time"
        if partial is not None:
            return done(partial)
        return given("feasible" if fixed.has_schedule else "unknown")
    sol = encode.solve(replace(listing, horizon=horizon, floor=floor), job.encoding, left())
    stats.update(sol.stats, joint="tie-breakers in one encoding" if proven else "one encoding")
    if sol.unsatisfiable:
        return done(job.none())
    if not sol.proven and partial is not None:
        if sol.entries is None or job.rank(partial) <= (makespan(sol.entries), 0, ()):
            return done(partial)
    if sol.entries is None:  # the given tree's schedule is the best found (proven: optimal)
        return given("optimal" if sol.proven and fixed.status == "optimal" else "feasible")
    sub = inst.restrict(sol.units)
    status = "optimal" if sol.proven else "feasible"
    entries = instances.compact(sub, sol.entries)
    found = ScheduleResult(problem, job.tree_of(sol.units, status), status, fixed.agents, entries, bounds(sub))
    return done(replace(found, baseline=makespan(list_schedule(sub)), joint=True, fixed=fixed))


def schedule(
    problem: Problem,
    tree: TaskTree,
    spec: ScheduleSpec | None = None,
    options: AspOptions | None = None,
    joint: bool = False,
    time_limit: float | None = None,
    encoding: str = DEFAULT_ENCODING,
    shortcut: bool = True,
    progress: Callable[[dict], None] | None = None,
) -> ScheduleResult:
    """Schedule ``tree`` on the agents of ``spec`` (default: one robot, every unit 1 s).

    ``joint``: choose the tree with the schedule (``fixed``: ``tree``'s own schedule).
    ``time_limit``: seconds per solve (default ``options.time_limit``, else
    :data:`DEFAULT_TIME_LIMIT`; ``math.inf``: none); a solve it stops answers ``feasible``.
    ``shortcut=False`` always runs the solver.  ``progress``: called with ``{"makespan",
    "lower", "human", "human_lower", "phase"}`` (ms) as the fixed tree's schedules improve.
    """
    spec = spec or ScheduleSpec()
    options = options or AspOptions()
    if encoding not in encode.ENCODINGS:
        raise InputError(f"unknown schedule encoding {encoding!r} (have {', '.join(encode.ENCODINGS)})")
    if joint:
        check_options(options)
    limit = options.time_limit if time_limit is None else time_limit
    if limit is None:
        limit = DEFAULT_TIME_LIMIT
    elif math.isinf(limit):
        limit = None
    req = Request(problem, spec, options, encoding, shortcut)
    fixed = schedule_fixed(req, tree, limit, progress=progress)
    if not joint or not tree.has_tree:
        return replace(fixed, joint=joint) if joint else fixed
    return schedule_joint(JointRequest(**vars(req), tree=tree, fixed=fixed), limit)
