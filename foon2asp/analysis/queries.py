"""Declarative queries over a FOON: reachability, missing items, user programs."""

from __future__ import annotations

import time
from collections.abc import Iterable

import clingo
import clingo.ast

from foon2asp.asp import encoding_files
from foon2asp.asp.constraints import check_syntax
from foon2asp.asp.control import Control
from foon2asp.asp.facts import facts
from foon2asp.asp.objectives import input_node_facts, objective_facts
from foon2asp.asp.options import OBJECTIVES, AspOptions, solver_args
from foon2asp.asp.predicates import (
    known_predicates,
    predicates,
    shipped_predicates,
    signature_text,
    undefined,
)
from foon2asp.errors import InputError, escape
from foon2asp.foon.problem import Problem
from foon2asp.methods.runner import solve_goals
from foon2asp.outcomes import MissingResult, QueryResult, ShownModel
from foon2asp.tree.tasktree import Goals, executable_order, meal_of, measures
from foon2asp.tree.weights import unit_weight


class Program:
    """One :class:`~foon2asp.asp.control.Control`: add named parts, ground once, solve once."""

    def __init__(self, parts: Iterable[tuple[str, str]], args: Iterable[str] = (), files: Iterable[str] = ()) -> None:
        """``parts``: named programs, the facts first; ``files``: encoding files loaded after the facts."""
        self.control = Control(list(args))
        parts = list(parts)
        self.control.add_all(parts[:1], user=[name for name, _ in parts[:1] if name != "facts"])
        for path in files:
            self.control.load(path)
        self.control.add_all(parts[1:], user=[name for name, _ in parts[1:] if name != "facts"])
        self.control.ground()

    def solve(self, time_limit: float | None = None, limit: int = 1) -> QueryResult:
        """Solve: when optimising keep the best model, else stop after ``limit`` models (0 = all).
        The status is optimal, satisfiable (no objective), feasible (stopped early), unsatisfiable
        or unknown.  The control must run with ``--models=0``."""
        answers: list[ShownModel] = []

        def on_model(model: clingo.Model) -> bool:
            answer = ShownModel(tuple(model.cost), model.optimality_proven, list(model.symbols(shown=True)))
            if answer.cost:
                answers[:] = [answer]
                return True
            answers.append(answer)
            return not (limit and len(answers) >= limit)

        result = self.control.solve(on_model, time_limit or None)
        if not answers:
            status = "unsatisfiable" if result.unsatisfiable and result.finished else "unknown"
        elif any(a.cost for a in answers):
            done = (result.exhausted and not result.interrupted and result.finished) or answers[-1].proven
            status = "optimal" if done else "feasible"
        else:
            status = "satisfiable"
        return QueryResult(status, answers, round(result.time_s, 6))


def reachable(problem: Problem, objects: Iterable[int]) -> dict[int, bool]:
    """For each object id: can it be made from the kitchen?  One grounding, one solve."""
    objects = list(dict.fromkeys(objects))
    asked = "".join(f"asked({o}).\n" for o in objects)
    prog = Program(
        [("facts", facts(problem)), ("asked", asked)], ["--models=0"], [encoding_files.entry("find_reachable")]
    )
    outcome = prog.solve()
    if not outcome.answers:  # pragma: no cover - the program is stratified, always one model
        raise RuntimeError("reachability program has no model")
    yes = {s.arguments[0].number for s in outcome.answers[-1].symbols if s.name == "reachable"}
    return {o: o in yes for o in objects}


#: the tree objectives ``missing`` can use after the fewest added objects
MISSING_OBJECTIVES = ("units", "success", "inputs", "cost")


def objective_parts(
    problem: Problem, objective: tuple[str, ...], units: list[int], first: int
) -> list[tuple[str, str]]:
    """The ``objective(Name,P)`` facts, the facts the objectives read and ``add_priority(first)``."""
    parts = [("objectives", objective_facts(objective))]
    if "inputs" in objective:
        parts.append(("input_nodes", input_node_facts(problem, units)))
    if "cost" in objective:
        weight = unit_weight(problem, "cost")
        parts.append(("motion costs", "".join(f"motion_cost({u},{weight(u)}).\n" for u in units)))
    parts.append(("add_priority", f"add_priority({first}).\n"))
    return parts


