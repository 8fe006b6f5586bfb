"""What preparation hands clingo for one goal: the part to search and what is known of it.

:func:`search` optimises over closed sets with loop cuts (``encodings/closed.lp``) or in one
round (``encodings/prepared.lp``).  Why this keeps every optimum: docs/proofs/solving.md.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import clingo

from foon2asp.asp.answers import Shot, Watch, cost_vector, solve_shot
from foon2asp.asp.control import Control
from foon2asp.foon.problem import Problem, least_fixpoint
from foon2asp.tree.tasktree import TaskTree
from foon2asp.tree.weights import unit_weight


@dataclass(frozen=True)
class Preparation:
    """The prepared part of one goal."""

    goal: int
    #: the units clingo may use (sorted)
    candidates: tuple[int, ...]
    #: units every tree for the goal uses
    landmarks: tuple[int, ...] = ()
    #: a valid tree to try first (a hint only: clingo decides)
    hint: tuple[int, ...] = ()
    #: the hint's solver cost vector when an optimum of that cost may be answered with the hint
    known: tuple[int, ...] | None = None
    #: a lower bound on the first objective's weight (the landmarks), for bounds and gaps
    floor: int | None = None
    #: does a model of this cost vector meet the lower bound (so it is optimal)?
    meets: Callable[[tuple[int, ...]], bool] | None = None

    @property
    def bound(self) -> tuple[int, ...] | None:
        """The hint's cost vector when it meets the lower bound (clingo then decides), else None."""
        if self.known is not None and self.meets is not None and self.meets(self.known):
            return self.known
        return None

    def facts(self) -> str:
        """``landmark/1``, ``hint/1`` and ``candidate/1`` facts."""
        lines = [f"candidate({u})." for u in self.candidates]
        lines += [f"landmark({u})." for u in self.landmarks]
        lines += [f"hint({u})." for u in self.hint]
        return "\n".join(lines) + "\n"

    def cut(self, problem: Problem, units: Iterable[int]) -> tuple[list[int], list[int]] | None:
        """The loop cut of a closed set of ``units`` (the needed objects it does not derive, and the
        units that make one of them from inputs outside them); None for a tree."""
        units = list(units)
        kitchen = problem.kitchen
        derived, _ = least_fixpoint(kitchen, problem.required, problem.products, units)
        need = {self.goal}.union(*(problem.required[u] for u in units))
        missing = sorted(o for o in need if o not in kitchen and o not in derived)
        if not missing:
            return None
        cut = set(missing)
        outside = [
            p
            for p in sorted({*self.candidates, *self.landmarks})
            if not cut.isdisjoint(problem.products[p]) and cut.isdisjoint(problem.required[p])
        ]
        return missing, outside


def decision_facts(problem: Problem, ranked: Sequence[str], preps: Sequence[Preparation]) -> str:
    """The facts of ``decide_many.lp`` for ``preps`` (each with a bound), goal K the K-th from 1:
    ``decide(K,G)``, ``candidate/2``, ``landmark/2``, ``hint/2``, ``budget(K,L,B)`` (its bound
    at level L of ``ranked``); ``required/2``, ``product/2`` and ``weight(L,U,W)`` of every
    candidate; ``kitchen/1`` of their objects."""
    lines: list[str] = []
    units: set[int] = set()
    for k, prep in enumerate(preps, 1):
        assert prep.bound is not None, f"goal {prep.goal} has no bound to decide at"
        units.update(prep.candidates)
        units.update(prep.landmarks)
        lines.append(f"decide({k},{prep.goal}).")
        lines += [f"candidate({k},{u})." for u in prep.candidates]
        lines += [f"landmark({k},{u})." for u in prep.landmarks]
        lines += [f"hint({k},{u})." for u in prep.hint]
        lines += [f"budget({k},{level},{b})." for level, b in enumerate(prep.bound, 1)]
    weights = [unit_weight(problem, name) for name in ranked]
    objects: set[int] = set()
    for u in sorted(units):
        lines += [f"required({u},{i})." for i in problem.required[u]]
        lines += [f"product({u},{o})." for o in problem.products[u]]
        lines += [f"weight({level},{u},{weight(u)})." for level, weight in enumerate(weights, 1)]
        objects.update(problem.required[u])
        objects.update(problem.products[u])
    objects.update(prep.goal for prep in preps)
    kitchen = problem.kitchen
    lines += [f"kitchen({o})." for o in sorted(objects) if o in kitchen]
    return "\n".join(lines) + "\n"


