"""Joint scheduling by trees: every tree that could beat a known makespan, each scheduled alone.

clingo lists the *designated* trees (each needed object with one first maker) that fit within
the known makespan; :class:`JointSearch` schedules them lowest lower bound first, or asks for them
one at a time, least work first, when they are too many (docs/proofs/schedules.md).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import clingo

from foon2asp.asp import dominance, encoding_files, objectives
from foon2asp.asp.control import Control
from foon2asp.asp.facts import OPTIONAL, facts
from foon2asp.asp.objectives import neglog_sum
from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.problem import Problem
from foon2asp.schedule.encode import Job, used
from foon2asp.schedule.instances import Instance, divisor, joint_tails
from foon2asp.schedule.lower_bounds import energy_over

#: tree objectives joint scheduling supports (depth needs the multi-shot driver)
JOINT_OBJECTIVES = ("units", "success", "inputs")


def check_options(options: AspOptions) -> tuple[str, ...]:
    """The ranked tree objectives of ``options``; InputError when joint scheduling cannot use them."""
    ranked = objectives.ranked(options)
    wrong = [o for o in ranked if o not in JOINT_OBJECTIVES]
    if wrong or options.max_depth is not None or not ranked:
        raise InputError(
            f"joint scheduling chooses trees by {', '.join(JOINT_OBJECTIVES)} only, not by depth or heuristics"
        )
    if options.human_steps is not None:
        raise InputError("joint scheduling counts a person's units through a human agent, not human steps")
    return ranked


def _dominance(problem: Problem, inst: Instance, ranked: tuple[str, ...]) -> str:
    """``dom(V,U)`` facts (encodings/dominance.lp): the tree dominance of
    :mod:`foon2asp.asp.dominance` where V also takes no longer than U on every kind that can
    do U and uses no resource U does not."""
    out = []
    for v, u, extra in dominance.dominance_pairs(problem, inst.units, ranked):
        dv, du = inst.durations[v], inst.durations[u]
        if all(k in dv and dv[k] <= d for k, d in du.items()) and set(inst.uses[v]) <= set(inst.uses[u]):
            out.append(f"dom({v},{u}).\n")
            out += [f"dom_extra({v},{u},{o}).\n" for o in extra]
    return "".join(out)


def tree_parts(problem: Problem, meal: tuple[int, ...], inst: Instance, options: AspOptions) -> list:
    """The facts of the tree (``encodings/joint_tree.lp``), its objectives (priorities 1..n) for
    the goals ``meal`` over the units of ``inst``, and the user's programs, for joint scheduling."""
    ranked = check_options(options)
    units = list(inst.units)
    parts = [("objective", objectives.objective_facts(ranked))]
    if "inputs" in ranked:
        parts.append(("input nodes", objectives.input_node_facts(problem, units)))
    parts.append(("goal", "".join(f"goal({g}).\n" for g in meal)))
    if not options.programs:
        parts.append(("dominated units", _dominance(problem, inst, ranked)))
    parts += list(options.programs)
    keep = {"neglog"} if "success" in ranked else set()
    leave_out = [] if options.programs else [p for p in OPTIONAL if p not in keep]
    return [("facts", facts(problem, units=units, leave_out=leave_out)), *parts]


#: the most designated trees listed at once
MAX_TREES = 2000

#: a tree (sorted unit ids) and its designation: (object, its first maker) pairs, sorted
#: (empty: each unit waits for the first maker of what it needs, whichever it is)
DesignatedTree = tuple[tuple[int, ...], tuple[tuple[int, int], ...]]


def _listing(control: Control, listing: Job, entry: str) -> Control:
    """``control`` with the tree's facts and programs, ``joint_tree.lp`` and the listing ``entry`` loaded."""
    control.add_all(listing.tree_parts[:1])
    control.load(encoding_files.entry("joint_tree"))
    control.load(encoding_files.entry(entry))
    control.add_all(listing.tree_parts[1:], user=listing.user)
    return control


