"""Consolidating candidate trees of one recipe into one proven-best tree."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import replace
from pathlib import Path

from foon2asp.analysis import queries
from foon2asp.asp.options import AspOptions
from foon2asp.errors import InputError
from foon2asp.foon.model import Foon, FoonObject
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import judged_on
from foon2asp.foon.treefiles import TreeUnit, read_trees
from foon2asp.methods.runner import solve_goals
from foon2asp.outcomes import Candidate, CandidateVerdict, Consolidation
from foon2asp.tree.tasktree import Goals, meal_of, measures
from foon2asp.tree.validate import judge_alone, last_products


def read_candidates(paths: Iterable[str | Path], strict: bool = False) -> list[Candidate]:
    """Each file as one candidate: its units, distinct, in file order; ``strict``: a unit a unit
    list would skip is an error."""
    out = []
    for path in paths:
        trees = read_trees(path, strict=strict)
        first: dict[tuple, TreeUnit] = {}
        for tu in (tu for tree in trees for tu in tree.units):
            first.setdefault(tu.unit.key(), tu)
        units = list(first.values())
        warnings = [w for tree in trees for w in tree.warnings]
        out.append(Candidate(str(path), units, warnings))
    if not out:
        raise InputError("no candidate tree given")
    return out


def merge(candidates: Sequence[Candidate]) -> tuple[Foon, list[list[str]]]:
    """The merged FOON of the candidates (a unit in several files once, its origin the first)
    and, per unit id, the files holding it in the order given."""
    foon = Foon()
    sources: list[list[str]] = []
    for cand in candidates:
        for tu in cand.units:
            uid = foon.add_unit(tu.unit, (cand.path, tu.line if tu.line is not None else tu.step))
            if uid == len(sources):
                sources.append([])
            if cand.path not in sources[uid]:
                sources[uid].append(cand.path)
    return foon, sources


def candidate_goals(candidates: Sequence[Candidate]) -> list[tuple[FoonObject, int]]:
    """Every product of a candidate's last unit with how many candidates share it, most shared first."""
    made = [last_products([tu.unit for tu in c.units]) for c in candidates]
    counts = Counter(o for products in made for o in set(products))
    order = list(dict.fromkeys(o for products in made for o in products))
    return sorted(((o, counts[o]) for o in order), key=lambda pair: -pair[1])


def shared_goal(candidates: Sequence[Candidate]) -> tuple[FoonObject, str]:
    """The product of the candidates' last units that most of them share, and where it came from in words."""
    ranked = candidate_goals(candidates)
    if not ranked:
        raise InputError("no candidate's last unit makes an object: name the goal", hint="no-goal")
    obj, n = ranked[0]
    return obj, f"the product of the last unit of {n} of {len(candidates)} candidates"


def judge(problem: Problem, goals: tuple[int, ...], cand: Candidate, tree_units: Iterable[int]) -> CandidateVerdict:
    """``cand`` for ``goals``: on its own units, in file order, from the problem's kitchen."""
    units = [tu.unit for tu in cand.units]
    ids = [uid for uid in map(problem.foon.unit_id, units) if uid is not None]
    assert len(ids) == len(units), "the FOON merges the candidates: each of their units is in it"
    objects = tuple(problem.objects[g] for g in goals)
    numbers = [tu.step for tu in cand.units]
    verdict = judge_alone(units, objects, problem.kitchen_items, problem.utensils, problem.utensil_rule, numbers)
    used = set(tree_units)
    steps = [tu.step for tu, u in zip(cand.units, ids) if u in used]
    return CandidateVerdict(cand, verdict, ids, measures(problem, goals, list(dict.fromkeys(ids))), steps)


def consolidate(
    problem: Problem,
    candidates: Sequence[Candidate],
    sources: list[list[str]],
    goals: Sequence[Goals],
    options: AspOptions | None = None,
    goal_source: str = "",
    kitchen_source: str = "leaves",
) -> list[Consolidation]:
    """For each of ``goals`` (a meal: a tuple) of the merged FOON ``problem``: the best tree,
    every candidate's verdict and, when unreachable, what to add."""
    options = options or AspOptions()
    out = []
    for goal, tree in zip(goals, solve_goals(problem, goals, "asp", options)):
        meal = meal_of(goal)
        missing = None
        if tree.status == "unreachable":
            target: Goals = meal if len(meal) > 1 else meal[0]
            objective = tuple(o for o in options.objective if o in queries.MISSING_OBJECTIVES) or ("units",)
            missing = queries.missing(problem, target, replace(options, objective=objective))
        seen = judged_on(problem, options.substitutes, meal)  # with substitutes, what they stand in for is had
        verdicts = [judge(seen, meal, c, tree.units) for c in candidates]
        out.append(
            Consolidation(
                meal, tree, sources, verdicts, missing, goal_source, kitchen_source, list(problem.kitchen_items)
            )
        )
    return out