def search(
    control: Control,
    prep: Preparation,
    problem: Problem,
    closed: bool,
    deadline: float | None,
    watch: Watch,
    on_model: Callable[[clingo.Model], bool | None] | None = None,
    renew: Callable[[], Control] | None = None,
) -> tuple[Shot, TaskTree | None, tuple[int, ...] | None, int]:
    """clingo's optimisation over the prepared part on ``control`` (with ``closed``, in rounds of loop
    cuts), ended by a tree that meets the lower bound (``prep.meets``: that tree is proven);
    ``watch`` and ``on_model`` see each model that is a tree; ``renew``: a fresh multi-shot
    grounding for the rounds after the first (``control`` solves once), which gets the first cut
    and then each further one.

    Returns the last round's shot, the answer (a tree read from a model, not finished; unproven
    when cut short), the best lower bound proven, and the number of cuts."""
    best: list[TaskTree] = []
    cuts_of: dict[tuple[int, ...], tuple[list[int], list[int]] | None] = {}

    def cut_of(tree: TaskTree) -> tuple[list[int], list[int]] | None:
        units = tuple(tree.units)
        if units not in cuts_of:
            cuts_of[units] = prep.cut(problem, units)
        return cuts_of[units]

    met = False

    def seen(answer: TaskTree, model: clingo.Model) -> bool:
        nonlocal met
        if closed:
            if cut_of(answer) is not None:
                return True
            best[:] = [answer]
        watch.on_model(model)
        if on_model is not None:
            on_model(model)
        if prep.meets is not None and prep.meets(cost_vector(answer)):
            met = True
            return False
        return True

    def done(shot: Shot, answer: TaskTree | None) -> tuple[Shot, TaskTree | None, tuple[int, ...] | None, int]:
        if answer is not None and met:
            answer.status = "optimal"
            shot.finished = True
        return shot, answer, lower, cuts

    cuts = 0
    texts: list[str] = []  # the loop cuts' facts
    lower: tuple[int, ...] | None = None
    bound = prep.bound
    while True:
        left = None if deadline is None else max(deadline - time.perf_counter(), 1e-3)
        mode = "opt" if bound is None else "first"
        shot = solve_shot(control, mode, 1, None, left, watch.on_lower, watch.stop, on_answer=seen, bound=bound)
        if shot.lower is not None and (lower is None or shot.lower > lower):
            lower = shot.lower
        answer = shot.last
        if bound is not None and answer is None and shot.finished:
            bound = None  # no tree within the bound: optimise instead
            continue
        if not closed or answer is None or (best and best[0].units == answer.units):
            return done(shot, answer)
        cut = cut_of(answer)
        if cut is None:
            return done(shot, answer)
        # an optimal closed set that is no tree: its cost bounds every tree from below
        if bound is None and shot.finished and (lower is None or cost_vector(answer) > lower):
            lower = cost_vector(answer)
        if not shot.finished or (deadline is not None and time.perf_counter() >= deadline):
            shot.finished = False
            if best:
                best[0].status = "feasible"
            return done(shot, best[0] if best else None)
        cuts += 1
        missing, outside = cut
        texts.append(
            "".join(f"cut({cuts},{o}).\n" for o in missing) + "".join(f"outside({cuts},{u}).\n" for u in outside)
        )
        fresh = renew is not None
        if renew is not None:
            control, renew = renew(), None  # a multi-shot control from here on: later cuts are added to it
        for k, text in enumerate(texts, 1):
            if fresh or k == cuts:
                control.extend(f"cut {k}", text, [("cut", [k])], what="a loop cut")
