"""clintest cases for every shipped encoding (encodings/*.lp, their parts and show files) and every objective.

Each case is a tiny FOON as facts (plus the facts the wrapper writes for the encoding), the
entry files the product loads (clingo resolves their ``#include`` directives), and the expected models
or optimum: the atoms shown and the cost, never mere satisfiability.

Single-shot cases run on :class:`clintest.solver.Clingo`.  Multi-shot cases (depth.lp's
``bound``/``meal`` parts, canonical.lp's externals) and schedule_dl.lp (a clingo-dl theory)
run on :class:`Shots`, a :class:`clintest.solver.Solver` that grounds parts with arguments and
switches externals as the drivers do, and with clingo-dl shows its assignment as ``dl(V,N)``
atoms (N relative to the zero node), so the same clintest assertions read it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

import clingo
import clingo.ast
import pytest
from clingodl import ClingoDLTheory
from clintest import assertion as a
from clintest import quantifier as q
from clintest import test as t
from clintest.solver import Clingo, Solver

from foon2asp.asp.encoding_files import root
from foon2asp.asp.multishot.depth import Levels

OPT = ["--opt-mode=optN", "0", "--warn=none"]  # every optimal model, each marked optimal
ALL = ["--opt-mode=ignore", "0", "--warn=none"]  # every model, costs ignored
DOMAIN = ["--heuristic=Domain", "1", "--warn=none"]  # the first model under the domain heuristic

Units = dict[int, tuple[Sequence[int], Sequence[int]]]


# --- building the programs -------------------------------------------------------------------


def foon(units: Units, kitchen: Iterable[int], goals: Iterable[int] = ()) -> str:
    """The facts of a tiny FOON: unit U requires ``units[U][0]`` and makes ``units[U][1]``."""
    lines = []
    for u, (required, products) in units.items():
        lines.append(f"unit({u}).")
        lines += [f"required({u},{o})." for o in required]
        lines += [f"product({u},{o})." for o in products]
    lines += [f"kitchen({o})." for o in kitchen]
    lines += [f"goal({g})." for g in goals]
    return "\n".join(lines) + "\n"


def files(names: Sequence[str]) -> list[str]:
    """The paths of the shipped encodings ``names``: entries (``solve``), or ``parts/NAME``, ``show/NAME``."""
    return [str(root() / f"{name}.lp") for name in names]


def program(names: Sequence[str], *facts: str) -> tuple[list[str], str]:
    """The shipped encodings ``names`` (:func:`files`, loaded by clingo) and the facts as one program."""
    return files(names), "\n".join(facts)


def solver(names: Sequence[str], *facts: str, args: Sequence[str] = OPT) -> Clingo:
    paths, text = program(names, *facts)
    return Clingo(list(args), text, paths)


def check(solver: Solver, test: t.Test) -> None:
    solver.solve(test)
    test.assert_()


# --- assertions and tests --------------------------------------------------------------------


class Cost(a.Assertion):
    """Holds if the model's cost vector (highest priority first) is ``cost``."""

    def __init__(self, *cost: int) -> None:
        self.cost = list(cost)

    def __repr__(self) -> str:
        return f"Cost({self.cost})"

    def holds_for(self, model) -> bool:
        return list(model.cost) == self.cost


def atoms(*names: str) -> a.Equals:
    return a.Equals(set(names))


def models(n: int, each: a.Assertion | None = None) -> t.Test:
    """Exactly ``n`` models, each satisfying ``each`` (if given)."""
    return t.And(t.Assert(q.Exact(n), a.True_()), t.Assert(q.All(), each or a.True_()))


def unsat() -> t.Test:
    return t.Assert(q.Exact(0), a.True_())


def optimum(shown: Iterable[str], *cost: int) -> t.Test:
    """Exactly one optimal model (run with OPT): these shown atoms, this cost."""
    return t.And(
        t.Assert(q.Exact(1), a.Optimal()),
        t.Assert(q.All(), a.Implies(a.Optimal(), a.And(a.Equals(set(shown)), Cost(*cost)))),
    )


def optima(choices: Sequence[Iterable[str]], *cost: int) -> t.Test:
    """The optimal models are exactly ``choices`` (run with OPT), each of this cost."""
    sets = [a.Equals(set(c)) for c in choices]
    return t.And(
        t.Assert(q.Exact(len(sets)), a.Optimal()),
        t.Assert(q.All(), a.Implies(a.Optimal(), a.And(a.Or(*sets), Cost(*cost)))),
        *(t.Assert(q.Any(), a.And(a.Optimal(), s)) for s in sets),
    )


def first(shown: Iterable[str]) -> t.Test:
    return t.Assert(q.First(), a.Equals(set(shown)))


def use(*units: int) -> list[str]:
    return [f"use({u})" for u in units]


# --- a solver for parts with arguments, externals and clingo-dl ------------------------------


class _TheoryModel:
    """A model with the theory's assignment shown as ``dl(V,N)`` atoms (for clintest's assertions)."""

    def __init__(self, model: clingo.Model, values: list[tuple[clingo.Symbol, int]]) -> None:
        self.model = model
        zero = dict((str(s), v) for s, v in values).get("0", 0)
        self.extra = {clingo.Function("dl", [s, clingo.Number(v - zero)]) for s, v in values if str(s) != "0"}

    def symbols(self, shown: bool = False, **kw) -> list[clingo.Symbol]:
        return [*self.model.symbols(shown=shown, **kw), *(self.extra if shown else ())]

    def contains(self, symbol: clingo.Symbol) -> bool:
        return symbol in self.extra or self.model.contains(symbol)

    @property
    def optimality_proven(self) -> bool:
        return self.model.optimality_proven

    @property
    def cost(self) -> list[int]:
        return self.model.cost

    def __str__(self) -> str:
        return " ".join(sorted(str(s) for s in self.symbols(shown=True)))


class Shots(Solver):
    """clingo grounding ``grounds`` one after the other (each a list of parts with their number
    arguments), then switching ``externals`` on; with ``theory`` (a clingo theory class, e.g.
    clingo-dl's) the program is rewritten for it and its assignment shown as ``dl/2``."""

    def __init__(
        self,
        arguments: Sequence[str],
        program: tuple[list[str], str],
        grounds: Sequence[Sequence[tuple[str, Sequence[int]]]] = ((("base", ()),),),
        externals: Iterable[str] = (),
        theory: Callable[[], object] | None = None,
    ) -> None:
        self.arguments = list(arguments)
        self.program = program
        self.grounds = grounds
        self.externals = list(externals)
        self.theory = theory

    def solve(self, test: t.Test) -> None:
        ctl = clingo.Control(self.arguments)
        theory = self.theory() if self.theory is not None else None
        paths, text = self.program
        if theory is None:
            for path in paths:
                ctl.load(path)
            ctl.add("base", [], text)
        else:
            theory.register(ctl)
            with clingo.ast.ProgramBuilder(ctl) as builder:
                clingo.ast.parse_files(paths, lambda stm: theory.rewrite_ast(stm, builder.add))
                clingo.ast.parse_string(text, lambda stm: theory.rewrite_ast(stm, builder.add))
        for parts in self.grounds:
            ctl.ground([(name, [clingo.Number(x) for x in args]) for name, args in parts])
        if theory is not None:
            theory.prepare(ctl)
        for name in self.externals:
            ctl.assign_external(clingo.parse_term(name), True)

        def on_model(model: clingo.Model) -> bool:
            if theory is None:
                return test.on_model(model)
            theory.on_model(model)
            return test.on_model(_TheoryModel(model, list(theory.assignment(model.thread_id))))

        if not test.outcome().is_certain():
            ctl.solve(on_model=on_model, on_unsat=test.on_unsat, on_finish=test.on_finish)


