"""Declarative queries over a FOON: reachability, missing items, user programs.

* :func:`reachable` -- which objects can be made from the kitchen at all, for
  many objects in one solve (``encodings/tree.lp`` + ``reachable.lp``);
* :func:`missing` -- the fewest objects to add to the kitchen so a goal can be
  made, then the fewest units (``encodings/missing.lp``), proven minimal; when
  no set helps, :func:`blocking_cycle` names a cycle that blocks the goal;
* :func:`query` -- a user's program run with the facts, its shown atoms
  decoded (object and unit ids become readable objects and units).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Iterable

import clingo

from foon2asp.asp import encodings
from foon2asp.asp.constraints import check, clingo_error
from foon2asp.errors import InputError
from foon2asp.asp.facts import facts
from foon2asp.foon.problem import Problem
from foon2asp.asp.session import OBJECTIVES
from foon2asp.tree.tasktree import TaskTree, executable_order, measures
from foon2asp.report.trees import tree_text

# --------------------------------------------------------------------------- running


@dataclass
class Answer:
    """One model: its shown symbols and its cost."""

    symbols: list[clingo.Symbol]
    cost: list[int] = field(default_factory=list)


@dataclass
class Outcome:
    """The result of one solve call."""

    #: ``optimal`` (optimum proven), ``satisfiable`` (models, no objective),
    #: ``feasible`` (stopped early), ``unsatisfiable`` or ``unknown``
    status: str
    answers: list[Answer]
    time_s: float
    #: facts the grounder derived, by predicate name (for signatures asked for)
    derived: dict[str, set[clingo.Symbol]] = field(default_factory=dict)


class Program:
    """One clingo control: add named parts, ground once, solve once."""

    def __init__(self, parts: Iterable[tuple[str, str]], args: Iterable[str] = ()) -> None:
        self._messages: list[str] = []
        self.ctl = clingo.Control(list(args), logger=self._log, message_limit=20)
        self.parts = list(parts)
        for name, text in self.parts:
            self._messages.clear()
            try:
                self.ctl.add("base", [], text)
            except RuntimeError:
                raise clingo_error(self._messages, name) from None
        self._messages.clear()
        try:
            self.ctl.ground([("base", [])])
        except RuntimeError:
            for name, text in self.parts:
                if name != "facts":
                    check(name, text)
            raise clingo_error(self._messages, "program") from None

    def _log(self, code: clingo.MessageCode, message: str) -> None:
        self._messages.append(message)

    def facts_of(self, name: str, arity: int) -> set[clingo.Symbol]:
        """Atoms of ``name/arity`` the grounder derived as facts."""
        return {a.symbol for a in self.ctl.symbolic_atoms.by_signature(name, arity) if a.is_fact}

    def solve(self, time_limit: float | None = None, limit: int = 1) -> Outcome:
        """Solve.  When optimising, keep the best model; else stop after ``limit`` models (0 = all).

        The control must run with ``--models=0`` (and ``--opt-mode=opt``) so
        optimisation is not cut short; plain enumeration stops here instead.
        """
        answers: list[Answer] = []
        proven = [False]

        def on_model(model: clingo.Model) -> bool:
            answer = Answer(list(model.symbols(shown=True)), list(model.cost))
            if answer.cost:
                answers[:] = [answer]
                proven[0] = model.optimality_proven
                return True
            answers.append(answer)
            return not (limit and len(answers) >= limit)

        t0 = time.perf_counter()
        with self.ctl.solve(on_model=on_model, async_=True) as handle:
            finished = handle.wait(time_limit) if time_limit else handle.wait()
            if not finished:
                handle.cancel()
            result = handle.get()
        elapsed = time.perf_counter() - t0
        optimising = any(a.cost for a in answers)
        if not answers:
            status = "unsatisfiable" if result.unsatisfiable and finished else "unknown"
        elif optimising:
            done = (result.exhausted and not result.interrupted and finished) or proven[0]
            status = "optimal" if done else "feasible"
        else:
            status = "satisfiable"
        return Outcome(status, answers, round(elapsed, 6))


# --------------------------------------------------------------------------- reachable


def reachable(problem: Problem, objects: Iterable[int]) -> dict[int, bool]:
    """For each object id: can it be made from the kitchen?  One grounding, one solve."""
    objects = list(dict.fromkeys(objects))
    asked = "".join(f"asked({o}).\n" for o in objects)
    prog = Program(
        [
            ("facts", facts(problem)),
            ("encodings/tree.lp", encodings.encoding("tree")),
            ("encodings/reachable.lp", encodings.encoding("reachable")),
            ("asked", asked),
        ],
        ["--models=0"],
    )
    outcome = prog.solve()
    if not outcome.answers:  # pragma: no cover - the program is stratified, always one model
        raise RuntimeError("reachability program has no model")
    yes = {s.arguments[0].number for s in outcome.answers[-1].symbols if s.name == "reachable"}
    return {o: o in yes for o in objects}


# --------------------------------------------------------------------------- missing


def with_kitchen(problem: Problem, extra: Iterable[int]) -> Problem:
    """The same problem with the objects ``extra`` (ids) added to the kitchen."""
    items = list(problem.kitchen_items) + [problem.objects[o] for o in extra]
    return Problem(problem.foon, items, problem.motion_rates, problem.utensils, problem.utensil_rule)


@dataclass
class MissingResult:
    """What to add to the kitchen so ``goal`` can be made, and the tree it allows."""

    goal: int
    #: ``optimal`` (proven minimal), ``feasible`` (time ran out), ``unreachable``, ``unknown``
    status: str
    #: object ids to add, in id order
    missing: list[int] = field(default_factory=list)
    #: the tree (unit ids in executable order, with the added objects in the kitchen)
    units: list[int] = field(default_factory=list)
    cost: dict = field(default_factory=dict)
    time_s: float = 0.0
    #: why nothing helps, in words (only when unreachable)
    reason: str | None = None
    #: a cycle that blocks the goal: (object, unit) pairs, each unit makes its
    #: object and needs the next object (the last needs the first)
    cycle: list[tuple[int, int]] = field(default_factory=list)
    #: objects leading from the goal to the cycle, as (object, unit) pairs
    path: list[tuple[int, int]] = field(default_factory=list)
    #: every object that may be added (relevant to the goal)
    buyable: list[int] = field(default_factory=list)

    @property
    def has_tree(self) -> bool:
        return self.status in ("optimal", "feasible")


def missing(
    problem: Problem,
    goal: int,
    user_programs: Iterable[tuple[str, str]] = (),
    time_limit: float | None = None,
) -> MissingResult:
    """The fewest objects to add to the kitchen so ``goal`` can be made, then the fewest units."""
    t0 = time.perf_counter()
    if goal in problem.kitchen:
        units: list[int] = []
    else:
        units = problem.relevant_units(goal)
    user_programs = list(user_programs)
    prog = Program(
        [
            ("facts", facts(problem, goal=goal, units=units)),
            ("encodings/missing.lp", encodings.encoding("missing")),
            *user_programs,
        ],
        ["--opt-mode=opt", "--models=0"],
    )
    buyable = sorted(s.arguments[0].number for s in prog.facts_of("buyable", 1))
    outcome = prog.solve(time_limit)
    elapsed = round(time.perf_counter() - t0, 6)
    if outcome.answers:
        shown = outcome.answers[-1].symbols
        added = sorted(s.arguments[0].number for s in shown if s.name == "add")
        used = [s.arguments[0].number for s in shown if s.name == "use"]
        extended = with_kitchen(problem, added)
        order = executable_order(extended, used)
        cost = measures(extended, goal, order)
        cost["added"] = len(added)
        # "satisfiable": no weighted atom was grounded, so every model costs 0
        status = "optimal" if outcome.status in ("optimal", "satisfiable") else "feasible"
        return MissingResult(goal, status, added, order, cost, elapsed, buyable=buyable)
    if outcome.status == "unknown":
        return MissingResult(goal, "unknown", time_s=elapsed, reason="time ran out", buyable=buyable)
    reach = {s.arguments[0].number for s in prog.facts_of("reach", 1)}
    result = MissingResult(goal, "unreachable", time_s=elapsed, buyable=buyable)
    if goal in reach:
        result.reason = "the constraints rule out every tree"
    elif goal not in problem.producers:
        result.reason = "no unit of the FOON makes it and it is not in the kitchen"
    else:
        result.path, result.cycle = blocking_cycle(problem, goal, reach)
        result.reason = "no set of objects that can only be brought in helps; a cycle blocks it"
    return result


def blocking_cycle(problem: Problem, goal: int, reach: set[int]) -> tuple[list[tuple[int, int]], list[tuple[int, int]]]:
    """A cycle of unreachable objects that blocks ``goal``, and the path to it.

    Edges go from an unreachable object O to an unreachable required input I
    of a unit U making O.  Every unreachable object that some unit makes has
    such an edge (its producers cannot fire), so a walk from the goal meets a
    cycle.  The shortest cycle through the goal is preferred, else the
    shortest through the object nearest the goal.
    """

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


# --------------------------------------------------------------------------- query

#: argument kinds of the vocabulary predicates: o = object id, u = unit id, - = other
VOCABULARY: dict[tuple[str, int], str] = {
    ("object", 1): "o",
    ("label", 2): "o-",
    ("state", 2): "o-",
    ("ingredient", 2): "o-",
    ("container", 2): "o-",
    ("unit", 1): "u",
    ("motion", 2): "u-",
    ("input", 2): "uo",
    ("required", 2): "uo",
    ("output", 2): "uo",
    ("product", 2): "uo",
    ("success", 2): "u-",
    ("neglog", 2): "u-",
    ("kitchen", 1): "o",
    ("goal_node", 2): "-o",
    ("goal", 1): "o",
    ("reach", 1): "o",
    ("viable", 1): "u",
    ("relevant", 1): "o",
    ("candidate", 1): "u",
    ("use", 1): "u",
    ("fire", 1): "u",
    ("had", 1): "o",
    ("asked", 1): "o",
    ("reachable", 1): "o",
    ("unreachable", 1): "o",
    ("needs", 2): "uo",
    ("buyable", 1): "o",
    ("add", 1): "o",
}


@dataclass
class QueryResult:
    status: str
    answers: list[Answer]
    time_s: float


def query(
    problem: Problem,
    program: tuple[str, str],
    goal_nodes: Iterable[int] = (),
    goal: int | None = None,
    with_encodings: Iterable[str] = (),
    models: int = 1,
    time_limit: float | None = None,
) -> QueryResult:
    """Run the user's ``program`` (name, text) with the facts of ``problem``.

    ``with_encodings`` loads shipped encodings (``tree``, ``units``, ...);
    objective encodings also get ``objective(Name,P)`` facts, the first
    listed with the highest priority P.  With an
    objective, the best model is returned; else up to ``models`` models
    (0 = all).
    """
    name, text = program
    check(name, text)
    parts = [("facts", facts(problem, goal_nodes=goal_nodes, goal=goal))]
    names = list(dict.fromkeys(with_encodings))
    ranked = [n for n in names if n in OBJECTIVES]
    for enc in names:
        try:
            parts.append((f"encodings/{enc}.lp", encodings.encoding(enc)))
        except KeyError as exc:
            raise InputError(str(exc.args[0])) from None
    # objective encodings listed first weigh most: objective(Name,P), P = n..1
    parts += [(f"objective {n}", f"objective({n},{len(ranked) - k}).\n") for k, n in enumerate(ranked)]
    parts.append((name, text))
    outcome = Program(parts, ["--opt-mode=opt", "--models=0"]).solve(time_limit, max(models, 0))
    return QueryResult(outcome.status, outcome.answers, outcome.time_s)


def _term(problem: Problem, sym: clingo.Symbol, kind: str = "-"):
    """A symbol as plain data; object/unit ids (by kind, or as object(N)/unit(N)) decoded."""
    if sym.type == clingo.SymbolType.Number:
        n = sym.number
        if kind == "o" and 0 <= n < len(problem.objects):
            return {"object": n, **problem.objects[n].to_json()}
        if kind == "u" and 0 <= n < len(problem.units):
            return {"unit": n, **problem.units[n].to_json()}
        return n
    if sym.type == clingo.SymbolType.String:
        return sym.string
    if sym.type == clingo.SymbolType.Function and len(sym.arguments) == 1 and sym.name in ("object", "unit"):
        arg = sym.arguments[0]
        if arg.type == clingo.SymbolType.Number:
            return _term(problem, arg, sym.name[0])
    return str(sym)


def decode(problem: Problem, sym: clingo.Symbol) -> dict:
    """``{"atom", "predicate", "arguments"}`` with ids decoded (see :data:`VOCABULARY`)."""
    if sym.type != clingo.SymbolType.Function:
        return {"atom": str(sym), "predicate": None, "arguments": [_term(problem, sym)]}
    kinds = VOCABULARY.get((sym.name, len(sym.arguments)), "-" * len(sym.arguments))
    return {
        "atom": str(sym),
        "predicate": sym.name,
        "arguments": [_term(problem, a, k) for a, k in zip(sym.arguments, kinds)],
    }


def _text(problem: Problem, value) -> str:
    if isinstance(value, dict) and "object" in value:
        return f"<{problem.objects[value['object']]}>"
    if isinstance(value, dict) and "unit" in value:
        return f"<{problem.units[value['unit']]}>"
    if isinstance(value, str):
        return clingo.String(value).__str__()
    return str(value)


def atom_text(problem: Problem, sym: clingo.Symbol) -> str:
    """An atom with objects as ``<label, states>`` and units as ``<motion: in -> out>``."""
    d = decode(problem, sym)
    if d["predicate"] is None:
        return d["atom"]
    if not d["arguments"]:
        return d["predicate"]
    return f"{d['predicate']}(" + ", ".join(_text(problem, a) for a in d["arguments"]) + ")"


# --------------------------------------------------------------------------- output


def reachable_json(problem: Problem, answers: dict[int, bool]) -> list[dict]:
    """``[{"goal": OBJ, "reachable": bool}, ...]`` in the order asked."""
    return [{"goal": problem.objects[o].to_json(), "reachable": ok} for o, ok in answers.items()]


def reachable_text(problem: Problem, answers: dict[int, bool]) -> str:
    lines = [f"{'yes' if ok else 'no ':3}  {problem.objects[o]}" for o, ok in answers.items()]
    n = sum(answers.values())
    lines.append(f"{n} of {len(answers)} reachable from the kitchen")
    return "\n".join(lines) + "\n"


def _cycle_json(problem: Problem, pairs: list[tuple[int, int]]) -> list[dict]:
    return [{"object": problem.objects[o].to_json(), "made_by": problem.units[u].to_json()} for o, u in pairs]


def missing_json(problem: Problem, result: MissingResult) -> dict:
    """``{"goal", "status", "missing", "units", "cost", "time_s"}`` (+ ``reason``, ``path``, ``cycle``)."""
    out = {
        "goal": problem.objects[result.goal].to_json(),
        "status": result.status,
        "missing": [problem.objects[o].to_json() for o in result.missing],
        "units": [problem.units[u].to_json() for u in result.units],
        "cost": result.cost,
        "time_s": result.time_s,
    }
    if result.reason:
        out["reason"] = result.reason
    if result.cycle:
        out["path"] = _cycle_json(problem, result.path)
        out["cycle"] = _cycle_json(problem, result.cycle)
    return out


def _needs(problem: Problem, o: int, u: int, nxt: int) -> str:
    return f"    {problem.objects[o]}\n      is made by '{problem.units[u].motion}', which needs {problem.objects[nxt]}"


def missing_text(problem: Problem, result: MissingResult) -> str:
    goal = problem.objects[result.goal]
    if not result.has_tree:
        lines = [f"Goal: {goal}", f"Status: {result.status}: {result.reason or 'no tree'}"]
        if result.cycle:
            chain = result.path + result.cycle
            if result.path:
                lines.append("  on the way:")
                for k, (o, u) in enumerate(result.path):
                    lines.append(_needs(problem, o, u, chain[k + 1][0]))
            lines.append("  the cycle:")
            for k, (o, u) in enumerate(result.cycle):
                nxt = result.cycle[(k + 1) % len(result.cycle)][0]
                lines.append(_needs(problem, o, u, nxt) + (" (back to the start)" if k == len(result.cycle) - 1 else ""))
        return "\n".join(lines) + "\n"
    tree = TaskTree(result.goal, "missing", result.status, result.units, result.cost, result.time_s)
    body = tree_text(problem, tree).splitlines()
    if result.missing:
        add = [f"  Missing {len(result.missing)} object(s); add to the kitchen:"]
        add += [f"    + {problem.objects[o]}" for o in result.missing]
        add.append("  Then:")
    elif result.goal in problem.kitchen:
        add = ["  Nothing is missing: the goal is in the kitchen."]
    else:
        add = ["  Nothing is missing: the goal can be made from the kitchen."]
    return "\n".join(body[:2] + add + body[2:]) + "\n"


def _ordered(symbols: list[clingo.Symbol]) -> list[clingo.Symbol]:
    """Grouped by predicate name, then in clingo's order."""
    return sorted(symbols, key=lambda s: (s.name if s.type == clingo.SymbolType.Function else "", s))


def query_json(problem: Problem, result: QueryResult) -> dict:
    """``{"status", "time_s", "models": [{"cost", "atoms": [decoded atom, ...]}]}``."""
    return {
        "status": result.status,
        "time_s": result.time_s,
        "models": [
            {"cost": a.cost, "atoms": [decode(problem, s) for s in _ordered(a.symbols)]} for a in result.answers
        ],
    }


def query_text(problem: Problem, result: QueryResult) -> str:
    lines = [f"Status: {result.status}"]
    for n, answer in enumerate(result.answers, 1):
        cost = f"  (cost {' '.join(map(str, answer.cost))})" if answer.cost else ""
        if len(result.answers) > 1 or cost:
            lines.append(f"Model {n}{cost}:")
        atoms = [atom_text(problem, s) for s in _ordered(answer.symbols)]
        lines += [f"  {a}" for a in atoms] or ["  (no shown atoms)"]
    return "\n".join(lines) + "\n"
