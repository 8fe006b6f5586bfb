"""ASP facts for a problem.

Objects and units are integer ids; every piece of text (labels, states,
ingredients, containers, motions) enters as a clingo string built with
:func:`clingo.String`, so quotes, backslashes, ``).``, ``#show`` or newlines
in a label stay data and can never change the program.

Vocabulary (stable, documented in docs/vocabulary.md):

=====================  =====================================================
``object(O)``          O is an object id
``label(O,L)``         its label; ``state(O,S)``, ``ingredient(O,I)``,
                       ``container(O,C)`` likewise
``unit(U)``            U is a functional unit id (FOON file order)
``motion(U,M)``        the motion of U
``input(U,O)``         O is an input of U; ``required(U,O)`` if it must be had
``output(U,O)``        O is an output of U; ``product(U,O)`` if it counts as made
``success(U,P)``       motion success rate of U in thousandths (1..1000)
``neglog(U,W)``        round(-1000 * ln rate), the weight the success objective sums
``kitchen(O)``         O is available in the kitchen
``goal_node(N,O)``     entry N (from 1) of the goals file is object O
``goal(O)``            the object to make (only when a goal is fixed)
=====================  =====================================================
"""

from __future__ import annotations

from collections.abc import Iterable

from foon2asp.foon.problem import Problem
from foon2asp.tree.weights import neglog_weight, success_permille

_ESCAPES = str.maketrans({"\\": "\\\\", '"': '\\"', "\n": "\\n", "\x00": None})


def q(text: str) -> str:
    """``text`` as an escaped ASP string literal (same escaping as ``str(clingo.String(text))``)."""
    return '"' + text.translate(_ESCAPES) + '"'


def object_facts(problem: Problem, oid: int, leave_out: frozenset[str] = frozenset()) -> list[str]:
    obj = problem.objects[oid]
    out = [f"object({oid})."]
    if "label" not in leave_out:
        out.append(f"label({oid},{q(obj.label)}).")
    if "state" not in leave_out:
        out += [f"state({oid},{q(s)})." for s in obj.states]
    if "ingredient" not in leave_out:
        out += [f"ingredient({oid},{q(i)})." for i in obj.ingredients]
    if obj.container is not None and "container" not in leave_out:
        out.append(f"container({oid},{q(obj.container)}).")
    return out


def unit_facts(problem: Problem, u: int, leave_out: frozenset[str] = frozenset()) -> list[str]:
    rate = problem.rates[u]
    out = [f"unit({u})."]
    if "motion" not in leave_out:
        out.append(f"motion({u},{q(problem.units[u].motion)}).")
    if "success" not in leave_out:
        out.append(f"success({u},{success_permille(rate)}).")
    if "neglog" not in leave_out:
        out.append(f"neglog({u},{neglog_weight(rate)}).")
    if "input" not in leave_out:
        out += [f"input({u},{o})." for o in dict.fromkeys(problem.inputs[u])]
    out += [f"required({u},{o})." for o in problem.required[u]]
    if "output" not in leave_out:
        out += [f"output({u},{o})." for o in dict.fromkeys(problem.outputs[u])]
    out += [f"product({u},{o})." for o in problem.products[u]]
    return out


#: predicates a solver session may leave out when no program it grounds reads them
OPTIONAL = ("label", "state", "ingredient", "container", "motion", "success", "neglog", "input", "output")


def fact_objects(problem: Problem, unit_ids: Iterable[int]) -> set[int]:
    """The objects :func:`facts` writes for these units (their inputs and outputs, the kitchen)."""
    objects: set[int] = set(problem.kitchen)
    for u in unit_ids:
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
    """The facts as ASP text.

    ``units`` restricts the FOON part to those units (and their objects);
    ``goal_nodes`` are written as ``goal_node(N,O)``, ``goal`` as ``goal(O)``.
    ``leave_out`` names predicates of :data:`OPTIONAL` not to write: the tree
    encodings read none of the strings, ``input/2`` or ``output/2``, and a
    solver session grounds faster without facts nobody reads.  ``whole_kitchen=False``
    writes only the kitchen items among the units' objects (a goal's part needs no other);
    ``declare=False`` leaves out ``unit/1`` and ``object/1`` (a prepared part reads neither).
    """
    leave_out = frozenset(leave_out)
    unknown = leave_out - set(OPTIONAL)
    if unknown:
        raise ValueError(f"facts cannot leave out {sorted(unknown)}")
    unit_ids = range(len(problem.units)) if units is None else sorted(set(units))
    lines = ["% units"]
    for u in unit_ids:
        lines += unit_facts(problem, u, leave_out)[0 if declare else 1 :]
    if whole_kitchen:
        objects = fact_objects(problem, unit_ids)
    else:
        objects = {o for u in unit_ids for o in (*problem.inputs[u], *problem.outputs[u])}
    goal_nodes = list(goal_nodes)
    objects.update(goal_nodes)
    if goal is not None:
        objects.add(goal)
    lines.append("% objects")
    if leave_out.issuperset(("label", "state", "ingredient", "container")):
        lines += [f"object({o})." for o in sorted(objects)] if declare else []
    else:
        for o in sorted(objects):
            lines += object_facts(problem, o, leave_out)
    lines.append("% kitchen")
    kitchen = problem.kitchen
    lines += [f"kitchen({o})." for o in sorted(objects) if o in kitchen]
    if goal_nodes:
        lines.append("% goals file")
        lines += [f"goal_node({n},{o})." for n, o in enumerate(goal_nodes, 1)]
    if goal is not None:
        lines.append(f"goal({goal}).")
    return "\n".join(lines) + "\n"