# --- tree.lp ---------------------------------------------------------------------------------

# 1 is in the kitchen; 0 and 1 make 9 through 2
CHAIN = foon({0: ([1], [2]), 1: ([2], [9])}, [1], [9])

# the honest path 2,3,4 (k -> a -> b -> g) and the cycle 0 (x -> g), 1 (g -> x)
CYCLE = foon({0: ([5], [4]), 1: ([4], [5]), 2: ([1], [2]), 3: ([2], [3]), 4: ([3], [4])}, [1], [4])


def test_tree_a_chain_is_the_only_tree():
    check(solver(["solve"], CHAIN, args=ALL), models(1, atoms(*use(0, 1))))


def test_tree_cycle_never_supports_a_unit():
    # every tree has the honest path; the cycle's units only ever ride on it
    each = a.And(
        a.SupersetOf(set(use(2, 3, 4))),
        a.Implies(a.Contains("use(0)"), a.Contains("use(1)")),
    )
    trees = [use(2, 3, 4), use(1, 2, 3, 4), use(0, 1, 2, 3, 4)]
    check(solver(["solve"], CYCLE, args=ALL), t.And(models(3, each), *(t.Assert(q.Any(), atoms(*s)) for s in trees)))


def test_tree_cycle_alone_has_no_tree():
    # 9 is made only from 5 and 5 only from 9: neither is reachable from the kitchen
    check(solver(["solve"], foon({0: ([5], [9]), 1: ([9], [5])}, [1], [9]), args=ALL), unsat())


def test_tree_landmark_is_forced():
    # 0 and 1 each make 9 from the kitchen; landmark(1) puts 1 in every tree
    facts = foon({0: ([1], [9]), 1: ([1], [9])}, [1], [9]) + "landmark(1).\n"
    check(solver(["solve"], facts, args=ALL), models(2, a.Contains("use(1)")))


def test_tree_landmark_decides_the_optimum():
    facts = foon({0: ([1], [9]), 1: ([1], [9])}, [1], [9]) + "landmark(1).\nobjective(units,1).\n"
    check(solver(["solve"], facts), optimum(use(1), 1))


def test_tree_goal_in_the_kitchen_needs_no_unit():
    check(solver(["solve"], foon({0: ([1], [9])}, [1, 9], [9]), args=ALL), models(1, atoms()))


def test_tree_never_makes_a_kitchen_item():
    # 0 makes 2, which the kitchen has: 0 is no candidate
    facts = foon({0: ([1], [2]), 1: ([2], [9])}, [1, 2], [9])
    check(solver(["solve"], facts, args=ALL), models(1, atoms(*use(1))))


def test_tree_never_uses_a_unit_that_cannot_fire():
    # 2 needs 7, which nothing makes
    facts = foon({0: ([1], [3]), 1: ([3], [9]), 2: ([7], [9])}, [1], [9])
    check(solver(["solve"], facts, args=ALL), models(1, atoms(*use(0, 1))))


def test_tree_reads_required_inputs_only():
    # 0 lists 7 as an input, not a required one: 7 need not be had
    facts = foon({0: ([1], [9])}, [1], [9]) + "input(0,1).\ninput(0,7).\n"
    check(solver(["solve"], facts, args=ALL), models(1, atoms(*use(0))))


def test_tree_shared_intermediate_is_made_and_counted_once():
    # 9 needs 3 and 4, both made from 2; 2 is made once (by 0) and counted once
    facts = foon({0: ([1], [2]), 1: ([2], [3]), 2: ([2], [4]), 3: ([3, 4], [9])}, [1], [9])
    check(solver(["solve"], facts, "objective(units,1).\n"), optimum(use(0, 1, 2, 3), 4))


def test_tree_without_a_producer_of_the_goal_has_no_tree():
    check(solver(["solve"], foon({0: ([1], [2])}, [1], [9]), args=ALL), unsat())


# --- prepared.lp -----------------------------------------------------------------------------

# 0 and 1 make 9 from the kitchen, 2 makes 3 and 3 makes 9 from it
ALTERNATIVES = {0: ([1], [9]), 1: ([1], [9]), 2: ([1], [3]), 3: ([3], [9])}


def prepared(units: Units, kitchen, goal, candidates, extra: str = "") -> str:
    """The facts of a prepared part: the candidates' objects only, as the wrapper writes them."""
    part = foon({u: units[u] for u in candidates}, kitchen, [goal])
    return part + "".join(f"candidate({u}).\n" for u in candidates) + extra


def test_prepared_candidates_restrict_the_trees():
    facts = prepared(ALTERNATIVES, [1], 9, [1, 2, 3])
    check(solver(["solve_prepared"], facts, args=ALL), models(4, a.Not(a.Contains("use(0)"))))


def test_prepared_candidates_decide_the_optimum():
    facts = prepared(ALTERNATIVES, [1], 9, [2, 3], "objective(units,1).\n")
    check(solver(["solve_prepared"], facts), optimum(use(2, 3), 2))


def test_prepared_cycle_of_candidates_is_no_tree():
    facts = prepared({0: ([5], [9]), 1: ([9], [5])}, [1], 9, [0, 1])
    check(solver(["solve_prepared"], facts, args=ALL), unsat())


def test_prepared_landmark_forces_its_unit():
    # without the landmark the optimum is 0 alone; landmark(3) needs 2 as well
    facts = prepared(ALTERNATIVES, [1], 9, [0, 2, 3], "landmark(3).\nobjective(units,1).\n")
    check(solver(["solve_prepared"], facts), optimum(use(2, 3), 2))


def test_prepared_landmark_in_every_tree():
    facts = prepared(ALTERNATIVES, [1], 9, [0, 1, 2, 3], "landmark(2).\n")
    check(solver(["solve_prepared"], facts, args=ALL), models(7, a.Contains("use(2)")))


def test_prepared_hint_leaves_the_other_candidates_out():
    facts = prepared(ALTERNATIVES, [1], 9, [0, 1, 2, 3], "hint(0).\n")
    check(solver(["solve_prepared"], facts, args=DOMAIN), first(use(0)))


def test_prepared_hint_units_are_tried_first():
    # the hinted tree need not be the smallest
    facts = prepared(ALTERNATIVES, [1], 9, [0, 1, 2, 3], "hint(1).\nhint(2).\nhint(3).\n")
    check(solver(["solve_prepared"], facts, args=DOMAIN), first(use(1, 2, 3)))


def test_prepared_goal_in_the_kitchen_needs_no_unit():
    check(solver(["solve_prepared"], prepared({}, [1, 9], 9, []), args=ALL), models(1, atoms()))


# --- closed.lp: closed sets, and loop cuts as part cut(k) --------------------------------------

# 0 and 1 make 4 and 5 from each other; the chain 2, 3, 4 makes 4 from the kitchen
LOOP = {0: ([5], [4]), 1: ([4], [5]), 2: ([1], [2]), 3: ([2], [3]), 4: ([3], [4])}


def closed(units: Units, kitchen, goal, candidates, extra: str = "", cuts: int = 0) -> Shots:
    """closed.lp with the units objective over a prepared part, grounded with ``cuts`` loop cuts."""
    text = program(["solve_closed"], prepared(units, kitchen, goal, candidates, extra), "objective(units,1).\n")
    return Shots(OPT, text, [[("base", ()), *(("cut", (k,)) for k in range(1, cuts + 1))]])


def test_closed_admits_a_cycle_that_is_no_tree():
    facts = prepared({0: ([5], [9]), 1: ([9], [5])}, [1], 9, [0, 1])
    check(solver(["solve_closed"], facts, args=ALL), models(1, atoms(*use(0, 1))))


