"""ASP facts for a problem.

Objects and units are integer ids; every text enters as an escaped string literal
(:func:`q`), so no label can change the program.  The predicates are the stable vocabulary
of docs/vocabulary.md.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

from foon2asp.foon.problem import Problem
from foon2asp.tree.weights import neglog_weight, success_permille

_ESCAPES = str.maketrans({"\\": "\\\\", '"': '\\"', "\n": "\\n", "\x00": None})


def q(text: str) -> str:
    """``text`` as an escaped ASP string literal (same escaping as ``str(clingo.String(text))``)."""
    return '"' + text.translate(_ESCAPES) + '"'


Lines = Callable[[Problem, int], list[str]]

#: the facts of an object after ``object(O).``, in order: (predicate, its lines)
_OBJECT_LINES: tuple[tuple[str, Lines], ...] = (
    ("label", lambda p, o: [f"label({o},{q(p.objects[o].label)})."]),
    ("state", lambda p, o: [f"state({o},{q(s)})." for s in p.objects[o].states]),
    ("ingredient", lambda p, o: [f"ingredient({o},{q(i)})." for i in p.objects[o].ingredients]),
    ("container", lambda p, o: [f"container({o},{q(c)})." for c in [p.objects[o].container] if c is not None]),
)

#: the facts of a unit after ``unit(U).``, in order ("": always written)
_UNIT_LINES: tuple[tuple[str, Lines], ...] = (
    ("motion", lambda p, u: [f"motion({u},{q(p.units[u].motion)})."]),
    ("success", lambda p, u: [f"success({u},{success_permille(p.rates[u])})."]),
    ("neglog", lambda p, u: [f"neglog({u},{neglog_weight(p.rates[u])})."]),
    ("input", lambda p, u: [f"input({u},{o})." for o in dict.fromkeys(p.inputs[u])]),
    ("", lambda p, u: [f"required({u},{o})." for o in p.required[u]]),
    ("output", lambda p, u: [f"output({u},{o})." for o in dict.fromkeys(p.outputs[u])]),
    ("", lambda p, u: [f"product({u},{o})." for o in p.products[u]]),
)


#: predicates a solver session may leave out when no program it grounds reads them
OPTIONAL = ("label", "state", "ingredient", "container", "motion", "success", "neglog", "input", "output")


def unit_ids(problem: Problem, units: Iterable[int] | None = None) -> Sequence[int]:
    """``units`` sorted, each once; None: every unit of ``problem``."""
    return range(len(problem.units)) if units is None else sorted(set(units))


def fact_objects(problem: Problem, units: Iterable[int]) -> set[int]:
    """The objects :func:`facts` writes for these units (their inputs and outputs, the kitchen)."""
    objects: set[int] = set(problem.kitchen)
    for u in units:
        objects.update(problem.inputs[u])
        objects.update(problem.outputs[u])
    return objects


def facts(
    problem: Problem,
    goal_nodes: Iterable[int] = (),
    goal: int | None = None,
    units: Iterable[int] | None = None,
    leave_out: Iterable[str] = (),
    whole_kitchen: bool = True,
    declare: bool = True,
) -> str:
    """The facts as ASP text: of ``units`` (None: all) and their objects, ``goal_node(N,O)``
    and ``goal(O)``; ``leave_out``: predicates of :data:`OPTIONAL` not to write;
    ``whole_kitchen=False``: only the kitchen items among the units' objects;
    ``declare=False``: no ``unit/1`` and ``object/1``."""
    leave_out = frozenset(leave_out)
    unknown = leave_out - set(OPTIONAL)
    if unknown:
        raise ValueError(f"facts cannot leave out {sorted(unknown)}")
    ids = unit_ids(problem, units)
    unit_lines = [make for name, make in _UNIT_LINES if name not in leave_out]
    object_lines = [make for name, make in _OBJECT_LINES if name not in leave_out]
    lines = ["% units"]
    for u in ids:
        lines += [f"unit({u})."] if declare else []
        lines += [line for make in unit_lines for line in make(problem, u)]
    if whole_kitchen:
        objects = fact_objects(problem, ids)
    else:
        objects = {o for u in ids for o in (*problem.inputs[u], *problem.outputs[u])}
    goal_nodes = list(goal_nodes)
    objects.update(goal_nodes)
    if goal is not None:
        objects.add(goal)
    lines.append("% objects")
    if object_lines or declare:
        for o in sorted(objects):
            lines.append(f"object({o}).")
            lines += [line for make in object_lines for line in make(problem, o)]
    lines.append("% kitchen")
    kitchen = problem.kitchen
    lines += [f"kitchen({o})." for o in sorted(objects) if o in kitchen]
    if goal_nodes:
        lines.append("% goals file")
        lines += [f"goal_node({n},{o})." for n, o in enumerate(goal_nodes, 1)]
    if goal is not None:
        lines.append(f"goal({goal}).")
    return "\n".join(lines) + "\n"
