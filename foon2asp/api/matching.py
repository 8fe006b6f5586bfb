"""Looser matching in the knowledge base: goals, tree files and substitutes as the comparison
(hierarchy level, normalisation, synonyms; :mod:`foon2asp.foon.matching`) sees them."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from foon2asp.api.options import Options
from foon2asp.asp.options import AspOptions
from foon2asp.asp.substitutes import substitute_facts
from foon2asp.errors import InputError
from foon2asp.foon import goals as goals_mod
from foon2asp.foon.loaders import Dataset, read_goals
from foon2asp.foon.matching import Projection
from foon2asp.foon.model import FoonObject
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import Substitute, candidates, substituted_kitchen
from foon2asp.foon.treefiles import TreeFile, TreeUnit


class Matching:
    """The part of :class:`foon2asp.api.KnowledgeBase` that knows its comparison and substitutes."""

    data: Dataset
    problem: Problem
    projection: Projection
    _views: dict

    def object_id(self, goal: Any) -> int:
        """The object id of a goal (:meth:`foon2asp.api.KnowledgeBase.object_id`)."""
        raise NotImplementedError

    @property
    def joined(self) -> dict[str, list[str]]:
        """The spellings joined by ``normalize``/``synonyms``: first spelling -> every spelling
        (first first); only texts spelled more than one way."""
        return {first: list(all_) for first, all_ in self.projection.texts_joined.items()}

    def substitutes(self, options: Options | None) -> tuple[Substitute, ...]:
        """The substitutes of a request, spelled as this knowledge base spells labels."""
        if options is None or options.substitutes is None:
            return ()
        return self.projection.substitutes(options.substitute_table())

    def _substitute_facts(self, options: Options | None) -> str:
        """``substitute/3`` (and ``max_substitutions/1``) facts of a request's substitutes (foon2asp.asp.substitutes)."""
        table = self.substitutes(options)
        if not table:
            return ""
        return substitute_facts(self.problem, table, limit=options.max_substitutions if options else None)

    def judging_problem(self, solver: AspOptions | Options | None, goals: Iterable[int] = ()) -> Problem:
        """The problem a tree is judged on: with substitutes, every object one can stand in
        for (but ``goals``) is a kitchen item (foon2asp.asp.substitutes.validate_with)."""
        if isinstance(solver, Options | None):
            solver = AspOptions(substitutes=self.substitutes(solver))
        if not solver.substitutes:
            return self.problem
        if solver.substitutes not in self._views:
            self._views[solver.substitutes] = ([c.needed for c in candidates(self.problem, solver.substitutes)], {})
        needed, views = self._views[solver.substitutes]
        skip = frozenset(goals).intersection(needed)
        if skip not in views:
            views[skip] = substituted_kitchen(self.problem, [n for n in needed if n not in skip])
        return views[skip]

    def project_tree(self, tree: TreeFile) -> TreeFile:
        """A tree read from a file, its units and goal as this knowledge base's level sees them."""
        if self.projection.identity:
            return tree
        p = self.projection
        units = [TreeUnit(p.unit(tu.unit), tu.step, tu.line) for tu in tree.units]
        goal = None if tree.goal is None else p.object(tree.goal)
        return replace(tree, units=units, goal=goal)

    def _projected_id(self, text: str) -> tuple[int | None, str]:
        """The object an object's text names as the comparison sees it, else None and the text
        with its label spelled as the comparison spells labels."""
        stripped = text.strip()
        if stripped.startswith("#"):
            return None, text
        parsed = goals_mod.parse_object_text(stripped)
        if parsed is not None:
            found = self.problem.foon.object_ids.get(self.projection.object(parsed))
            if found is not None:
                return found, text
        if parsed is None or parsed == FoonObject(parsed.label):  # a label
            return None, self.projection.label(stripped)
        return None, text

    def _projected_goals(self, goal: Sequence[str], goals: str | Path | None) -> list[int]:
        """``select_goals`` when objects are compared loosely: goals files read as the comparison sees them."""
        named = [self.object_id(g) for g in goal]
        if goals is None and named:
            return named
        if goals is None or str(goals) in ("all", "all-objects"):
            return named + goals_mod.resolve(self.data, self.problem, (), None if goals is None else str(goals))
        path = str(goals)
        from_file = [goals_mod.goal_id(self.problem, self.projection.object(o), path, n) for o, n in read_goals(path)]
        if not from_file:
            raise InputError("the goals file lists no goal", path)
        return named + from_file