def bound_facts(listing: Job) -> str:
    """work/2, too_late/1 and capacity/1 for ``schedule_trees.lp``: which trees of the candidate
    units fit the agents within ``listing.horizon`` (times in steps of the divisor)."""
    inst, head, tail, g = listing.inst, listing.head, listing.tail, divisor(listing.inst)
    late = [u for u in inst.units if u not in head or u not in tail or head[u] + tail[u] > listing.horizon]
    lines = [f"work({u},{inst.min_duration(u) // g})." for u in inst.units if inst.durations[u]]
    lines += [f"too_late({u})." for u in late]
    lines.append(f"capacity({len(inst.agents) * (listing.horizon // g)}).")
    return "\n".join(lines) + "\n"


def candidate_trees(listing: Job, time_limit: float | None) -> tuple[list[DesignatedTree], bool]:
    """The designated trees whose work fits the agents within the horizon and whose units can
    each end within it, at most :data:`MAX_TREES`; and whether they are all."""
    control = _listing(Control(["--opt-mode=ignore", "--models=0", *listing.args]), listing, "list_designations")
    control.add_all([("bounds", bound_facts(listing))])
    control.ground()
    found: list[DesignatedTree] = []

    def on_model(model: clingo.Model) -> bool:
        atoms = model.symbols(atoms=True)
        units = used(atoms)
        first = sorted(
            (s.arguments[0].number, s.arguments[1].number) for s in atoms if s.name == "first" and len(s.arguments) == 2
        )
        found.append((units, tuple(first)))
        return len(found) <= MAX_TREES

    result = control.solve(on_model, time_limit)
    return found[:MAX_TREES], result.finished and len(found) <= MAX_TREES


def tree_cost(problem: Problem, units: Sequence[int], human: Sequence[int], ranked: Sequence[str]) -> tuple:
    """The tree objective of ``units`` as the solver ranks it (a person's unit succeeds for sure)."""
    measure: dict[str, Callable[[], Any]] = {
        "units": lambda: len(units),
        "success": lambda: neglog_sum(problem, units, human),
        "inputs": lambda: sum(len(problem.inputs[u]) for u in units),
    }
    return tuple(measure[name]() for name in ranked)


