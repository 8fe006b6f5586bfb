"""A goal's minimum-weight tree as weighted MaxSAT, closed by loop cuts.

**The relaxation.**  A set ``S`` of units is *closed* for the goal ``g`` when every
object that is ``g`` or a required input of a unit of ``S``, and not a kitchen item,
is a product of a unit of ``S``.  Every tree is closed (its units fire, so whatever
they need is had, and what is had and not in the kitchen was made).  With a variable
``use(u)`` per unit and ``need(o)`` per object:

* ``need(g)``;
* ``use(u) -> need(i)`` for every required input ``i`` of ``u`` that is not a kitchen item;
* ``need(o) -> use(p1) or ... or use(pk)`` over the producers ``p`` of ``o``;
* soft: ``not use(u)`` at the price of ``u``'s weight.

No unit has to *fire*: units may support each other around a cycle, so a closed set
need not be a tree, and the least weight of a closed set is a lower bound on the
least weight of a tree.

**Loop cuts.**  When an optimum ``S`` of the relaxation derives ``g`` from the kitchen
(the least fixpoint over ``S``), it is a tree of that least weight: an optimal tree.
Otherwise let ``L`` be the needed objects that ``S`` does not derive.  In any tree that
needs an object of ``L``, consider the first object of ``L`` it has: its producer
fired with its inputs had before, so none of them is in ``L``.  So every tree
satisfies ``need(o) -> OR use(p)`` over the producers ``p`` of objects of ``L`` whose
required inputs avoid ``L`` (the *external* producers), for each ``o`` in ``L``; ``S``
does not (each producer ``S`` has of an object of ``L`` needs an object of ``L``,
else it would fire).  The clauses are added and the solver goes on with its cores:
they remain valid, as the cut only removes closed sets that are not trees.  Each
round removes the last optimum, and only finitely many sets exist, so the loop ends
with an optimal tree.  On the hard presets the relaxation's first optimum has been a
tree every time (BENCHMARKS.md, "MaxSAT").

**Within a depth.**  With a depth bound ``d`` (:func:`minimum_tree`'s ``depth``) the
variables are indexed by rounds, as in ``encodings/depth.lp``: ``need(o,t)`` (``o`` must
be had after ``t`` rounds) and ``fire(u,t)`` (``u`` fires within ``t`` rounds):
``need(g,d)``; ``need(o,t) -> OR fire(p,t)`` over the producers ``p`` of ``o`` that can
fire by round ``t`` (their level in the least fixpoint is at most ``t``);
``fire(u,t) -> need(i,t-1)`` for its required inputs that are not kitchen items;
``fire(u,t) -> use(u)``.  Rounds only go down, so nothing rests on a cycle: an optimum's
used units (each fires, or it would be dropped) are a tree of depth at most ``d``, and
every such tree is a model.  No loop cut is needed.

**The smallest optimal tree.**  Asked for it (``smallest``), the search walks on from
the optimum to the lexicographically smallest optimum over the units in id order
(:meth:`foon2asp.maxsat.oracle.Oracle.smallest`, within a budget of SAT conflicts):
the canonical tree of :mod:`foon2asp.asp.canonical` when the walk completes.  A
closed set it ends on that is no tree is cut as above and the walk starts again.

The solver's cost is a lower bound at every moment (:mod:`foon2asp.maxsat.oracle`),
so a search cut short still says how far from proven the best known tree is.

**HiGHS beside RC2.**  With ``mip_after`` set, a goal RC2 has not proven after that many
seconds is also given, on a second thread, to HiGHS (:mod:`foon2asp.maxsat.mip`) as a
0/1 program over the same clauses and loop cuts (:func:`minimum_tree_mip`); whichever
proves the optimum first ends both.  The bound is the better of the two, and the best
tree HiGHS found (a closed set that derives the goal) is offered when both are cut
short.  A tree HiGHS proves is its optimum, not the smallest in the canonical order
(``search == "mip"``).

**UWrMaxSat after RC2.**  With ``uwr_after`` set, a goal RC2 has not proven after that many
seconds is handed to UWrMaxSat (:mod:`foon2asp.maxsat.uwr`, in a child process): the same
clauses, loop cuts and required units (:func:`minimum_tree_uwr`).  RC2 stops there, so the
two do not share a core; the bound it proved stays (UWrMaxSat reports none), and HiGHS, when
it runs beside, may raise it.  Its tree, like HiGHS's, is its first optimum
(``search == "uwrmaxsat"``).  On the hardest goals of the hard presets it proves in seconds
what takes RC2 tens of seconds (BENCHMARKS.md, "UWrMaxSat after RC2").
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

from foon2asp.foon.derive import least_fixpoint
from foon2asp.foon.problem import Problem
from foon2asp.maxsat import mip, uwr
from foon2asp.maxsat.oracle import Oracle, Stopped


@dataclass
class Result:
    """A MaxSAT search for one goal: the optimal tree (None: cut short, or no tree) and
    the least weight proven for every tree (the optimum's when ``tree`` is set)."""

    tree: tuple[int, ...] | None
    lower: int
    #: "optimal" | "stopped" (deadline or ``stop``) | "unreachable" (no tree over the units)
    status: str
    #: loop cuts added (rounds whose optimum was not a tree)
    cuts: int = 0
    time_s: float = 0.0
    #: how the walk to the smallest optimal tree ended: "complete" | "budget" | "time" (None: not asked,
    #: or the optimum weighed ``known``; "mip" or "uwrmaxsat": HiGHS or UWrMaxSat proved the tree, no walk)
    search: str | None = None
    #: cut short: the best tree found all the same (HiGHS's), None when there is none
    incumbent: tuple[int, ...] | None = None
    #: the solver that proved the result: "rc2" | "highs" | "uwrmaxsat"
    solver: str = "rc2"


class _Encoding:
    """Variables ``use(u)`` and ``need(o)`` of one goal over ``units``."""

    def __init__(self, problem: Problem, goal: int, units: Sequence[int]):
        self.problem, self.goal, self.units = problem, goal, list(units)
        self.use = {u: k + 1 for k, u in enumerate(self.units)}
        #: the highest variable so far
        self.top = len(self.use)
        self.need: dict[int, int] = {}
        self.producers: dict[int, list[int]] = {}
        for u in self.units:
            for o in problem.products[u]:
                self.producers.setdefault(o, []).append(u)

    def var(self, table: dict, key) -> int:
        """The variable of ``key`` in ``table``, a new one the first time."""
        if key not in table:
            self.top += 1
            table[key] = self.top
        return table[key]

    def need_var(self, o: int) -> int:
        return self.var(self.need, o)

    def clauses(self) -> Iterable[list[int]]:
        kitchen = self.problem.kitchen
        yield [self.need_var(self.goal)]
        for u in self.units:
            for i in self.problem.required[u]:
                if i not in kitchen:
                    yield [-self.use[u], self.need_var(i)]
        for o in list(self.need):
            # every needed object is made by one of its producers (none: never needed)
            yield [-self.need[o]] + [self.use[p] for p in self.producers.get(o, ())]

    def weighted(self, weights: Sequence[int], require: Iterable[int]) -> tuple[list[list[int]], list[tuple[int, int]]]:
        """The formula as MaxSAT solvers take it: the hard clauses (with a unit clause per
        unit of ``require``) and the soft literals ``not use(u)`` with ``u``'s weight."""
        hard = list(self.clauses())
        hard += [[self.use[u]] for u in sorted(set(require)) if u in self.use]
        return hard, [(-self.use[u], weights[u]) for u in self.units]

    def cut(self, chosen: set[int]) -> list[list[int]] | None:
        """The loop cut of the closed set ``chosen`` (None: it derives the goal, a tree)."""
        problem, kitchen = self.problem, self.problem.kitchen
        made, _ = least_fixpoint(kitchen, problem.required, problem.products, sorted(chosen))
        if self.goal in made or self.goal in kitchen:
            return None
        needed = {i for u in chosen for i in problem.required[u] if i not in kitchen} | {self.goal}
        loop = {o for o in needed if o not in made}
        external = sorted({p for o in loop for p in self.producers.get(o, ()) if loop.isdisjoint(problem.required[p])})
        outside = [self.use[p] for p in external]
        return [[-self.need_var(o)] + outside for o in sorted(loop)]


class _Rounds(_Encoding):
    """Variables ``use(u)``, ``need(o,t)`` and ``fire(u,t)`` of one goal within ``depth`` rounds."""

    def __init__(self, problem: Problem, goal: int, units: Sequence[int], depth: int):
        super().__init__(problem, goal, units)
        self.depth = depth
        _, self.level = least_fixpoint(problem.kitchen, problem.required, problem.products, self.units)
        self.fire: dict[tuple[int, int], int] = {}

    def clauses(self) -> Iterable[list[int]]:
        kitchen = self.problem.kitchen
        needs: dict[tuple[int, int], int] = {}
        start = (self.goal, self.depth)
        yield [self.var(needs, start)]
        todo = [start]
        while todo:
            o, t = todo.pop()
            makers = []
            for p in self.producers.get(o, ()):
                if p not in self.level or self.level[p] > t:
                    continue
                new = (p, t) not in self.fire
                f = self.var(self.fire, (p, t))
                makers.append(f)
                if not new:
                    continue
                yield [-f, self.use[p]]
                for i in self.problem.required[p]:
                    if i in kitchen:
                        continue
                    if (i, t - 1) not in needs:
                        todo.append((i, t - 1))
                    yield [-f, self.var(needs, (i, t - 1))]
            yield [-needs[(o, t)]] + makers

    def cut(self, chosen: set[int]) -> list[list[int]] | None:
        return None  # rounds only go down: every optimum is a tree


def _encoding(problem: Problem, goal: int, units: Iterable[int], depth: int | None) -> _Encoding:
    pool = sorted(set(units))
    return _Encoding(problem, goal, pool) if depth is None else _Rounds(problem, goal, pool, depth)


class _Race:
    """What the solvers beside RC2 (HiGHS, UWrMaxSat) report to its search: a bound, a best
    tree, a proof (the first one stands)."""

    def __init__(self) -> None:
        self.done = threading.Event()  # RC2 is done: the others stop
        self.handed = threading.Event()  # UWrMaxSat has taken over: RC2 stops
        self.lower = 0
        self.proof: Result | None = None
        self.incumbent: tuple[int, ...] | None = None
        self._lock = threading.Lock()

    def raise_lower(self, bound: int) -> None:
        """A helper proved every tree weighs at least ``bound``."""
        with self._lock:
            self.lower = max(self.lower, bound)

    def over(self) -> bool:
        """Is the race over: RC2 done, or a proof in?"""
        return self.done.is_set() or self.proof is not None

    def prove(self, found: Result) -> None:
        """``found`` (an optimum) is the answer unless another solver proved one first."""
        with self._lock:
            if self.proof is None:
                self.proof = found


def minimum_tree_mip(
    problem: Problem,
    goal: int,
    units: Iterable[int],
    weights: Sequence[int],
    require: Iterable[int] = (),
    deadline: float | None = None,
    depth: int | None = None,
    halt: Callable[[], bool] | None = None,
    race: _Race | None = None,
) -> Result:
    """:func:`minimum_tree` by HiGHS (no walk to the smallest tree): the same clauses, loop
    cuts and result; ``halt()`` ends it early; ``race`` (the search beside RC2) receives the
    bound and the best tree as they come."""
    t0 = time.perf_counter()
    enc = _encoding(problem, goal, units, depth)
    clauses = list(enc.clauses())
    require = sorted({enc.use[u] for u in require if u in enc.use})
    program = mip.Program(enc.top, {enc.use[u]: weights[u] for u in enc.units}, require)
    program.add(clauses)
    race = race or _Race()
    program.on_lower = race.raise_lower  # the bound as it rises (an answer cut short reports it)
    cuts = 0
    while True:
        status, model = program.solve(deadline, halt)
        race.raise_lower(program.lower)
        chosen = None if model is None else {u for u in enc.units if enc.use[u] in model}
        clauses_ = None if chosen is None else enc.cut(chosen)
        if chosen is not None and clauses_ is None:
            tree = tuple(sorted(chosen))
            if status == "optimal":
                cost = sum(weights[u] for u in tree)
                took = time.perf_counter() - t0
                return Result(tree, cost, "optimal", cuts, took, "mip", None, "highs")
            race.incumbent = tree
        if status == "infeasible":
            return Result(None, program.lower, "unreachable", cuts, time.perf_counter() - t0, solver="highs")
        if status == "stopped":
            took = time.perf_counter() - t0
            return Result(None, program.lower, "stopped", cuts, took, incumbent=race.incumbent, solver="highs")
        cuts += 1
        program.add(clauses_ or ())


def minimum_tree_uwr(
    problem: Problem,
    goal: int,
    units: Iterable[int],
    weights: Sequence[int],
    require: Iterable[int] = (),
    deadline: float | None = None,
    depth: int | None = None,
    halt: Callable[[], bool] | None = None,
    race: _Race | None = None,
) -> Result:
    """:func:`minimum_tree` by UWrMaxSat in its child process (:mod:`foon2asp.maxsat.uwr`; no
    walk to the smallest tree, no bound of its own: ``lower`` is 0 unless it proves): the
    same clauses and loop cuts; ``halt()`` ends it early. ``race`` is the caller's."""
    t0 = time.perf_counter()
    enc = _encoding(problem, goal, units, depth)
    hard, soft = enc.weighted(weights, require)
    cuts = 0
    while True:
        status, model = uwr.solver().solve(enc.top, hard, soft, deadline, halt)
        if status == "infeasible":
            return Result(None, 0, "unreachable", cuts, time.perf_counter() - t0, solver="uwrmaxsat")
        if status != "optimal" or model is None:
            return Result(None, 0, "stopped", cuts, time.perf_counter() - t0, solver="uwrmaxsat")
        chosen = {u for u in enc.units if enc.use[u] in model}
        more = enc.cut(chosen)
        if more is None:
            tree = tuple(sorted(chosen))
            cost = sum(weights[u] for u in tree)
            return Result(tree, cost, "optimal", cuts, time.perf_counter() - t0, "uwrmaxsat", None, "uwrmaxsat")
        cuts += 1
        hard += more


def minimum_tree(
    problem: Problem,
    goal: int,
    units: Iterable[int],
    weights: Sequence[int],
    require: Iterable[int] = (),
    deadline: float | None = None,
    stop: Callable[[int], bool] | None = None,
    depth: int | None = None,
    smallest: bool = False,
    known: int | None = None,
    mip_after: float | None = None,
    uwr_after: float | None = None,
) -> Result:
    """The least-weight tree for ``goal`` over ``units`` (each unit ``u`` weighs
    ``weights[u] > 0``), every unit of ``require`` in it; with ``depth``, among the
    trees of at most that depth; with ``smallest``, the smallest such tree in the
    canonical order unless the least weight is ``known`` (the caller has that tree).

    ``deadline`` (``time.perf_counter()``) and ``stop(lower)`` end the search early:
    the result is then ``stopped`` with the lower bound proven so far (a walk to the
    smallest tree cut short ends on the smallest reached, ``search == "time"``).
    ``mip_after``: HiGHS starts beside RC2 after that many seconds (None: never);
    ``uwr_after``: UWrMaxSat takes over from RC2 after that many seconds (None: never):
    RC2 stops (its bound stays) and UWrMaxSat goes on in its child process."""
    t0 = time.perf_counter()
    units = sorted(set(units))
    race = _Race()
    helpers = [
        (after, how, name)
        for after, how, name, have in (
            (mip_after, minimum_tree_mip, "highs-beside", mip.available),
            (uwr_after, minimum_tree_uwr, "uwrmaxsat", uwr.available),
        )
        if after is not None and have()
    ]
    taking_over: threading.Thread | None = None
    for after, how, name in helpers:

        def beside(after: float = after, how: Callable[..., Result] = how) -> None:
            if race.done.wait(after):
                return
            if how is minimum_tree_uwr:
                race.handed.set()  # RC2 stops at its next look at ``stop``
            try:
                found = how(problem, goal, units, weights, require, deadline, depth, race.over, race)
            except Exception:  # noqa: BLE001 (the helper failing leaves RC2's search as it was)
                return
            if found.status == "optimal":
                race.prove(found)

        # not a daemon: the interpreter waits for it at exit (it stops at HiGHS's next callback once
        # ``race.done`` is set); a HiGHS run cut off by the exit aborted the process (status 134)
        thread = threading.Thread(target=beside, name=name, daemon=False)
        thread.start()
        if how is minimum_tree_uwr:
            taking_over = thread
    user_stop = stop
    if helpers:

        def stop(lower: int) -> bool:
            return (
                race.proof is not None
                or race.handed.is_set()
                or (user_stop is not None and user_stop(max(lower, race.lower)))
            )

    try:
        found = _by_cores(problem, goal, units, weights, require, deadline, stop, depth, smallest, known, race)
        if found.status == "stopped" and taking_over is not None and race.handed.is_set():
            # UWrMaxSat goes on alone (HiGHS beside it) until a proof, the deadline or the caller's stop
            while taking_over.is_alive() and not (user_stop is not None and user_stop(max(found.lower, race.lower))):
                taking_over.join(0.05)
    finally:
        race.done.set()  # the helpers stop (HiGHS at its next callback, about once a second): not waited for
    proof = race.proof
    if found.status == "stopped" and proof is not None and proof.lower >= found.lower:
        proof.time_s = time.perf_counter() - t0
        return proof
    found.lower = max(found.lower, race.lower) if found.status == "stopped" else found.lower
    found.incumbent = race.incumbent if found.status == "stopped" else None
    found.time_s = time.perf_counter() - t0
    return found


def _by_cores(
    problem: Problem,
    goal: int,
    units: Sequence[int],
    weights: Sequence[int],
    require: Iterable[int],
    deadline: float | None,
    stop: Callable[[int], bool] | None,
    depth: int | None,
    smallest: bool,
    known: int | None,
    race: _Race,
) -> Result:
    """:func:`minimum_tree` by RC2 (``race.done`` set once it has an optimum)."""
    t0 = time.perf_counter()
    enc = _encoding(problem, goal, units, depth)
    oracle = Oracle()
    hard, soft = enc.weighted(weights, require)
    oracle.hards(hard, enc.top)
    for literal, weight in soft:
        oracle.soft(literal, weight)
    cuts = 0
    order = [enc.use[u] for u in enc.units]
    unit_of = {v: u for u, v in enc.use.items()}
    try:
        while True:
            model = oracle.solve(deadline, stop)
            if model is None:
                race.done.set()
                return Result(None, oracle.lower, "unreachable", cuts, time.perf_counter() - t0)
            chosen = {u for u in enc.units if enc.use[u] in model}
            clauses = enc.cut(chosen)
            if clauses is None:
                race.done.set()  # an optimal tree: HiGHS stops, the walk starts
            search = None
            if clauses is None and smallest and sum(weights[u] for u in chosen) != known:
                true, search = oracle.smallest(order, deadline)
                walked = {unit_of[v] for v in true}
                walked_cut = enc.cut(walked)
                if walked_cut is None or search != "time":  # out of time on a closed set: the tree before
                    chosen, clauses = walked, walked_cut
            if clauses is None:
                took = time.perf_counter() - t0
                return Result(tuple(sorted(chosen)), oracle.lower, "optimal", cuts, took, search)
            cuts += 1
            oracle.hards(clauses)
    except Stopped:
        return Result(None, oracle.lower, "stopped", cuts, time.perf_counter() - t0)