def test_closed_cut_without_outside_producers_leaves_no_set():
    cut = "cut(1,9). cut(1,5).\n"
    check(closed({0: ([5], [9]), 1: ([9], [5])}, [1], 9, [0, 1], cut, cuts=1), unsat())


def test_closed_optimum_rests_on_the_cheaper_cycle():
    check(closed(LOOP, [1], 4, range(5)), optimum(use(0, 1), 2))


def test_closed_loop_cut_leaves_the_tree():
    # the cycle's objects 4 and 5 are made from outside them only by 4 (from 3)
    cut = "cut(1,4). cut(1,5). outside(1,4).\n"
    check(closed(LOOP, [1], 4, range(5), cut, cuts=1), optimum(use(2, 3, 4), 3))


def test_closed_a_cut_not_grounded_is_not_applied():
    cut = "cut(1,4). cut(1,5). outside(1,4).\n"
    check(closed(LOOP, [1], 4, range(5), cut, cuts=0), optimum(use(0, 1), 2))


def test_closed_every_needed_input_is_made():
    # 1 would need 6, which nothing makes and the kitchen lacks
    check(closed(JOIN, [1], 9, [0, 1, 2, 3]), optimum(use(0, 2, 3), 3))


def test_closed_landmark_forces_its_unit():
    check(closed(ALTERNATIVES, [1], 9, [0, 2, 3], "landmark(3).\n"), optimum(use(2, 3), 2))


def test_closed_hint_units_are_tried_first():
    facts = prepared(ALTERNATIVES, [1], 9, [0, 1, 2, 3], "hint(1).\nhint(2).\nhint(3).\n")
    check(solver(["solve_closed"], facts, args=DOMAIN), first(use(1, 2, 3)))


def test_closed_goal_in_the_kitchen_needs_no_unit():
    check(solver(["solve_closed"], prepared({}, [1, 9], 9, []), args=ALL), models(1, atoms()))


# --- decide_many.lp: many goals, each decided at its bound -------------------------------------


def decide(units: Units, kitchen, goals: dict[int, tuple[int, Sequence[int], Sequence[int]]], extra: str = "") -> str:
    """The facts of a grouped decision: goal K is ``(object, candidates, bound per level)``, the
    units objective (weight 1 at level 1), the candidates' objects only, as the wrapper writes them."""
    lines = []
    used: set[int] = set()
    for k, (goal, candidates, bounds) in goals.items():
        used.update(candidates)
        lines.append(f"decide({k},{goal}).")
        lines += [f"candidate({k},{u})." for u in candidates]
        lines += [f"budget({k},{level},{b})." for level, b in enumerate(bounds, 1)]
    for u in sorted(used):
        required, products = units[u]
        lines += [f"required({u},{o})." for o in required]
        lines += [f"product({u},{o})." for o in products]
        lines.append(f"weight(1,{u},1).")
    lines += [f"kitchen({o})." for o in kitchen]
    return "\n".join(lines) + "\n" + extra


def decided(*pairs: tuple[int, int]) -> list[str]:
    """What a model shows of sets that are not their goal's hinted tree: each unit, and the goal."""
    return [f"use({k},{u})" for k, u in pairs] + [f"differs({k})" for k in sorted({k for k, _ in pairs})]


def test_decide_each_goal_gets_a_set_within_its_bound():
    # goal 1 (object 9): 0 or 1 alone, or 2 and 3; goal 2 (object 3): 2 alone
    facts = decide(ALTERNATIVES, [1], {1: (9, [0, 1, 2, 3], [1]), 2: (3, [2, 3], [1])})
    sets = [decided((1, 0), (2, 2)), decided((1, 1), (2, 2))]
    check(solver(["decide_many"], facts, args=ALL), models(2, a.Or(*(a.Equals(set(x)) for x in sets))))


def test_decide_a_bound_below_every_set_leaves_no_model():
    facts = decide(ALTERNATIVES, [1], {1: (9, [0, 1, 2, 3], [0]), 2: (3, [2, 3], [1])})
    check(solver(["decide_many"], facts, args=ALL), unsat())


def test_decide_a_looser_bound_admits_dearer_sets():
    # 0 alone, 2 and 3, or 0 with 2 (whose 3 nothing needs); never all three
    facts = decide(ALTERNATIVES, [1], {1: (9, [0, 2, 3], [2])})
    sets = [decided((1, 0)), decided((1, 2), (1, 3)), decided((1, 0), (1, 2))]
    check(solver(["decide_many"], facts, args=ALL), models(3, a.Or(*(a.Equals(set(x)) for x in sets))))


def test_decide_admits_a_cycle_within_the_bound():
    # the cycle 0, 1 is closed and costs 2, as the tree 2, 3, 4 costs 3: the wrapper checks trees
    facts = decide(LOOP, [1], {1: (4, range(5), [2])})
    check(solver(["decide_many"], facts, args=ALL), models(1, atoms(*decided((1, 0), (1, 1)))))


def test_decide_landmark_forces_its_unit():
    facts = decide(ALTERNATIVES, [1], {1: (9, [0, 2, 3], [2])}, "landmark(1,3).\n")
    check(solver(["decide_many"], facts, args=ALL), models(1, atoms(*decided((1, 2), (1, 3)))))


def test_decide_every_level_is_bounded():
    # level 2 weighs unit 0 at 5: only 2, 3 (weight 0 there) fit the bound 1 at level 2
    extra = "weight(2,0,5). weight(2,2,0). weight(2,3,0). budget(1,2,1).\n"
    facts = decide(ALTERNATIVES, [1], {1: (9, [0, 2, 3], [2])}, extra)
    check(solver(["decide_many"], facts, args=ALL), models(1, atoms(*decided((1, 2), (1, 3)))))


def test_decide_hint_units_are_tried_first_and_a_hinted_set_shows_nothing():
    facts = decide(
        ALTERNATIVES, [1], {1: (9, [0, 1, 2, 3], [3]), 2: (9, [0, 1], [1])}, "hint(1,2). hint(1,3). hint(2,1).\n"
    )
    check(solver(["decide_many"], facts, args=DOMAIN), first([]))
    # of the two sets within the bound only the one that is not the hinted tree shows its units
    facts = decide(ALTERNATIVES, [1], {1: (9, [0, 1], [1])}, "hint(1,1).\n")
    check(solver(["decide_many"], facts, args=ALL), models(2, a.Or(a.Equals(set()), a.Equals(set(decided((1, 0)))))))


def test_decide_a_hint_that_is_no_set_within_the_bound_is_left():
    # the hint 2 alone does not make 9: the model holds another set, shown
    facts = decide(ALTERNATIVES, [1], {1: (9, [0, 2], [1])}, "hint(1,2).\n")
    check(solver(["decide_many"], facts, args=DOMAIN), first(decided((1, 0))))


def test_decide_goal_in_the_kitchen_needs_no_unit():
    facts = decide(ALTERNATIVES, [1, 9], {1: (9, [0, 1], [0])})
    check(solver(["decide_many"], facts, args=ALL), models(1, atoms()))


# --- core.lp, through tree.lp and prepared.lp ------------------------------------------------


def front(name: str, units: Units, kitchen, goal, candidates, extra: str = "") -> Clingo:
    """``name`` (tree or prepared) over the FOON, with the units objective."""
    if name == "tree":
        facts = foon(units, kitchen, [goal]) + extra
    else:
        facts = prepared(units, kitchen, goal, candidates, extra)
    return solver(["solve" if name == "tree" else "solve_prepared"], facts, "objective(units,1).\n")


def test_core_through_tree_cycle_is_dearer_but_invalid():
    units = {0: ([5], [4]), 1: ([4], [5]), 2: ([1], [2]), 3: ([2], [3]), 4: ([3], [4])}
    check(front("tree", units, [1], 4, range(5)), optimum(use(2, 3, 4), 3))


