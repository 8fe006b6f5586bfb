"""Looser matching: how ``load``'s level, normalisation and synonyms compare objects, and goals,
tree files and substitutes as that comparison (:mod:`foon2asp.foon.matching`) sees them."""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import replace
from pathlib import Path

from foon2asp.analysis import check as check_mod
from foon2asp.analysis import queries
from foon2asp.api.options import Options
from foon2asp.asp.options import AspOptions
from foon2asp.asp.substitutes import report as report_substitutions
from foon2asp.asp.substitutes import substitute_facts as substitute_facts_text
from foon2asp.errors import InputError
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.loaders import Dataset, read_goals
from foon2asp.foon.matching import Projection, Texts, parse_synonyms, read_synonyms
from foon2asp.foon.model import FoonObject
from foon2asp.foon.motioncost import MotionCosts, motion_key, unscaled
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import LINE_BREAKS, Substitute, candidates, substituted_kitchen, with_substitutes
from foon2asp.foon.treefiles import TreeFile, TreeUnit, read_trees
from foon2asp.tree.results import MissingResult, Report
from foon2asp.tree.tasktree import meal_of

#: a goal as the API takes it: a label, an object's text, ``"#ID"``, an object id or a FoonObject
GoalLike = str | int | FoonObject


def jobs(ids: Sequence[int], together: bool) -> list[int | tuple[int, ...]]:
    """The goals ``ids`` one by one, or with ``together`` one meal of them (a tuple)."""
    return [tuple(dict.fromkeys(ids))] if together else list(ids)


def projection(level: int, normalize: bool, synonyms: str | Path | Mapping[str, str] | None) -> Projection:
    """How objects are compared for ``load``'s ``level``, ``normalize`` and ``synonyms`` (checked
    before any FOON is read; :class:`foon2asp.foon.matching.Projection`)."""
    if isinstance(level, bool) or level not in (1, 2, 3):
        raise InputError(f"--level must be 1, 2 or 3, not {level!r}")
    if synonyms is None:
        table: dict[str, str] = {}
    elif isinstance(synonyms, Mapping):
        for text in (t for pair in synonyms.items() for t in pair):
            if not isinstance(text, str) or any(c in LINE_BREAKS for c in text):
                raise InputError(f"synonyms: a name must be a string without line breaks, not {text!r}")
        text = "".join(f"{name} = {canonical}\n" for name, canonical in synonyms.items())
        table = parse_synonyms(text, "synonyms", normalize)
    else:
        table = read_synonyms(synonyms, normalize)
    return Projection(level, Texts(normalize, table))


def joined(seen_as: Projection) -> dict[str, list[str]]:
    """The spellings ``seen_as`` joins: first spelling -> every spelling (first first); only texts
    spelled more than one way."""
    return {first: list(all_) for first, all_ in seen_as.texts_joined.items()}


def substitutes(seen_as: Projection, options: Options | None) -> tuple[Substitute, ...]:
    """The substitutes of a request, spelled as ``seen_as`` spells labels."""
    if options is None or options.substitutes is None:
        return ()
    return seen_as.substitutes(options.substitute_table())


def substitute_facts(problem: Problem, seen_as: Projection, options: Options | None) -> str:
    """``substitute/3`` (and ``max_substitutions/1``) facts of a request's substitutes (foon2asp.asp.substitutes)."""
    table = substitutes(seen_as, options)
    if not table:
        return ""
    return substitute_facts_text(problem, table, limit=options.max_substitutions if options else None)


def find_objects(
    problem: Problem, seen_as: Projection, query: str | None, only: str | None, options: Options | None
) -> list[int]:
    """Ids of the objects ``query`` names (:meth:`foon2asp.api.KnowledgeBase.find_objects`); with the
    substitutes of ``options``, ``derivable`` when they may stand in for kitchen items."""
    if only == "derivable" and substitutes(seen_as, options):
        problem = with_substitutes(problem, substitutes(seen_as, options))
    return goals_mod.find_objects(problem, query, only)


