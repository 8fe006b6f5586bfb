"""Does a given tree satisfy the user's constraints?  One grounding, one decision per tree.

The programs are grounded once with ``use/1`` as externals (docs/proofs/solving.md, "The routes").
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import clingo

from foon2asp.asp.control import Control
from foon2asp.asp.facts import facts
from foon2asp.asp.predicates import FACTS, predicates
from foon2asp.foon.problem import Problem


def checkable(programs: Iterable[tuple[str, str]]) -> bool:
    """Do the ``programs`` read only the facts, ``use/1`` and what they define themselves?"""
    allowed = set(FACTS) | {("use", 1)}
    for _, text in programs:
        try:
            found = predicates(text)
        except RuntimeError:
            return False
        if not set(found.used) <= allowed | found.defined:
            return False
    return True


class _Constraints(clingo.Observer):
    """Sees whether grounding left any integrity constraint (a rule with an empty head)."""

    def __init__(self) -> None:
        self.found = False

    def rule(self, choice: bool, head: Sequence[int], body: Sequence[int]) -> None:
        self.found = self.found or (not choice and not head)

    def weight_rule(self, choice: bool, head: Sequence[int], lower_bound: int, body: Sequence[tuple[int, int]]) -> None:
        self.found = self.found or (not choice and not head)


class ConstraintCheck:
    """The user's ``programs`` grounded once over ``problem``'s ``units`` (None: all), asked tree by tree."""

    def __init__(self, problem: Problem, programs: Sequence[tuple[str, str]], units: Iterable[int] | None = None):
        self.control = Control(["--opt-mode=ignore"])
        ids = sorted(set(units)) if units is not None else None
        parts = [("facts", facts(problem, units=ids)), ("trees", "#external use(U) : unit(U).\n")]
        self.control.add_all([*parts, *programs], user=[name for name, _ in programs])
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
            return self.control.solve().satisfiable is True