def test_core_through_prepared_cycle_is_dearer_but_invalid():
    units = {0: ([5], [4]), 1: ([4], [5]), 2: ([1], [2]), 3: ([2], [3]), 4: ([3], [4])}
    check(front("prepared", units, [1], 4, range(5)), optimum(use(2, 3, 4), 3))


# 3 needs 4 and 5; 4 has two makers (0, 1), 5 one (2)
JOIN = {0: ([1], [4]), 1: ([6], [4]), 2: ([1], [5]), 3: ([4, 5], [9])}


def test_core_through_tree_every_required_input_is_had():
    # 1 would need 6, which nothing makes and the kitchen lacks
    check(front("tree", JOIN, [1], 9, [0, 1, 2, 3]), optimum(use(0, 2, 3), 3))


def test_core_through_prepared_every_required_input_is_had():
    # prepared.lp is told 1 is a candidate; it still cannot fire
    check(front("prepared", JOIN, [1], 9, [0, 1, 2, 3]), optimum(use(0, 2, 3), 3))


def test_core_alone_with_candidates_and_relevant_objects():
    # core.lp reads candidate/1 and relevant/1 as given: only relevant kitchen items are had
    facts = foon(JOIN, [1, 6], [9]) + "candidate(0..3).\nrelevant(1;4;5;9).\n"
    check(solver(["parts/core", "show/tree"], facts, args=ALL), models(1, atoms(*use(0, 2, 3))))


# --- the objectives: units.lp, success.lp, inputs.lp, cost.lp --------------------------------

# 9 by one unit (0) or by the chain 1, 2; neglog, input nodes and motion costs disagree
SCORES = foon({0: ([1], [9]), 1: ([1], [3]), 2: ([3], [9])}, [1], [9]) + (
    "neglog(0,900). neglog(1,100). neglog(2,100).\n"
    "input_nodes(0,5). input_nodes(1,1). input_nodes(2,1).\n"
    "motion_cost(0,100). motion_cost(1,80). motion_cost(2,80).\n"
)


def objectives(*ranked: str) -> str:
    """``objective(Name,P)`` facts, the first most important (as the wrapper writes them)."""
    return "".join(f"objective({o},{len(ranked) - i}).\n" for i, o in enumerate(ranked))


def test_units_fewest_units():
    check(solver(["solve"], SCORES, objectives("units")), optimum(use(0), 1))


def test_success_greatest_product_of_rates():
    check(solver(["solve"], SCORES, objectives("success")), optimum(use(1, 2), 200))


def test_inputs_fewest_input_nodes():
    check(solver(["solve"], SCORES, objectives("inputs")), optimum(use(1, 2), 2))


def test_cost_least_motion_cost():
    check(solver(["solve"], SCORES, objectives("cost")), optimum(use(0), 100))


@pytest.mark.parametrize(
    "ranked, units, cost",
    [
        (("units", "success"), (0,), (1, 900)),
        (("success", "units"), (1, 2), (200, 2)),
        (("cost", "inputs"), (0,), (100, 5)),
        (("inputs", "cost"), (1, 2), (2, 160)),
    ],
    ids=lambda v: ",".join(map(str, v)),
)
def test_lexicographic_objectives(ranked, units, cost):
    """Two objectives: the first listed decides, the second breaks ties."""
    check(solver(["solve"], SCORES, objectives(*ranked)), optimum(use(*units), *cost))


def test_units_tie_broken_by_a_lower_priority():
    # 0 and 1 both make 9 alone; success (priority 1) prefers 1
    facts = foon({0: ([1], [9]), 1: ([1], [9])}, [1], [9]) + "neglog(0,300). neglog(1,100).\n"
    check(solver(["solve"], facts, objectives("units", "success")), optimum(use(1), 1, 100))


def test_units_ties_are_all_optimal():
    facts = foon({0: ([1], [9]), 1: ([1], [9]), 2: ([1], [3]), 3: ([3], [9])}, [1], [9])
    check(solver(["solve"], facts, objectives("units")), optima([use(0), use(1)], 1))


# --- depth.lp --------------------------------------------------------------------------------

# 9 by the chain 0,1,2 (depth 3, 3 units) or by 3,4,5 then 6 (depth 2, 4 units); 10 by 7 (depth 1)
DEPTH_UNITS: Units = {
    0: ([1], [2]),
    1: ([2], [3]),
    2: ([3], [9]),
    3: ([1], [4]),
    4: ([1], [5]),
    5: ([1], [6]),
    6: ([4, 5, 6], [9]),
    7: ([1], [10]),
}
DEPTH_KITCHEN = [1]
DEPTH_LEVELS = Levels(
    set(DEPTH_KITCHEN),
    {u: list(r) for u, (r, _) in DEPTH_UNITS.items()},
    {u: list(p) for u, (_, p) in DEPTH_UNITS.items()},
)


def depth_shots(goals: Sequence[int], ranked: Sequence[str], blocks: Sequence[tuple[int, int]], meal: int = 0, **kw):
    """tree.lp, the objectives, depth.lp and the facts; ``blocks`` (goal, bound) grounded as the
    driver does (the windows from :class:`Levels` in a part of their own, then ``bound(k,g,d)``),
    and with ``meal`` a bound, the block ``meal(1,meal)`` over them."""
    paths, text = program(["solve"], foon(DEPTH_UNITS, DEPTH_KITCHEN, goals), objectives(*ranked))
    grounds: list = [[("base", ())]]
    for k, (goal, bound) in enumerate(blocks, 1):
        windows = "".join(f"window({k},{u},{lo},{hi}).\n" for u, lo, hi in DEPTH_LEVELS.windows(goal, bound))
        text += f"\n#program depth_windows_{k}.\n{windows}"
        grounds.append([(f"depth_windows_{k}", ()), ("bound", (k, goal, bound))])
    if meal:
        text += "\n#program depth_meal_1.\n" + "".join(f"member(1,{k}).\n" for k in range(1, len(blocks) + 1))
        grounds.append([("depth_meal_1", ()), ("meal", (1, meal))])
    return Shots(OPT, (paths, text), grounds, **kw)


def test_depth_windows_are_the_drivers():
    # the windows the blocks below are grounded with (first round, last useful round)
    assert DEPTH_LEVELS.windows(9, 3) == [(0, 1, 1), (1, 2, 2), (2, 3, 3), (3, 1, 2), (4, 1, 2), (5, 1, 2), (6, 2, 3)]


def test_depth_first_the_shallow_tree():
    shots = depth_shots([9], ["depth", "units"], [(9, 3)], externals=["query(1)", "within(1)"])
    check(shots, optimum(use(3, 4, 5, 6), 2, 4))


def test_depth_after_units_the_chain():
    shots = depth_shots([9], ["units", "depth"], [(9, 3)], externals=["query(1)", "within(1)"])
    check(shots, optimum(use(0, 1, 2), 3, 3))


def test_depth_bound_two_leaves_the_wide_tree_only():
    shots = depth_shots([9], ["units"], [(9, 2)], externals=["query(1)"])
    check(shots, optimum(use(3, 4, 5, 6), 4))


def test_depth_bound_one_has_no_tree():
    check(depth_shots([9], ["units"], [(9, 1)], externals=["query(1)"]), unsat())


def test_depth_bound_off_leaves_the_chain():
    # the block is grounded but query(1) is off: the bound does not hold
    check(depth_shots([9], ["units"], [(9, 1)]), optimum(use(0, 1, 2), 3))