def missing(problem: Problem, goal: Goals, options: AspOptions | None = None) -> MissingResult:
    """The fewest objects to add to the kitchen so ``goal`` (a meal: a tuple) can be made, then
    the best tree by ``options.objective`` (any of :data:`MISSING_OBJECTIVES`).  A goal that can
    be made as the kitchen is gets the tree ``solve`` gives."""
    options = options or AspOptions()
    objective = tuple(dict.fromkeys(options.objective))
    for name in objective:
        if name not in MISSING_OBJECTIVES:
            raise InputError(f"missing takes the objectives {', '.join(MISSING_OBJECTIVES)}, not {name!r}")
    meal = meal_of(goal)
    t0 = time.perf_counter()
    units = sorted({u for g in meal if g not in problem.kitchen for u in problem.relevant_units(g)})
    text = facts(problem, goal=meal[0], units=units) + "".join(f"goal({g}).\n" for g in meal[1:])
    prog = Program(
        [("facts", text), *objective_parts(problem, objective, units, len(objective) + 1), *options.programs],
        ["--opt-mode=opt", "--models=0", *solver_args(options.opt_strategy, options.threads)],
        [encoding_files.entry("find_missing")],
    )
    buyable = sorted(s.arguments[0].number for s in prog.control.facts_of("buyable", 1))
    goals = meal if len(meal) > 1 else ()
    result = MissingResult(meal[0], "unreachable", buyable=buyable, goals=goals)
    if all(g in problem.derivable for g in meal):
        (tree,) = solve_goals(problem, [goal], "asp", options)
        if tree.status in ("optimal", "feasible"):
            result.status, result.units, result.cost = tree.status, list(tree.units), dict(tree.cost, added=0)
            result.time_s = round(time.perf_counter() - t0, 6)
            return result
    left = None
    if options.time_limit:
        left = max(options.time_limit - (time.perf_counter() - t0), 0.001)
    outcome = prog.solve(left)
    result.time_s = round(time.perf_counter() - t0, 6)
    if outcome.answers:
        shown = outcome.answers[-1].symbols
        result.missing = sorted(s.arguments[0].number for s in shown if s.name == "add")
        extended = problem.with_kitchen(problem.kitchen.union(result.missing))
        result.units = executable_order(extended, [s.arguments[0].number for s in shown if s.name == "use"])
        result.cost = dict(measures(extended, meal, result.units), added=len(result.missing))
        # "satisfiable": no weighted atom was grounded, so every model costs 0
        result.status = "optimal" if outcome.status in ("optimal", "satisfiable") else "feasible"
        return result
    if outcome.status == "unknown":
        result.status, result.reason = "unknown", "time ran out"
        return result
    if goals:
        # which goals are blocked on their own
        blocked = [g for g in meal if not missing(problem, g, options).has_tree]
        names = "; ".join(str(problem.objects[g]) for g in blocked)
        result.reason = (
            f"no set of objects helps these goal(s): {names}" if blocked else "the constraints rule out every tree"
        )
        if not blocked:
            result.status = "infeasible"
        return result
    goal = meal[0]
    reach = {s.arguments[0].number for s in prog.control.facts_of("reach", 1)}
    if goal in reach:
        result.status = "infeasible"
        result.reason = "the constraints rule out every tree"
    elif goal not in problem.producers:
        result.reason = "no unit of the FOON makes it and it is not in the kitchen"
    else:
        result.path, result.cycle = blocking_cycle(problem, goal, reach)
        result.reason = "no set of objects that can only be brought in helps; a cycle blocks it"
    return result


def blocking_cycle(problem: Problem, goal: int, reach: set[int]) -> tuple[list[tuple[int, int]], list[tuple[int, int]]]:
    """A cycle of unreachable objects that blocks ``goal`` (the shortest through the goal, else
    through the object nearest it) and the path to it; ``reach``: the objects reachable."""

    def succ(o: int) -> Iterable[tuple[int, int]]:
        for u in problem.producers.get(o, ()):
            for i in problem.required[u]:
                if i not in reach:
                    yield u, i

    # objects reachable from the goal along edges, nearest first, with the path to them
    route: dict[int, list[tuple[int, int]]] = {goal: []}
    order = [goal]
    for o in order:
        for u, i in succ(o):
            if i not in route:
                route[i] = route[o] + [(o, u)]
                order.append(i)
    for start in order:
        back: dict[int, tuple[int, int]] = {}
        queue = [start]
        for o in queue:
            for u, i in succ(o):
                if i == start:
                    cycle = [(o, u)]
                    while o != start:
                        o, u = back[o]
                        cycle.append((o, u))
                    return route[start], cycle[::-1]
                if i not in back and i != start:
                    back[i] = (o, u)
                    queue.append(i)
    return [], []


