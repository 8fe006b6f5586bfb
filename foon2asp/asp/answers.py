"""From models to task trees: one solve call's answers, their status and the tree they make.

Each model is read straight into a :class:`~foon2asp.tree.tasktree.TaskTree`
(:meth:`~foon2asp.tree.tasktree.TaskTree.from_model`); the answer's tree is then finished in
place (:func:`finish`).  When an answer counts as proven: docs/proofs/solving.md, "Proven
answers and the gap".
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import clingo

from foon2asp.asp import objectives
from foon2asp.asp.control import Control
from foon2asp.foon.problem import Problem
from foon2asp.tree.gap import gap_of
from foon2asp.tree.tasktree import Goals, TaskTree, executable_order, goal_fields, measures


@dataclass
class Shot:
    """The outcome of one solve call: the trees its models were read into (not yet finished)."""

    #: "opt", "first": the last model; "optN": the distinct optimal trees, smallest unit ids
    #: first (the last model when the search was cut short before one)
    answers: list[TaskTree] = field(default_factory=list)
    unsat: bool = False
    finished: bool = True
    exhausted: bool = False
    #: the last model the solver reported
    last: TaskTree | None = None
    #: the best lower bound the solver proved, per priority level
    lower: tuple[int, ...] | None = None


def solve_shot(
    control: Control,
    mode: str = "opt",
    count: int = 1,
    on_model: Callable[[clingo.Model], bool | None] | None = None,
    time_limit: float | None = None,
    on_lower: Callable[[tuple[int, ...]], None] | None = None,
    stop: Callable[[], bool] | None = None,
    on_answer: Callable[[TaskTree, clingo.Model], bool | None] | None = None,
    bound: Sequence[int] | None = None,
) -> Shot:
    """Solve once in ``mode`` (:meth:`Control.solving`) for at most ``time_limit`` seconds or until
    ``stop()``, ``on_model`` or ``on_answer`` (the model read into a tree) answers False."""
    optimal: dict[tuple[int, ...], TaskTree] = {}
    last: list[TaskTree] = []

    def record(model: clingo.Model) -> bool:
        answer = TaskTree.from_model(model)
        last[:] = [answer]
        if mode == "optN" and answer.proven:
            optimal.setdefault(tuple(answer.units), answer)
        if (on_answer is not None and on_answer(answer, model) is False) or (
            on_model is not None and on_model(model) is False
        ):
            if mode != "opt":
                return False
            control.stop_soon()  # answering False can break clasp's core shrinking
        return True

    with control.solving(mode, count, bound):
        result = control.solve(record, time_limit, on_lower=on_lower, stop=stop)
    finished = result.finished
    latest = last[0] if last else None
    if latest is not None and mode != "first" and (finished or not any(latest.asp_cost or ())):
        latest.status = "optimal"  # its search ended, or it has no cost
    found = [latest] if latest is not None else []
    if mode == "optN":
        found = sorted(optimal.values(), key=lambda a: a.units) or ([] if finished else found)
    return Shot(found, result.unsatisfiable is True, finished, result.exhausted, latest, result.lower)


class Watch:
    """The best cost and proven lower bound while one goal is solved: reported to ``progress`` and,
    with a ``target`` gap (on level ``first``, the lower bound raised to ``floor``), the signal to stop."""

    def __init__(
        self,
        first: int = 0,
        target: float | None = None,
        floor: int | None = None,
        progress: Callable[[dict], None] | None = None,
    ) -> None:
        self.first, self.target, self.floor, self.progress = first, target, floor, progress
        self.cost: tuple[int, ...] | None = None
        self.lower: tuple[int, ...] | None = None

    def on_model(self, model: clingo.Model) -> None:
        cost = tuple(model.cost)
        if self.cost is None or cost < self.cost:
            self.cost = cost
        self._report()

    def on_lower(self, lower: tuple[int, ...]) -> None:
        self.lower = lower
        self._report()

    def gap(self) -> float | None:
        if not self.cost:
            return None
        return gap_of(self.cost, self.lower, self.first, self.floor)

    def stop(self) -> bool:
        if not self.target or self.target <= 0:
            return False
        found = self.gap()
        return found is not None and 0 < found <= self.target

    def _report(self) -> None:
        if self.progress is not None:
            lower = list(self.lower or ())
            if self.floor is not None and self.first == 0:
                lower = [max(lower[0] if lower else 0, self.floor), *lower[1:]]
            self.progress({"cost": list(self.cost or ()), "lower": lower, "gap": self.gap()})


def cost_vector(tree: TaskTree) -> tuple[int, ...]:
    """The solver's cost vector of ``tree`` (:attr:`~TaskTree.asp_cost`), to compare with bounds."""
    return tuple(tree.asp_cost or ())


def status(answer: TaskTree | None, shot: Shot, best: list[int] | None = None) -> str:
    """``optimal``, ``ranked`` (proven best once the better trees are excluded, cost above ``best``),
    ``feasible`` (not proven), or without an answer ``unreachable`` or ``unknown`` (cut short)."""
    if answer is None:
        return "unreachable" if shot.unsat else "unknown"
    if not answer.proven:
        return "feasible"
    return "optimal" if best is None or answer.asp_cost == best else "ranked"


def finish(
    problem: Problem,
    method: str,
    goal: Goals,
    status: str,
    answer: TaskTree | None,
    time_s: float,
    stats: dict,
    human_steps: bool = False,
) -> TaskTree:
    """``answer``, the tree a model was read into, finished in place for ``goal`` by ``method``:
    its status, its units in executable order, their measures, the time and statistics
    (None: a new tree without units); ``human_steps``: the steps a person does are kept, in
    executable order, else dropped."""
    if answer is None:
        return TaskTree(method=method, status=status, time_s=round(time_s, 6), stats=stats, **goal_fields(goal))
    tree, fields = answer, goal_fields(goal)
    tree.goal, tree.goals = fields["goal"], fields["goals"]
    tree.method, tree.status, tree.time_s, tree.stats = method, status, round(time_s, 6), stats
    units = tree.units = executable_order(problem, tree.units)
    tree.cost = measures(problem, goal, units)
    if human_steps:
        human = set(tree.human_steps or ())
        tree.cost["success"] = objectives.success_product(problem, units, human)
        tree.human_steps = [u for u in units if u in human]
        tree.human_step_numbers = [i for i, u in enumerate(units, 1) if u in human]
    else:
        tree.human_steps = None
    return tree
