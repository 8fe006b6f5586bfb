"""Depth bounds by multi-shot solving on one clingo Control.

:class:`Rounds` grounds each block ``bound(k,g,d)`` of ``encodings/depth.lp`` (goal ``g``
within ``d`` rounds, switched by ``query(k)`` and ``within(k)``; a meal's ``meal(m,d)``)
once, over the windows of :class:`Levels`; the driver's ``level`` runs the loop over bounds
(docs/proofs/solving.md, "Depth rounds").
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

import clingo

from foon2asp.asp.control import Control
from foon2asp.asp.interrupts import deferred_signals
from foon2asp.foon.problem import least_fixpoint


class Levels:
    """The least fixpoint of the session's facts, for depth windows: ``required`` (facts
    only) gives the levels, ``required_any`` (every ``required`` atom) the distances."""

    def __init__(
        self,
        kitchen: set[int],
        required: dict[int, list[int]],
        products: dict[int, list[int]],
        required_any: dict[int, list[int]] | None = None,
    ):
        self.kitchen = kitchen

        def outside(table: dict[int, list[int]]) -> dict[int, list[int]]:
            return {u: [o for o in dict.fromkeys(objects) if o not in kitchen] for u, objects in table.items()}

        self.required = outside(required)
        self.required_any = self.required if required_any is None else outside(required_any)
        self.products = outside(products)
        self.producers: dict[int, list[int]] = {}
        for u, prods in self.products.items():
            for o in prods:
                self.producers.setdefault(o, []).append(u)
        # levels as in Problem.derivation_levels (kitchen items are level 0)
        self.object_level, self.unit_level = least_fixpoint(kitchen, self.required, self.products, self.required)

    @classmethod
    def from_problem(cls, problem, units) -> Levels:
        """From the Problem, for a session whose facts are exactly ``units`` of it."""
        units = list(units)
        return cls(
            set(problem.kitchen),
            {u: list(problem.required[u]) for u in units},
            {u: list(problem.products[u]) for u in units},
        )

    @classmethod
    def from_control(cls, ctl: clingo.Control) -> Levels:
        """From the grounded atoms (user programs may add facts)."""
        atoms = ctl.symbolic_atoms

        def numbers(name: str, arity: int, facts_only: bool = False) -> list[tuple[int, ...]]:
            out = []
            for a in atoms.by_signature(name, arity):
                args = a.symbol.arguments
                if (a.is_fact or not facts_only) and all(x.type == clingo.SymbolType.Number for x in args):
                    out.append(tuple(x.number for x in args))
            return out

        units = [u for (u,) in numbers("unit", 1)]

        def table(name: str, facts_only: bool) -> dict[int, list[int]]:
            out: dict[int, list[int]] = {u: [] for u in units}
            for u, o in numbers(name, 2, facts_only):
                if u in out:
                    out[u].append(o)
            return out

        kitchen = {o for (o,) in numbers("kitchen", 1)}
        return cls(kitchen, table("required", True), table("product", False), table("required", False))

    def level(self, goal: int | tuple[int, ...]) -> int | None:
        """The least depth of any tree for ``goal`` (0 in the kitchen, None: no tree);
        for a meal, the greatest over its goals."""
        if not isinstance(goal, int):
            levels = [self.level(g) for g in goal]
            return None if any(x is None for x in levels) else max(x for x in levels if x is not None)
        return 0 if goal in self.kitchen else self.object_level.get(goal)

    def windows(self, goal: int, bound: int) -> list[tuple[int, int, int]]:
        """``(unit, first, last)``: the rounds in which a unit's firing can matter for having
        ``goal`` within ``bound`` rounds."""
        dist = {goal: 0}
        queue = deque([goal])
        unit_dist: dict[int, int] = {}
        while queue:
            o = queue.popleft()
            d = dist[o]
            for u in self.producers.get(o, ()):
                if u in unit_dist or u not in self.unit_level:
                    continue
                unit_dist[u] = d  # breadth first: the first visit is the least distance
                for i in self.required_any[u]:
                    if i not in dist:
                        dist[i] = d + 1
                        queue.append(i)
        out = []
        for u, d in unit_dist.items():
            first, last = self.unit_level[u], bound - d
            if first <= last:
                out.append((u, first, last))
        return sorted(out)


@dataclass
class DepthSearch:
    """What the depth loop knows of the current goal (kept across its cost levels)."""

    #: the least bound not yet refuted (None: the loop has not started)
    bound: int | None = None
    #: ``(bound, how)``: how = "grounder" (the least fixpoint puts the goal higher: refuted
    #: without solving) or "solver" (unsatisfiable)
    refuted: list[tuple[int, str]] = field(default_factory=list)


class Rounds:
    """The depth blocks grounded on one session's Control, each once, and the session's :class:`Levels`."""

    def __init__(self, control: Control, levels: Levels) -> None:
        self.control = control
        self.levels = levels
        #: ``(goal, bound)`` -> the id ``k`` of its block
        self.blocks: dict[tuple[int, int], int] = {}
        #: ``(meal, bound)`` -> the id ``m`` of its meal block
        self.meal_blocks: dict[tuple[tuple[int, ...], int], int] = {}

    @classmethod
    def of(cls, session) -> Rounds:
        """For ``session``: its levels from the Problem, or from the grounded atoms when user programs may add facts."""
        control = session.control
        options = session.options
        if options.programs:
            return cls(control, Levels.from_control(control.ctl))
        units = [a.symbol.arguments[0].number for a in control.ctl.symbolic_atoms.by_signature("unit", 1)]
        return cls(control, Levels.from_problem(session.problem, units))

    def block(self, goal: int, bound: int) -> int:
        """Ground the block for ``goal`` and ``bound`` (once) and return its id ``k``."""
        if (goal, bound) not in self.blocks:
            k = len(self.blocks) + 1
            text = "".join(f"window({k},{u},{lo},{hi}).\n" for u, lo, hi in self.levels.windows(goal, bound))
            what = "grounding the depth rounds"
            with deferred_signals():  # a signal waits until the block is grounded and known
                self.control.extend(f"depth_windows_{k}", text, [("bound", (k, goal, bound))], what)
                self.blocks[(goal, bound)] = k
        return self.blocks[(goal, bound)]

    def meal_block(self, meal: tuple[int, ...], bound: int) -> int:
        """Ground the blocks of ``meal``'s goals and the meal block for ``bound`` (once); its id ``m``."""
        if (meal, bound) not in self.meal_blocks:
            members = [self.block(g, bound) for g in meal]
            m = len(self.meal_blocks) + 1
            text = "".join(f"member({m},{k}).\n" for k in members)
            what = "grounding the depth rounds of a meal"
            with deferred_signals():
                self.control.extend(f"depth_meal_{m}", text, [("meal", (m, bound))], what)
                self.meal_blocks[(meal, bound)] = m
        return self.meal_blocks[(meal, bound)]

    def externals(self, goal: int | tuple[int, ...], bound: int, count_depth: bool) -> list[clingo.Symbol]:
        """The externals for depth bound ``bound`` of ``goal`` (its block grounded if need be):
        query(k), and within(k) when the depth cost is counted; meal_query(m), meal_within(m) for a meal."""
        if not isinstance(goal, int) and len(goal) == 1:
            goal = goal[0]
        if isinstance(goal, int):
            k, names = self.block(goal, bound), ("query", "within")
        else:
            k, names = self.meal_block(tuple(goal), bound), ("meal_query", "meal_within")
        return [clingo.Function(name, [clingo.Number(k)]) for name in (names if count_depth else names[:1])]