@dataclass
class JointSearch:
    """The best result of ``solve`` (a designated tree, the time left, the best makespan so far)
    by ``key`` over trees, ties to the first found; ``bound``: a lower bound on a tree's key;
    ``left``: the time left."""

    solve: Callable[[DesignatedTree, float | None, int | None], Any]
    key: Callable[[Any], tuple]
    bound: Callable[[DesignatedTree], tuple]
    left: Callable[[], float | None]
    best: Any = None
    proven: bool = True

    def offer(self, cand: DesignatedTree) -> None:
        r = self.solve(cand, self.left(), None if self.best is None else self.best.makespan)
        self.proven = self.proven and r.status in ("optimal", "unschedulable")
        if r.has_schedule and (self.best is None or self.key(r) < self.key(self.best)):
            self.best = r

    def over(self, trees: list[DesignatedTree]) -> tuple[Any, bool]:
        """The best over ``trees``, lowest bound first, stopping when the next bound is no
        better than the best, or when the time is up (the bounds' time too); (best, proven)."""
        bounded = []
        for t in trees:
            if self.left() == 0.0:
                return self.best, False
            bounded.append((self.bound(t), t))
        for low, t in sorted(bounded, key=lambda pair: pair[0]):
            if self.best is not None and low >= self.key(self.best):
                break  # sorted: no later tree can beat the best
            if self.left() == 0.0:
                return self.best, False
            self.offer(t)
        return self.best, self.proven

    def by_work(self, listing: Job, levels: int, first: bool = False) -> tuple[Any, bool]:
        """The best over the undesignated trees, asked for one at a time, least work first,
        stopping when a tree's work over the agents exceeds the best makespan.  ``first``: the
        first tree is the best (one agent)."""
        m = len(listing.inst.agents)
        facts = bound_facts(listing)
        order = f"work_priority({levels + 1}).\n"
        seen: list[tuple[int, ...]] = []
        last: list[tuple[int, ...]] = []  # the trees of one solve
        while True:
            left = self.left()
            if left == 0.0:
                return self.best, False
            listed = "".join(
                f"listed_size({k},{len(t)}).\n" + "".join(f"listed({k},{u}).\n" for u in t)
                for k, t in enumerate(seen, 1)
            )
            control = _listing(Control(["--opt-mode=opt", *listing.args]), listing, "list_trees")
            control.add_all([("bounds", facts), ("least work first", order + listed)])
            control.ground()
            last.clear()
            if not control.solve(lambda model: last.append(used(model.symbols(shown=True))), left).finished:
                return self.best, False
            if not last:
                return self.best, self.proven  # no tree left
            t = last[-1]
            seen.append(t)
            work = sum(listing.inst.min_duration(u) for u in t)
            if self.best is not None and -(-work // m) > self.best.makespan:
                return self.best, self.proven
            if self.best is None or self.bound((t, ())) < self.key(self.best):
                self.offer((t, ()))
            if first:
                return self.best, self.proven


def every_tree_bound(
    inst: Instance, goals: Sequence[int], products: Sequence[tuple[int, ...]], start: dict[int, int], floor: int
) -> int:
    """A lower bound, at least ``floor``, on the makespan of every tree of ``inst`` for ``goals``
    (``start``: the units' earliest starts)."""
    makers: dict[int, list[int]] = {}
    for u in inst.units:
        for o, ms in inst.needs[u]:
            makers.setdefault(o, list(ms))
    for g in goals:
        makers.setdefault(g, [u for u in inst.units if g in products[u]])
    lm = _landmarks(inst, goals, makers, start)
    if lm is None:
        return floor
    made = {o for u in lm for o in products[u]}
    wanted = [g for g in goals if g not in made] + sorted({o for u in lm for o, _ in inst.needs[u] if o not in made})
    parts: list[list[int]] = [[u] for u in sorted(lm)]
    taken = set(lm)
    for o in wanted:
        choice = [m for m in makers.get(o, ()) if m in start]
        if choice and taken.isdisjoint(choice):
            taken.update(choice)
            parts.append(choice)
    d = {u: inst.min_duration(u) for part in parts for u in part}
    work = -(-sum(min(d[u] for u in part) for part in parts) // len(inst.agents))
    tail = _chain_tails(inst, lm, joint_tails(inst, goals, products))
    return energy_over(parts, d, start, tail, len(inst.agents), max(floor, work), divisor(inst))


def _landmarks(
    inst: Instance, goals: Sequence[int], makers: dict[int, list[int]], start: dict[int, int]
) -> frozenset[int] | None:
    """The units every tree of ``inst`` for ``goals`` holds (None: some goal has no tree)."""
    makes: dict[int, list[int]] = {}
    for o, ms in makers.items():
        for m in ms:
            makes.setdefault(m, []).append(o)
    ulm: dict[int, frozenset[int]] = {}
    lm: dict[int, frozenset[int]] = {}
    order = sorted(start, key=lambda u: (start[u], u))  # a unit's needs are made by units before it
    changed = True
    while changed:
        changed = False
        for u in order:
            parts = [lm.get(o) for o, _ in inst.needs[u]]
            if any(p is None for p in parts):
                continue
            new = frozenset().union(*(p for p in parts if p is not None)) | {u}
            if ulm.get(u) != new:
                ulm[u] = new
                changed = True
                for o in makes.get(u, ()):
                    lm[o] = frozenset.intersection(*(ulm[m] for m in makers.get(o, ()) if m in ulm))
    out: set[int] = set()
    for g in goals:
        known = [ulm[m] for m in makers.get(g, ()) if m in ulm]
        if not known:
            return None
        out |= frozenset.intersection(*known)
    return frozenset(out)


def _chain_tails(inst: Instance, units: frozenset[int], tail: dict[int, int]) -> dict[int, int]:
    """``tail`` raised, for ``units`` (in every tree), by the longest chain of them that must
    wait one for another (a unit waits for the sole maker of what it needs)."""
    succs: dict[int, list[int]] = {u: [] for u in units}
    for v in units:
        for _, ms in inst.needs[v]:
            if len(ms) == 1 and ms[0] in units:
                succs[ms[0]].append(v)
    done: dict[int, int] = {}

    def longest(u: int) -> int:
        if u not in done:
            done[u] = tail.get(u, 0)  # a guard against cycles among the sole makers
            done[u] = max(tail.get(u, 0), inst.min_duration(u) + max((longest(v) for v in succs[u]), default=0))
        return done[u]

    return {**tail, **{u: longest(u) for u in units}}