def object_info(problem: Problem, seen_as: Projection, oid: int) -> dict:
    """:func:`foon2asp.foon.goals.object_info` of ``oid``, with ``"joined"``: the texts of the
    objects it stands for when ``seen_as`` joined several."""
    info = goals_mod.object_info(problem, oid)
    texts = seen_as.sources.get(problem.objects[oid], [])
    if len(texts) > 1:
        info["joined"] = list(texts)
    return info


def costed(problem: Problem, weights: dict[str, int]) -> Problem:
    """``problem`` with the motion-cost table of the solver's ``weights`` (cost in hundredths per
    motion): every tree's measures then include ``cost``."""
    out = copy.copy(problem)  # what it caches does not depend on the costs
    out.motion_costs = MotionCosts({motion_key(m): unscaled(w) for m, w in weights.items()})
    return out


def judging_problem(problem: Problem, views: dict, table: tuple[Substitute, ...], goals: Iterable[int] = ()) -> Problem:
    """The problem a tree is judged on: with the substitutes of ``table``, every object one can
    stand in for (but ``goals``) is a kitchen item (foon2asp.asp.substitutes.validate_with);
    ``views`` keeps the problems made so far."""
    if not table:
        return problem
    if table not in views:
        views[table] = ([c.needed for c in candidates(problem, table)], {})
    needed, made = views[table]
    skip = frozenset(goals).intersection(needed)
    if skip not in made:
        made[skip] = substituted_kitchen(problem, [n for n in needed if n not in skip])
    return made[skip]


def project_tree(seen_as: Projection, tree: TreeFile) -> TreeFile:
    """A tree read from a file, its units and goal as ``seen_as`` sees them."""
    if seen_as.identity:
        return tree
    units = [TreeUnit(seen_as.unit(tu.unit), tu.step, tu.line) for tu in tree.units]
    goal = None if tree.goal is None else seen_as.object(tree.goal)
    return replace(tree, units=units, goal=goal)


def object_id(data: Dataset, problem: Problem, seen_as: Projection, goal: GoalLike) -> int:
    """The object id of a goal given as a label, an object's text, ``#ID``, an id or an object."""
    if isinstance(goal, FoonObject):
        return goals_mod.goal_id(problem, seen_as.object(goal))
    if isinstance(goal, int):
        if not 0 <= goal < len(problem.objects):
            raise InputError(f"no object #{goal}")
        return goal
    if not seen_as.identity:
        found, goal = _projected_id(problem, seen_as, goal)
        if found is not None:
            return found
    return goals_mod.resolve_goal(data, problem, goal)


def goal_ids(
    data: Dataset, problem: Problem, seen_as: Projection, goals: GoalLike | Iterable[GoalLike] | None
) -> list[int]:
    """Object ids for ``goals``: one goal, several, ``"all"`` (the goals file) or ``"all-objects"``."""
    if goals is None:
        return goals_mod.default_goals(data, problem)
    if goals == "all":
        return goals_mod.resolve(data, problem, (), "all")
    if goals == "all-objects":
        return goals_mod.all_objects(problem)
    if isinstance(goals, str | int | FoonObject):
        return [object_id(data, problem, seen_as, goals)]
    return [object_id(data, problem, seen_as, g) for g in goals]


def _projected_id(problem: Problem, seen_as: Projection, text: str) -> tuple[int | None, str]:
    """The object an object's text names as the comparison sees it, else None and the text
    with its label spelled as the comparison spells labels."""
    stripped = text.strip()
    if stripped.startswith("#"):
        return None, text
    parsed = goals_mod.parse_object_text(stripped)
    if parsed is not None:
        found = problem.foon.object_ids.get(seen_as.object(parsed))
        if found is not None:
            return found, text
    if parsed is None or parsed == FoonObject(parsed.label):  # a label
        return None, seen_as.label(stripped)
    return None, text