def test_depth_goal_in_the_kitchen_is_depth_zero():
    # 1 is in the kitchen: reached after 0 rounds, so no round costs (and no level has a literal)
    shots = depth_shots([1], ["depth", "units"], [(1, 2)], externals=["query(1)", "within(1)"])
    check(shots, models(1, a.And(atoms(), Cost())))


def test_depth_meal_is_its_deepest_goal():
    shots = depth_shots(
        [9, 10], ["depth", "units"], [(9, 2), (10, 2)], meal=2, externals=["meal_query(1)", "meal_within(1)"]
    )
    check(shots, optimum(use(3, 4, 5, 6, 7), 2, 5))


def test_depth_meal_bound_below_a_goal_has_no_tree():
    shots = depth_shots([9, 10], ["units"], [(9, 1), (10, 1)], meal=1, externals=["meal_query(1)"])
    check(shots, unsat())


# --- canonical.lp ----------------------------------------------------------------------------

# 0, 1 and 2 each make 9 from the kitchen; the chain of unit ids for canonical.lp
TRIO = foon({0: ([1], [9]), 1: ([1], [9]), 2: ([1], [9])}, [1], [9]) + "lex_first(0).\nlex_next(0,1).\nlex_next(1,2).\n"


def canonical(externals: Sequence[str], args=ALL, extra: str = "") -> Shots:
    return Shots(args, program(["solve"], TRIO, extra), externals=externals)


def test_canonical_off_keeps_every_tree():
    check(canonical(["lex_cur(1)"]), models(7))


def test_canonical_on_only_smaller_trees():
    # smaller than {1}: every tree with 0, and {1,2} (first difference 2, which it holds)
    smaller = [use(0), use(0, 1), use(0, 2), use(0, 1, 2), use(1, 2)]
    each = a.Or(*(a.Equals(set(s)) for s in smaller))
    check(canonical(["lex_on", "lex_cur(1)"]), models(5, each))


def test_canonical_on_optimal_smaller_trees():
    facts = "objective(units,1).\n"
    shots = canonical(["lex_on", "lex_cur(2)"], OPT, facts)
    check(shots, optima([use(0), use(1)], 1))


def test_canonical_smallest_optimal_tree_has_no_smaller_optimal_one():
    # {0} is the canonical optimum: the smaller trees all cost more
    facts = "objective(units,1).\n"
    shots = canonical(["lex_on", "lex_cur(0)"], OPT, facts)
    check(shots, optima([use(0, 1), use(0, 2)], 2))


def test_canonical_on_with_the_full_tree_current():
    # {0,1,2} holds every unit: nothing differs first in a unit it lacks
    check(canonical(["lex_on", "lex_cur(0)", "lex_cur(1)", "lex_cur(2)"]), unsat())


# --- greedy.lp, greedy_h1.lp, greedy_h2.lp ---------------------------------------------------

# 9 by 0, 1 or 2 from the kitchen, or by 3 from 5; 5 by 4 or 5; 6 needs 7, which nothing makes
GREEDY = foon(
    {0: ([1], [9]), 1: ([1], [9]), 2: ([1], [9]), 3: ([5], [9]), 4: ([1], [5]), 5: ([1], [5]), 6: ([7], [9])},
    [1],
    [9],
)


def test_greedy_one_producer_per_needed_object():
    # tree.lp alone has many more trees; greedy picks one maker of 9, and of 5 if 3 is picked
    trees = [use(0), use(1), use(2), use(3, 4), use(3, 5)]
    check(solver(["solve_greedy"], GREEDY, args=ALL), models(5, a.Or(*(a.Equals(set(s)) for s in trees))))


def test_greedy_every_picked_unit_is_used():
    # 0 needs 5 and 6; 2 makes both, 1 makes 5: picking 1 for 5 puts 1 in the tree
    facts = foon({0: ([5, 6], [9]), 1: ([1], [5]), 2: ([1], [6, 5])}, [1], [9])
    trees = [use(0, 2), use(0, 1, 2)]
    check(
        solver(["solve_greedy"], facts, args=ALL),
        t.And(models(2, a.Or(*(a.Equals(set(s)) for s in trees))), *(t.Assert(q.Any(), atoms(*s)) for s in trees)),
    )


@pytest.mark.parametrize(
    "heuristic, ranks, chosen",
    [
        # h1 ranks by success rate: 2 is the likeliest maker of 9
        (
            "greedy_h1",
            "rank(9,2,0). rank(9,0,1). rank(9,1,2). rank(9,3,3). rank(9,6,4). rank(5,4,0). rank(5,5,1).",
            (2,),
        ),
        # rank 0 for every needed object
        (
            "greedy_h1",
            "rank(9,3,0). rank(9,0,1). rank(9,1,2). rank(9,2,3). rank(9,6,4). rank(5,5,0). rank(5,4,1).",
            (3, 5),
        ),
        # 6 is ranked first but needs 7; the next rank is taken
        (
            "greedy_h1",
            "rank(9,6,0). rank(9,1,1). rank(9,0,2). rank(9,2,3). rank(9,3,4). rank(5,4,0). rank(5,5,1).",
            (1,),
        ),
        # h2 ranks by input nodes: ties to file order, 0 first
        (
            "greedy_h2",
            "rank(9,0,0). rank(9,1,1). rank(9,2,2). rank(9,3,3). rank(9,6,4). rank(5,4,0). rank(5,5,1).",
            (0,),
        ),
        # rank 0 for every needed object
        (
            "greedy_h2",
            "rank(9,3,0). rank(9,2,1). rank(9,1,2). rank(9,0,3). rank(9,6,4). rank(5,4,0). rank(5,5,1).",
            (3, 4),
        ),
    ],
)
def test_greedy_first_model_takes_rank_zero(heuristic, ranks, chosen):
    check(solver(["solve_greedy"], GREEDY, ranks + "\n", args=DOMAIN), first(use(*chosen)))


# --- missing.lp ------------------------------------------------------------------------------


def missing(units: Units, ranked=("units",), extra: str = "", args=OPT) -> Clingo:
    facts = foon(units, [1], [9]) + objectives(*ranked) + f"add_priority({len(ranked) + 1}).\n" + extra
    return solver(["find_missing"], facts, args=args)


def test_missing_fewest_added_objects():
    # 0 needs 2 and 3, 1 needs 4; nothing makes them
    units = {0: ([1, 2, 3], [9]), 1: ([1, 4], [9])}
    check(missing(units), optimum(["add(4)", *use(1)], 1, 1))


def test_missing_nothing_added_when_the_goal_can_be_made():
    units = {0: ([1, 2, 3], [9]), 1: ([1, 4], [9]), 2: ([1], [4])}
    check(missing(units), optimum(use(1, 2), 0, 2))


def test_missing_buys_into_a_cycle():
    # 9 from 5, 5 only from 9: 5 is bought
    check(missing({0: ([5], [9]), 1: ([9], [5])}), optimum(["add(5)", *use(0)], 1, 1))


def test_missing_never_adds_the_goal():
    check(missing({0: ([1], [2])}), unsat())


def test_missing_every_used_unit_fires():
    # 2 makes 9 from the kitchen; 0 (5 -> 9) and 1 (9 -> 5) ride on it, never on each other
    trees = [use(2), use(1, 2), use(0, 1, 2)]
    each = a.Or(*(a.Equals(set(s)) for s in trees))
    check(missing({0: ([5], [9]), 1: ([9], [5]), 2: ([1], [9])}, (), args=ALL), models(3, each))


def test_missing_ties_go_to_the_tree_objective():
    # one object either way; success prefers the chain 1, 2
    units = {0: ([1, 2], [9]), 1: ([1, 3], [5]), 2: ([5], [9])}
    weights = "neglog(0,900). neglog(1,10). neglog(2,10).\n"
    check(missing(units, ("success",), weights), optimum(["add(3)", *use(1, 2)], 1, 20))


