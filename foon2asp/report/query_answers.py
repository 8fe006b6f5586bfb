"""Answers of ``reachable``, ``missing`` and ``query`` as text and JSON."""

from __future__ import annotations

import json

import clingo

from foon2asp.foon.problem import Problem
from foon2asp.outcomes import MissingResult, QueryResult
from foon2asp.report.formats import register
from foon2asp.tree.serialize import goal_heading, tree_text
from foon2asp.tree.tasktree import TaskTree

#: argument kinds of the vocabulary predicates: o = object id, u = unit id, - = other
VOCABULARY: dict[tuple[str, int], str] = {
    (name, len(kinds)): kinds
    for kinds, names in (
        ("o", "object kitchen goal reach relevant had asked reachable unreachable buyable add"),
        ("u", "unit viable candidate use fire"),
        ("o-", "label state ingredient container"),
        ("u-", "motion success neglog"),
        ("uo", "input required output product needs"),
        ("-o", "goal_node"),
    )
    for name in names.split()
}


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
        return str(clingo.String(value))
    return str(value)


def atom_text(problem: Problem, sym: clingo.Symbol) -> str:
    """An atom with objects as ``<label, states>`` and units as ``<motion: in -> out>``."""
    d = decode(problem, sym)
    if d["predicate"] is None:
        return d["atom"]
    if not d["arguments"]:
        return d["predicate"]
    return f"{d['predicate']}(" + ", ".join(_text(problem, a) for a in d["arguments"]) + ")"


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
    head = (
        {"goals": [problem.objects[g].to_json() for g in result.goals]}
        if result.goals
        else {"goal": problem.objects[result.goal].to_json()}
    )
    out = {
        **head,
        "status": result.status,
        "missing": [problem.objects[o].to_json() for o in result.missing],
        "units": [problem.units[u].to_json() for u in result.units],
        "cost": result.cost,
        "time_s": result.time_s,
    }
    if result.substitutions is not None:
        out["substitutions"] = result.substitutions
    if result.reason:
        out["reason"] = result.reason
    if result.cycle:
        out["path"] = _cycle_json(problem, result.path)
        out["cycle"] = _cycle_json(problem, result.cycle)
    return out


def _needs(problem: Problem, o: int, u: int, nxt: int) -> str:
    return f"    {problem.objects[o]}\n      is made by '{problem.units[u].motion}', which needs {problem.objects[nxt]}"


def missing_text(problem: Problem, result: MissingResult) -> str:
    tree = TaskTree(result.goal, "missing", result.status, result.units, result.cost, result.time_s, goals=result.goals)
    if not result.has_tree:
        lines = [goal_heading(problem, tree), f"Status: {result.status}: {result.reason or 'no tree'}"]
        if result.cycle:
            chain = result.path + result.cycle
            if result.path:
                lines.append("  on the way:")
                for k, (o, u) in enumerate(result.path):
                    lines.append(_needs(problem, o, u, chain[k + 1][0]))
            lines.append("  the cycle:")
            for k, (o, u) in enumerate(result.cycle):
                nxt = result.cycle[(k + 1) % len(result.cycle)][0]
                lines.append(
                    _needs(problem, o, u, nxt) + (" (back to the start)" if k == len(result.cycle) - 1 else "")
                )
        return "\n".join(lines) + "\n"
    body = tree_text(problem, tree).splitlines()
    top = 2 + len(result.goals)  # the heading (one line per goal of a meal) and the method line
    if result.missing:
        add = [f"  Missing {len(result.missing)} object(s); add to the kitchen:"]
        add += [f"    + {problem.objects[o]}" for o in result.missing]
        add.append("  Then:")
    elif all(g in problem.kitchen for g in tree.meal):
        add = ["  Nothing is missing: the goal is in the kitchen."]
    else:
        add = ["  Nothing is missing: the goal can be made from the kitchen."]
    uses = [f"uses {s['used']} for {s['needed']}" for s in result.substitutions or ()]
    return "\n".join(body[:top] + uses + add + body[top:]) + "\n"


def _ordered(symbols: list[clingo.Symbol]) -> list[clingo.Symbol]:
    """Grouped by predicate name, then in clingo's order."""
    return sorted(symbols, key=lambda s: (s.name if s.type == clingo.SymbolType.Function else "", s))


def query_json(problem: Problem, result: QueryResult) -> dict:
    """``{"status", "time_s", "models": [{"cost", "atoms": [decoded atom, ...]}]}``."""
    return {
        "status": result.status,
        "time_s": result.time_s,
        "encodings": result.encodings,
        "warnings": result.warnings,
        "models": [
            {"cost": a.cost, "atoms": [decode(problem, s) for s in _ordered(a.symbols)]} for a in result.answers
        ],
    }


def query_text(problem: Problem, result: QueryResult) -> str:
    lines = [f"Status: {result.status}"]
    if result.encodings:
        lines.append(f"Encodings: {', '.join(result.encodings)}")
    for n, answer in enumerate(result.answers, 1):
        cost = f"  (cost {' '.join(map(str, answer.cost))})" if answer.cost else ""
        if len(result.answers) > 1 or cost:
            lines.append(f"Model {n}{cost}:")
        atoms = [atom_text(problem, s) for s in _ordered(answer.symbols)]
        lines += [f"  {a}" for a in atoms] or ["  (no shown atoms)"]
    return "\n".join(lines) + "\n"


register("reachable", "text", "txt")(reachable_text)
register("reachable", "json", "json")(
    lambda problem, answers: json.dumps(reachable_json(problem, answers), indent=2) + "\n"
)
register("missing", "text", "txt")(lambda problem, results: "\n".join(missing_text(problem, r) for r in results))
register("reachable", "jsonl", "jsonl")(
    lambda problem, answers: "".join(json.dumps(r) + "\n" for r in reachable_json(problem, answers))
)
register("missing", "jsonl", "jsonl")(
    lambda problem, results: "".join(json.dumps(missing_json(problem, r)) + "\n" for r in results)
)
register("missing", "json", "json")(
    lambda problem, results: json.dumps([missing_json(problem, r) for r in results], indent=2) + "\n"
)
register("query", "text", "txt")(query_text)
register("query", "json", "json")(lambda problem, result: json.dumps(query_json(problem, result), indent=2) + "\n")