def select_goals(
    data: Dataset, problem: Problem, seen_as: Projection, goal: Sequence[str], goals: str | Path | None
) -> list[int]:
    """The goals a request names (:meth:`foon2asp.api.KnowledgeBase.select_goals`); when objects
    are compared loosely, goals files are read as the comparison sees them."""
    if seen_as.identity:
        return goals_mod.resolve(data, problem, tuple(goal), None if goals is None else str(goals))
    named = [object_id(data, problem, seen_as, g) for g in goal]
    if goals is None and named:
        return named
    if goals is None or str(goals) in ("all", "all-objects"):
        return named + goals_mod.resolve(data, problem, (), None if goals is None else str(goals))
    path = str(goals)
    from_file = [goals_mod.goal_id(problem, seen_as.object(o), path, n) for o, n in read_goals(path)]
    if not from_file:
        raise InputError("the goals file lists no goal", path)
    return named + from_file


def check_file(
    data: Dataset,
    problem: Problem,
    seen_as: Projection,
    view: Callable[[Iterable[int]], Problem],
    path: str | Path,
    goal: GoalLike | Sequence[GoalLike] | None,
    goals: Sequence[GoalLike] | str | Path | None,
    strict: bool,
) -> list[Report]:
    """The reports on every tree of a tree file read as ``seen_as`` sees it
    (:meth:`foon2asp.api.KnowledgeBase.check` without the optimum); ``view(goals)``: the
    problem a tree making ``goals`` is judged on."""

    def name(g: GoalLike) -> str:
        if isinstance(g, str) and seen_as.identity:
            return g
        return f"#{object_id(data, problem, seen_as, g)}"

    goal_list = [] if goal is None else [goal] if isinstance(goal, str | int | FoonObject) else list(goal)
    labels = tuple(name(g) for g in goal_list) or None
    among = None
    if isinstance(goals, str | Path):
        among = select_goals(data, problem, seen_as, (), goals)
    elif goals is not None:
        among = [object_id(data, problem, seen_as, g) for g in goals]
    files = [project_tree(seen_as, t) for t in read_trees(path, problem, strict)]
    reports = check_mod.check_trees(data, view(()), files, labels, among)
    for i, r in enumerate(reports):  # a goal a substitute stands in for is judged without it
        judged_on = view(r.meal)
        if judged_on is not view(()):
            reports[i] = check_mod.check_tree(judged_on, r.tree, r.goals or r.goal)
            reports[i].goal_source = r.goal_source
    return reports


def reachable(view: Callable[[Iterable[int]], Problem], ids: list[int]) -> dict[int, bool]:
    """For each of ``ids``: can it be made from the kitchen of ``view(())`` (one solve for all)?
    ``view(goals)``: the problem ``goals`` are judged on."""
    base = view(())
    answers = queries.reachable(base, ids)
    for goal in ids:  # a goal a substitute stands in for is not had by substituting it
        judged_on = view((goal,))
        if judged_on is not base:
            answers[goal] = queries.reachable(judged_on, [goal])[goal]
    return answers


def missing(
    problem: Problem, view: Callable[[Iterable[int]], Problem], target: int | tuple[int, ...], solver: AspOptions
) -> MissingResult:
    """:func:`foon2asp.analysis.queries.missing` of ``target`` (a goal or a meal); with the
    solver's substitutes, the fewest of them when nothing need be added, else judged on
    ``view(goals)``, and the substitutions the tree uses reported."""
    meal, judged_on = meal_of(target), problem
    if solver.substitutes:  # substitutes may stand in: the fewest of them when nothing need be added
        lenient = with_substitutes(problem, solver.substitutes)
        judged_on = lenient if all(g in lenient.derivable for g in meal) else view(meal)
    answer = queries.missing(judged_on, target, solver)
    if solver.substitutes:
        bought = substituted_kitchen(problem, answer.missing)  # the kitchen with what is added
        answer.substitutions = report_substitutions(bought, meal, answer.units, solver.substitutes)
    return answer