# --- dominance.lp ----------------------------------------------------------------------------


def test_dominance_dominated_unit_never_used():
    facts = foon({0: ([1], [9]), 1: ([1], [9])}, [1], [9]) + "dom(0,1).\n"
    check(solver(["solve"], facts, args=ALL), models(1, atoms(*use(0))))


def test_dominance_extra_product_not_relevant():
    # 1 also makes 5, which nothing needs: still dominated
    facts = foon({0: ([1], [9]), 1: ([1], [9, 5])}, [1], [9]) + "dom(0,1).\ndom_extra(0,1,5).\n"
    check(solver(["solve"], facts, args=ALL), models(1, atoms(*use(0))))


def test_dominance_extra_product_relevant():
    # 3 needs 9 and 5; 1 makes both, so it is allowed and the optimum uses it
    units = {0: ([1], [9]), 1: ([1], [9, 5]), 2: ([1], [5]), 3: ([9, 5], [10])}
    facts = foon(units, [1], [10]) + "dom(0,1).\ndom_extra(0,1,5).\n" + objectives("units")
    check(solver(["solve"], facts), optimum(use(1, 3), 2))


# --- reachable.lp ----------------------------------------------------------------------------


def test_reachable_asked_objects():
    # 3 via 2; 4 and 5 only make each other; 7 needs 6, which nothing makes
    units = {0: ([1], [2]), 1: ([2], [3]), 2: ([4], [5]), 3: ([5], [4]), 4: ([6], [7])}
    facts = foon(units, [1]) + "asked(1;3;5;7).\n"
    shown = ["reachable(1)", "reachable(3)", "unreachable(5)", "unreachable(7)"]
    check(solver(["find_reachable"], facts, args=ALL), models(1, atoms(*shown)))


def test_reachable_unasked_objects_are_not_reported():
    facts = foon({0: ([1], [2])}, [1]) + "asked(2).\n"
    check(solver(["find_reachable"], facts, args=ALL), models(1, atoms("reachable(2)")))


# --- substitutes.lp --------------------------------------------------------------------------

# 0 makes 9 from the kitchen item 1 and 5; the kitchen item numbered 0 may stand in for 5
NEEDS_FIVE = {0: ([1, 5], [9])}


def substitutes(units: Units, extra: str, ranked=("units",), args=OPT) -> Clingo:
    facts = foon(units, [1], [9]) + objectives(*ranked) + extra
    return solver(["solve"], facts, args=args)


def test_substitutes_stand_in_for_a_missing_object():
    check(substitutes(NEEDS_FIVE, "substitute(5,0,1).\n"), optimum(["subst(5,0)", *use(0)], 1, 1))


def test_substitutes_rank_above_the_objectives():
    # 1 makes 5: a second unit beats a substitution
    units = {**NEEDS_FIVE, 1: ([1], [5])}
    check(substitutes(units, "substitute(5,0,1).\n"), optimum(use(0, 1), 0, 2))


def test_substitutes_the_cheapest_stands_in():
    check(substitutes(NEEDS_FIVE, "substitute(5,0,3).\nsubstitute(5,1,1).\n"), optimum(["subst(5,1)", *use(0)], 1, 1))


def test_substitutes_bounded_in_number():
    # 0 needs two substitutions, 1 one; at most one is allowed
    units = {0: ([1, 5, 6], [9]), 1: ([6, 7], [9]), 2: ([1], [7])}
    extra = "substitute(5,0,1).\nsubstitute(6,1,1).\nmax_substitutions(1).\n"
    check(substitutes(units, extra), optimum(["subst(6,1)", *use(1, 2)], 1, 2))


def test_substitutes_only_for_an_input_a_used_unit_requires():
    # 5 is relevant through 0; without 0 in the tree nothing stands in for it
    units = {0: ([1, 5], [9]), 2: ([1], [9])}
    each = a.Implies(a.Contains("subst(5,0)"), a.Contains("use(0)"))
    check(substitutes(units, "substitute(5,0,1).\n", (), ALL), models(3, each))


def test_substitutes_one_per_object():
    extra = "substitute(5,0,1).\nsubstitute(5,1,1).\n"
    each = a.Or(atoms("subst(5,0)", *use(0)), atoms("subst(5,1)", *use(0)))
    check(substitutes(NEEDS_FIVE, extra, (), ALL), models(2, each))


def test_substitutes_bound_leaves_no_tree():
    extra = "substitute(5,0,1).\nsubstitute(6,1,1).\nmax_substitutions(1).\n"
    check(substitutes({0: ([1, 5, 6], [9])}, extra), unsat())


def test_substitutes_never_for_the_goal():
    check(substitutes({0: ([5], [9])}, "substitute(9,0,1).\n"), unsat())


# --- human.lp --------------------------------------------------------------------------------

# 9 by the chain 0 (900), 1 (10), 2 (10) or by 3 (450), 4 (450); human_unit: heaviest first
HUMAN = (
    foon({0: ([1], [2]), 1: ([2], [3]), 2: ([3], [9]), 3: ([1], [4]), 4: ([4], [9])}, [1], [9])
    + "neglog(0,900). neglog(1,10). neglog(2,10). neglog(3,450). neglog(4,450).\n"
    + "human_unit(1,0). human_unit(2,3). human_unit(3,4). human_unit(4,1). human_unit(5,2).\n"
    + objectives("success", "units")
)


def human(limit: int | None) -> Clingo:
    return solver(["solve"], HUMAN, "" if limit is None else f"human_limit({limit}).\n")


def test_human_without_human_steps():
    check(human(None), optimum(use(3, 4), 900, 2))


def test_human_one_step_takes_the_least_likely_unit():
    check(human(1), optimum(["human(0)", *use(0, 1, 2)], 20, 3, 1))


def test_human_two_steps_change_the_tree():
    check(human(2), optimum(["human(3)", "human(4)", *use(3, 4)], 0, 2, 2))


def test_human_at_most_the_limit():
    # the chain alone: the two least likely of its three units are done by a person
    chain = foon({0: ([1], [2]), 1: ([2], [3]), 2: ([3], [9])}, [1], [9])
    facts = chain + "neglog(0,900). neglog(1,10). neglog(2,10).\n"
    # positions 1, 2, 3 without a gap, as the wrapper numbers the units of the facts
    facts += "human_unit(1,0). human_unit(2,1). human_unit(3,2).\nhuman_limit(2).\n" + objectives("success", "units")
    check(solver(["solve"], facts), optimum(["human(0)", "human(1)", *use(0, 1, 2)], 10, 3, 2))


def test_human_limit_zero_is_no_human_step():
    check(human(0), optimum(use(3, 4), 900, 2))


# --- schedule_steps.lp -----------------------------------------------------------------------

ROBOT = 'kind("robot",1).\n'
PRIORITIES = "priority(makespan,2).\npriority(human,1).\n"


#: the time-step encoding and the order encoding of the same facts (fixed trees, no durations 0)
BOTH = [("schedule_steps",), ("schedule_order",)]


def steps(facts: str, horizon: int, names=("schedule_steps",)) -> Clingo:
    return solver(list(names), facts, f"horizon({horizon}).\nfloor(0).\n", PRIORITIES)


@pytest.mark.parametrize("names", BOTH)
def test_schedule_steps_a_maker_first(names):
    facts = ROBOT + 'use(0;1).\ncan(0,"robot",2).\ncan(1,"robot",1).\nwindow(0,0,3).\nwindow(1,0,3).\n'
    facts += "need(1,5).\nmaker(0,5).\n"
    shown = ['on(0,"robot")', 'on(1,"robot")', "start(0,0)", "start(1,2)"]
    check(steps(facts, 4, names), optimum(shown, 3))


