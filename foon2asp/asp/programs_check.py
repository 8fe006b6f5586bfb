"""The user's programs asked of given trees: does a tree satisfy every constraint?

The programs are grounded once with the facts and ``encodings/check_trees.lp`` (every
``use/1`` atom an external); each tree is one solve with its units switched on.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import clingo

from foon2asp.asp import encoding_files
from foon2asp.asp.control import Control
from foon2asp.asp.facts import facts
from foon2asp.foon.problem import Problem


class _Constraints(clingo.Observer):
    """Sees whether grounding left any integrity constraint (a rule with an empty head)."""

    def __init__(self) -> None:
        self.found = False

    def rule(self, choice: bool, head: Sequence[int], body: Sequence[int]) -> None:
        self.found = self.found or (not choice and not head)

    def weight_rule(self, choice: bool, head: Sequence[int], lower_bound: int, body: Sequence[tuple[int, int]]) -> None:
        self.found = self.found or (not choice and not head)


class ProgramsCheck:
    """The user's ``programs`` grounded once over ``problem``'s ``units`` (None: all), asked tree by tree."""

    def __init__(
        self,
        problem: Problem,
        programs: Sequence[tuple[str, str]],
        units: Iterable[int] | None = None,
        time_limit: float | None = None,
    ):
        """``time_limit``: seconds for each tree asked (None: no limit); a tree not decided by then
        does not count as satisfying the programs."""
        self.time_limit = time_limit
        self.control = Control(["--opt-mode=ignore"])
        ids = sorted(set(units)) if units is not None else None
        self.control.load(encoding_files.entry("check_trees"))
        self.control.add_all([("facts", facts(problem, units=ids)), *programs], user=[name for name, _ in programs])
        seen = _Constraints()
        self.control.ctl.register_observer(seen)
        self.control.ground()
        self.vacuous = not seen.found

    def allows(self, tree: Iterable[int]) -> bool:
        """Does the tree whose units are ``tree`` satisfy every program?"""
        if self.vacuous:
            return True
        atoms = [clingo.Function("use", [clingo.Number(u)]) for u in tree]
        with self.control.switched(a for a in atoms if self.control.has_atom(a)):
            result = self.control.solve(time_limit=self.time_limit)
            return result.finished and result.satisfiable is True
