"""Many goals decided by one clingo call: :class:`~foon2asp.asp.grounding.Decisions`.

Each goal's bounds tree meets its lower bound, so a tree within that cost is optimal.
clingo searches every goal's closed sets within its bound at once (``encodings/decide_many.lp``);
a goal whose set is a tree is decided, and answered as its own search would answer it: the
hint (the bounds tree), optimal.  A goal whose set rests on a cycle, or every goal when the
search is cut short, is left to its own search.
"""

from __future__ import annotations

import clingo

from foon2asp.asp import encoding_files
from foon2asp.asp.answers import finish
from foon2asp.asp.control import Control
from foon2asp.asp.grounding import Decisions, Grounding
from foon2asp.tree.gap import settle
from foon2asp.tree.tasktree import TaskTree


def decide(group: Decisions) -> set[int]:
    """The goals of ``group`` clingo found a tree for within their bounds (none when the search
    ran out of time or found no model)."""
    control = Control(list(group.args))
    control.statistics = False
    control.load(encoding_files.entry(group.entry))
    control.add("decisions", group.facts())
    control.ground()
    preps = group.preparations
    differ: dict[int, list[int]] = {}  # goal number -> its set, when that is not its hint

    def on_model(model: clingo.Model) -> None:
        differ.clear()
        for atom in model.symbols(shown=True):
            if atom.name == "differs":
                differ.setdefault(atom.arguments[0].number, [])
            else:
                k, u = atom.arguments
                differ.setdefault(k.number, []).append(u.number)

    with control.solving("first"):
        result = control.solve(on_model, group.time_limit)
    if not (result.finished and result.satisfiable):
        return set()
    # a set shown is not the hint; the others are: either is a tree when it derives the goal
    return {prep.goal for k, prep in enumerate(preps, 1) if prep.cut(group.problem, differ.get(k, prep.hint)) is None}


def decided(grounding: Grounding, time_s: float) -> TaskTree:
    """The answer of a prepared ``grounding`` whose goal was decided (:func:`decide`): the hint,
    optimal, as the goal's own search answers a tree that meets the lower bound."""
    prep = grounding.prepared
    assert prep is not None and prep.known is not None, "a decided goal has a bounds tree"
    method, known = grounding.options.method, list(prep.known)
    answer = TaskTree(prep.goal, method, "optimal", sorted(prep.hint), asp_cost=known)
    tree = finish(grounding.problem, method, (prep.goal,), "optimal", answer, time_s, {"lower": known})
    return settle(grounding.problem, tree, grounding.levels, known, prep.floor)