@pytest.mark.parametrize("names", BOTH)
def test_schedule_steps_a_person_only_when_it_is_shorter(names):
    facts = ROBOT + 'kind("human",1).\nhuman_kind("human").\nuse(0;1).\n'
    facts += 'can(0,"robot",2).\ncan(1,"robot",2).\ncan(1,"human",3).\nwindow(0,0,4).\nwindow(1,0,4).\n'
    # the robot's unit may start at 0 or 1 within the person's 3 steps
    schedules = [['on(0,"robot")', 'on(1,"human")', f"start(0,{s})", "start(1,0)"] for s in (0, 1)]
    check(steps(facts, 6, names), optima(schedules, 3, 1))


@pytest.mark.parametrize("names", BOTH)
def test_schedule_steps_resource_capacity(names):
    facts = 'kind("robot",2).\nuse(0;1).\ncan(0,"robot",2).\ncan(1,"robot",2).\nwindow(0,0,4).\nwindow(1,0,4).\n'
    facts += 'uses(0,"pan").\nuses(1,"pan").\ncapacity("pan",1).\n'
    orders = [
        ['on(0,"robot")', 'on(1,"robot")', "start(0,0)", "start(1,2)"],
        ['on(0,"robot")', 'on(1,"robot")', "start(0,2)", "start(1,0)"],
    ]
    check(steps(facts, 6, names), optima(orders, 4))


def test_schedule_steps_zero_durations_follow_their_makers():
    facts = ROBOT + 'zeros.\nuse(0;1).\ncan(0,"robot",0).\ncan(1,"robot",1).\nwindow(0,0,2).\nwindow(1,0,2).\n'
    facts += "need(1,5).\nmaker(0,5).\n"
    shown = ['on(0,"robot")', 'on(1,"robot")', "start(0,0)", "start(1,0)"]
    check(steps(facts, 3), optimum(shown, 1))


def test_schedule_steps_zero_durations_no_cycle():
    # 0 and 1 each need what the other makes, both at once: not well-founded
    facts = ROBOT + 'zeros.\nuse(0;1).\ncan(0,"robot",0).\ncan(1,"robot",0).\nwindow(0,0,2).\nwindow(1,0,2).\n'
    facts += "need(0,6).\nmaker(1,6).\nneed(1,5).\nmaker(0,5).\n"
    check(steps(facts, 3), unsat())


def test_schedule_steps_every_unit_ends_by_the_horizon():
    # the window allows starts 0..3, the horizon 3 only starts 0 and 1 for 2 steps
    facts = ROBOT + 'use(0).\ncan(0,"robot",2).\nwindow(0,0,3).\nhorizon(3).\n'
    each = a.Or(*(atoms('on(0,"robot")', f"start(0,{s})") for s in (0, 1)))
    check(solver(["schedule_steps"], facts, args=ALL), models(2, each))


@pytest.mark.parametrize("names", BOTH)
def test_schedule_steps_one_agent_one_unit_at_a_time(names):
    # 0 and 1 must start at 0, 2 at 2: the work fits 3 steps, but 0 and 1 overlap on one robot
    facts = ROBOT + "use(0;1;2).\n" + "".join(f'can({u},"robot",1).\n' for u in range(3))
    facts += "window(0,0,0).\nwindow(1,0,0).\nwindow(2,2,2).\n"
    check(steps(facts, 3, names), unsat())


# --- schedule_order.lp: the same facts, each start a chain of "starts by step T" atoms -------
# (the cases marked BOTH above run on it too)


def test_schedule_order_tail_rules_out_a_late_start():
    # unit 0 and what waits for it take 3 steps (tail): within 4 steps it starts at 0 or 1
    facts = ROBOT + 'use(0).\ncan(0,"robot",1).\nwindow(0,0,3).\ntail(0,3).\n'
    each = a.Or(*(atoms('on(0,"robot")', f"start(0,{s})") for s in (0, 1)))
    check(solver(["schedule_order"], facts, "horizon(4).\n", args=ALL), models(2, each))


def test_schedule_steps_floor():
    # one step of work, but no schedule counts less than the floor of 3
    facts = ROBOT + 'use(0).\ncan(0,"robot",1).\nwindow(0,0,3).\nfloor(3).\n'
    starts = [['on(0,"robot")', f"start(0,{s})"] for s in (0, 1, 2)]
    check(solver(["schedule_steps"], facts, "horizon(4).\n", PRIORITIES), optima(starts, 3))


def test_schedule_steps_joint_with_tree():
    # tree.lp chooses: 0 alone takes 3 steps, the chain 1, 2 takes 2
    facts = foon({0: ([1], [9]), 1: ([1], [3]), 2: ([3], [9])}, [1], [9])
    facts += ROBOT + 'can(0,"robot",3).\ncan(1,"robot",1).\ncan(2,"robot",1).\n'
    facts += "window(0,0,3).\nwindow(1,0,3).\nwindow(2,0,3).\nneed(2,3).\nmaker(1,3).\n"
    facts += "priority(makespan,3).\npriority(human,2).\nobjective(units,1).\n"
    shown = [*use(1, 2), 'on(1,"robot")', 'on(2,"robot")', "start(1,0)", "start(2,1)"]
    # no human kind: the human level has no literal and is left out of the cost
    check(solver(["schedule_steps", "joint_tree"], facts, "horizon(4).\nfloor(0).\n"), optimum(shown, 2, 2))


# --- schedule_dl.lp (clingo-dl) --------------------------------------------------------------


def dl(facts: str, bound: int, args=OPT) -> Shots:
    """schedule_dl.lp with clingo-dl, its part bound(b) grounded and switched on."""
    grounds = [[("base", ())], [("bound", (bound,))]]
    return Shots(args, program(["schedule_dl"], facts), grounds, [f"bounded({bound})"], ClingoDLTheory)


DL_SEQUENCE = (
    ROBOT
    + 'agent("robot",1).\nuse(0;1).\ncan(0,"robot",2).\ncan(1,"robot",1).\nwindow(0,0,0).\nwindow(1,0,0).\n'
    + "need(1,5).\nmaker(0,5).\n"
)


def test_schedule_dl_a_maker_first():
    shown = ['on(0,"robot",1)', 'on(1,"robot",1)', "dl(s(0),0)", "dl(s(1),2)", "dl(mk,3)"]
    check(dl(DL_SEQUENCE, 3), models(1, atoms(*shown)))


def test_schedule_dl_bound_below_the_makespan():
    check(dl(DL_SEQUENCE, 2), unsat())


def test_schedule_dl_two_agents_in_parallel():
    facts = 'kind("robot",2).\nagent("robot",1).\nagent("robot",2).\nuse(0;1).\n'
    facts += 'can(0,"robot",2).\ncan(1,"robot",2).\nwindow(0,0,0).\nwindow(1,0,0).\n'
    # symmetry: agent 2 takes 1 only after agent 1 took 0
    shown = ['on(0,"robot",1)', 'on(1,"robot",2)', "dl(s(0),0)", "dl(s(1),0)", "dl(mk,2)"]
    check(dl(facts, 2), models(1, atoms(*shown)))


DL_PERSON = (
    ROBOT
    + 'agent("robot",1).\nkind("human",1).\nagent("human",1).\nhuman_kind("human").\npriority(human,1).\n'
    + 'use(0;1).\ncan(0,"robot",2).\ncan(1,"robot",2).\ncan(1,"human",2).\nwindow(0,0,0).\nwindow(1,0,0).\n'
)


def test_schedule_dl_no_person_when_the_robot_has_time():
    each = a.And(a.Contains('on(0,"robot",1)'), a.Contains('on(1,"robot",1)'), a.Contains("dl(mk,4)"), Cost(0))
    check(
        dl(DL_PERSON, 4),
        t.And(t.Assert(q.GreaterEqual(1), a.Optimal()), t.Assert(q.All(), a.Implies(a.Optimal(), each))),
    )