def shows(text: str) -> bool:
    """Does the program ``text`` (free of syntax errors) have a ``#show`` statement of its own?"""
    kinds = (clingo.ast.ASTType.ShowSignature, clingo.ast.ASTType.ShowTerm)
    found: list[bool] = []
    clingo.ast.parse_string(text, lambda stm: found.append(stm.ast_type in kinds))
    return any(found)


def query_warnings(prog: Program, program: tuple[str, str], loaded: Iterable[str]) -> list[str]:
    """Warnings about the user's ``program`` (name, text) and the shipped encodings ``loaded``
    that ``prog`` grounded: each predicate used but defined by no rule head and no fact, at its
    first use, with the closest defined names or the encoding that defines it."""
    name, text = program
    user = predicates(text)
    shipped = shipped_predicates()
    found = [(name, user)] + [(f"encodings/parts/{enc}.lp", shipped[enc]) for enc in loaded]
    known = known_predicates() | user.defined
    atoms = prog.control.ctl.symbolic_atoms  # the predicates with atoms after grounding
    here = {(n, a) for n, a, _ in atoms.signatures if next(iter(atoms.by_signature(n, a)), None) is not None}
    for _, pred in found:
        here |= pred.defined
    out = []
    for k, (part, pred) in enumerate(found):
        for sig, where in pred.used.items():
            if sig in here:
                continue
            if k == 0 and sig not in known:  # the user's program
                out.append(undefined(part, sig, where, known))
                continue
            line, column = where
            message = f"{escape(part)}:{line}:{column}: {signature_text(sig)} occurs in no rule head and no fact"
            defines = [enc for enc, p in shipped.items() if sig in p.defined and sig not in p.declared]
            by = sorted(defines, key=lambda enc: (enc != "tree", enc))
            if by:
                also = f" (or {', '.join(by[1:])})" if by[1:] else ""
                message += f"; load the encoding {by[0]}{also}, which defines it"
            out.append(message)
    return out


def query(
    problem: Problem,
    program: tuple[str, str],
    goal_nodes: Iterable[int] = (),
    goal: int | None = None,
    with_encodings: Iterable[str] = (),
    models: int = 1,
    time_limit: float | None = None,
) -> QueryResult:
    """Run the user's ``program`` (name, text) with the facts of ``problem`` and the shipped
    ``with_encodings`` (objectives: the first listed weighs most).  With an objective the best
    model is returned, else up to ``models`` models (0 = all)."""
    name, text = program
    check_syntax(name, text)
    own_show = shows(text)
    parts = [("facts", facts(problem, goal_nodes=goal_nodes, goal=goal))]
    asked = list(dict.fromkeys(with_encodings))
    ranked = [n for n in asked if n in OBJECTIVES]
    have = encoding_files.parts()
    for enc in asked:
        if enc not in have:
            raise InputError(f"no encoding {enc!r}; have {', '.join(have)}")
    # the parts that do not derive a tree themselves are read over tree.lp's
    shipped = shipped_predicates()
    names = ["tree", *asked] if any(("use", 1) not in shipped[enc].defined for enc in asked) else asked
    names = list(dict.fromkeys(names))
    files = [encoding_files.part(enc) for enc in names]
    if own_show:  # only what the user's #show statements show
        files.append(encoding_files.show("nothing"))
    else:
        files += [encoding_files.show(enc) for enc in names if enc in encoding_files.shows()]
    if "inputs" in names:
        parts.append(("input_nodes", input_node_facts(problem)))
    # objective encodings listed first weigh most: objective(Name,P), P = n..1
    parts.append(("objectives", objective_facts(ranked)))
    parts.append((name, text))
    prog = Program(parts, ["--opt-mode=opt", "--models=0"], files)
    warnings = query_warnings(prog, (name, text), names)
    result = prog.solve(time_limit, max(models, 0))
    result.warnings, result.encodings = warnings, names
    return result