def test_schedule_dl_a_person_within_a_tight_bound():
    shown = ['on(0,"robot",1)', 'on(1,"human",1)', "dl(s(0),0)", "dl(s(1),0)", "dl(mk,2)"]
    check(dl(DL_PERSON, 2), optimum(shown, 1))


def test_schedule_dl_window_start():
    facts = ROBOT + 'agent("robot",1).\nuse(0).\ncan(0,"robot",1).\nwindow(0,3,3).\n'
    check(dl(facts, 4, ALL), models(1, atoms('on(0,"robot",1)', "dl(s(0),3)", "dl(mk,4)")))


def test_schedule_dl_window_later_than_the_bound():
    facts = ROBOT + 'agent("robot",1).\nuse(0).\ncan(0,"robot",1).\nwindow(0,3,3).\n'
    check(dl(facts, 3, ALL), unsat())


def test_schedule_dl_makespan_bound_beyond_the_work():
    # two robots: the work fits 2 per robot, but 1 waits for what 0 makes
    facts = 'kind("robot",2).\nagent("robot",1).\nagent("robot",2).\nuse(0;1).\n'
    facts += 'can(0,"robot",2).\ncan(1,"robot",1).\nwindow(0,0,0).\nwindow(1,0,0).\nneed(1,5).\nmaker(0,5).\n'
    check(dl(facts, 2, ALL), unsat())


def test_schedule_dl_tail_bound():
    # 0 and what must follow it take 3, more than the bound 2
    facts = ROBOT + 'agent("robot",1).\nuse(0).\ncan(0,"robot",1).\nwindow(0,0,0).\ntail(0,3).\n'
    check(dl(facts, 2, ALL), unsat())


def test_schedule_dl_zero_durations_follow_their_makers():
    facts = ROBOT + 'agent("robot",1).\nzeros.\nuse(0;1).\ncan(0,"robot",0).\ncan(1,"robot",1).\n'
    facts += "window(0,0,0).\nwindow(1,0,0).\nneed(1,5).\nmaker(0,5).\n"
    shown = ['on(0,"robot",1)', 'on(1,"robot",1)', "dl(s(0),0)", "dl(s(1),0)", "dl(mk,1)"]
    check(dl(facts, 1, ALL), models(1, atoms(*shown)))


def test_schedule_dl_zero_durations_no_cycle():
    facts = ROBOT + 'agent("robot",1).\nzeros.\nuse(0;1).\ncan(0,"robot",0).\ncan(1,"robot",0).\n'
    facts += "window(0,0,0).\nwindow(1,0,0).\nneed(0,6).\nmaker(1,6).\nneed(1,5).\nmaker(0,5).\n"
    check(dl(facts, 1, ALL), unsat())


def test_schedule_dl_one_lane_no_overlap():
    facts = 'kind("robot",2).\nagent("robot",1).\nagent("robot",2).\nuse(0;1).\n'
    facts += 'can(0,"robot",2).\ncan(1,"robot",2).\nwindow(0,0,0).\nwindow(1,0,0).\n'
    facts += 'uses(0,"pan").\nuses(1,"pan").\ncapacity("pan",1).\n'
    one = a.And(a.Contains("dl(s(0),0)"), a.Contains("dl(s(1),2)"))
    other = a.And(a.Contains("dl(s(0),2)"), a.Contains("dl(s(1),0)"))
    # unit 1 on either robot, either order
    check(dl(facts, 4, ALL), models(4, a.Or(one, other)))


def test_schedule_dl_lanes_taken_in_order():
    # capacity 2 within bound 2: 0 in lane 1 and 1 in lane 2, one answer (no mirrored lanes)
    facts = 'kind("robot",2).\nagent("robot",1).\nagent("robot",2).\nuse(0;1).\n'
    facts += 'can(0,"robot",2).\ncan(1,"robot",2).\nwindow(0,0,0).\nwindow(1,0,0).\n'
    facts += 'uses(0,"pan").\nuses(1,"pan").\ncapacity("pan",2).\n'
    check(
        dl(facts, 2, ALL),
        models(1, atoms('on(0,"robot",1)', 'on(1,"robot",2)', "dl(s(0),0)", "dl(s(1),0)", "dl(mk,2)")),
    )


def test_schedule_dl_resource_lanes():
    facts = 'kind("robot",2).\nagent("robot",1).\nagent("robot",2).\nuse(0;1).\n'
    facts += 'can(0,"robot",2).\ncan(1,"robot",2).\nwindow(0,0,0).\nwindow(1,0,0).\n'
    facts += 'uses(0,"pan").\nuses(1,"pan").\ncapacity("pan",1).\n'
    check(dl(facts, 3, ALL), unsat())


# --- schedule_trees.lp -----------------------------------------------------------------------

# 9 by 0 alone or by the chain 1, 2
TREES = foon({0: ([1], [9]), 1: ([1], [3]), 2: ([3], [9])}, [1], [9])


def trees(extra: str = "", args=ALL) -> Clingo:
    return solver(["joint_tree", "list_trees"], TREES, extra, args=args)


def test_schedule_trees_every_unit_needed():
    # tree.lp alone also has {0,1}: 1 makes what no used unit needs
    each = a.Or(*(a.Equals(set(s)) for s in (use(0), use(1, 2), use(0, 1, 2))))
    check(trees(), models(3, each))


def test_schedule_trees_work_fits_the_agents():
    check(trees("work(0,5). work(1,1). work(2,1).\ncapacity(3).\n"), models(1, atoms(*use(1, 2))))


def test_schedule_trees_too_late_unit_never_used():
    check(trees("too_late(1).\n"), models(1, atoms(*use(0))))


def first_trees(extra: str = "", args=ALL) -> Clingo:
    return solver(["joint_tree", "list_designations"], TREES, extra, args=args)


def test_schedule_first_one_maker_per_needed_object():
    # {0,1,2} makes 9 twice: whichever makes it first, the other is not needed
    each = a.Or(*(a.Equals(set(s)) for s in (use(0), use(1, 2))))
    check(first_trees(), models(2, each))


def test_schedule_first_designates_the_goal_maker():
    check(first_trees(":- not first(9,2).\n"), models(1, atoms(*use(1, 2))))


# 0 and 5 make a, d and b, e from the kitchen; 1 makes b from a, 2 makes a from b; 3 makes 9
CROSS = foon({0: ([1], [4, 6]), 5: ([1], [5, 7]), 1: ([4], [5]), 2: ([5], [4]), 3: ([4, 5, 6, 7], [9])}, [1], [9])


def test_schedule_first_never_designates_in_a_circle():
    # with 1 and 2 both used, 2 must first make 4 (=a) and 1 first make 5 (=b): each waits for the other
    cross = solver(["joint_tree", "list_designations"], CROSS, ":- not use(1).\n:- not use(2).\n", args=ALL)
    check(cross, unsat())


def test_schedule_first_designates_one_of_the_crossing_makers():
    # 1 alone beside 0 and 5: it may first make 5 (=b) from 4 (=a), which 0 makes first
    one = solver(["joint_tree", "list_designations"], CROSS, ":- not use(1).\n:- use(2).\n", args=ALL)
    check(one, models(1, a.And(a.Equals(set(use(0, 1, 3, 5))), a.Contains("first(5,1)"))))


def test_schedule_trees_answers_are_distinct_trees():
    # a choice beside the tree doubles the answers; the projection on use/1 keeps one per tree
    check(trees("{ aside }.\n", ["0", "--project=project", "--warn=none"]), models(3))
