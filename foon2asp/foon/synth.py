"""Seeded synthetic FOONs N times the size of a given one, with the same shape.

Copy ``k`` (0..N-1) of the base FOON renames every label, ingredient and
container to ``"LABEL~k"`` (copy 0 keeps the names), so each copy has the
base's producers per object, inputs per unit, depths and cycles; the kitchen
and the utensils are copied the same way, motions are shared.  Cross-links
then tie the copies together: for a fraction ``cross`` of the units of
copies 1.., an extra unit is added that makes the same outputs from the same
inputs except one required input taken from another (random) copy.  That
adds alternative producers and cycles across copies, as a merged FOON of
many recipe sets has, while the averages stay close to the base.
"""

from __future__ import annotations

import json
import random
from dataclasses import dataclass
from pathlib import Path

from foon2asp.foon.loaders import Dataset
from foon2asp.foon.model import Foon, FoonObject, Unit
from foon2asp.foon.parser import write_foon
from foon2asp.foon.problem import Problem, required_flags


def _rename(obj: FoonObject, copy: int) -> FoonObject:
    if copy == 0:
        return obj
    tag = f"~{copy}"
    return FoonObject(
        obj.label + tag,
        obj.states,
        tuple(sorted(i + tag for i in obj.ingredients)),
        obj.container + tag if obj.container is not None else None,
    )


def _unit(unit: Unit, copy: int) -> Unit:
    return Unit(
        unit.motion, tuple(_rename(o, copy) for o in unit.inputs), tuple(_rename(o, copy) for o in unit.outputs)
    )


@dataclass
class Synthetic:
    """A synthetic data set (the same parts as :class:`~foon2asp.loaders.Dataset`)."""

    foon: Foon
    kitchen: list[FoonObject]
    goals: list[FoonObject]
    motion: dict[str, float]
    utensils: frozenset[str]

    def problem(self, utensil_rule: str = "starter") -> Problem:
        return Problem(self.foon, self.kitchen, self.motion, self.utensils, utensil_rule)

    def write(self, directory: str | Path) -> Path:
        """Write FOON.txt, kitchen.json, goal_nodes.json, motion.txt, utensils.txt."""
        out = Path(directory)
        out.mkdir(parents=True, exist_ok=True)
        with open(out / "FOON.txt", "w", encoding="utf-8") as fh:
            write_foon(self.foon, fh, header=f"synthetic FOON: {len(self.foon.units)} units")
        (out / "kitchen.json").write_text(json.dumps([o.to_json() for o in self.kitchen], indent=1), encoding="utf-8")
        (out / "goal_nodes.json").write_text(json.dumps([o.to_json() for o in self.goals], indent=1), encoding="utf-8")
        (out / "motion.txt").write_text(
            "".join(f"{m}\t{r}\n" for m, r in sorted(self.motion.items())), encoding="utf-8"
        )
        (out / "utensils.txt").write_text("".join(f"{u}\n" for u in sorted(self.utensils)), encoding="utf-8")
        return out


def synthesize(data: Dataset, factor: int, seed: int = 0, cross: float = 0.02) -> Synthetic:
    """``factor`` renamed copies of ``data`` plus cross-links (see the module docstring)."""
    if factor < 1:
        raise ValueError("factor must be at least 1")
    rng = random.Random(seed)
    base = data.foon
    foon = Foon()
    for k in range(factor):
        for unit in base.units:
            foon.add_unit(_unit(unit, k), ("synthetic", 0))
    if factor > 1 and cross > 0:
        for k in range(1, factor):
            for unit in base.units:
                if rng.random() >= cross:
                    continue
                flags = required_flags(unit, data.utensils)
                positions = [i for i, f in enumerate(flags) if f]
                if not positions:
                    continue
                swap = rng.choice(positions)
                other = rng.choice([j for j in range(factor) if j != k])
                ins = tuple(_rename(o, other if i == swap else k) for i, o in enumerate(unit.inputs))
                foon.add_unit(Unit(unit.motion, ins, tuple(_rename(o, k) for o in unit.outputs)), ("synthetic", 0))
    kitchen = [_rename(o, k) for k in range(factor) for o in data.kitchen]
    goals = [_rename(o, k) for k in range(factor) for o, _ in data.goals]
    utensils = frozenset(u + (f"~{k}" if k else "") for k in range(factor) for u in data.utensils)
    return Synthetic(foon, kitchen, goals, dict(data.motion), utensils)


def shape(problem: Problem) -> dict:
    """Shape figures of a problem: units, objects, producers per object, inputs per unit, depth, cycles."""
    producers = [len(v) for v in problem.producers.values()]
    inputs = [len(r) for r in problem.required]
    obj_level, _ = problem.derivation_levels()
    # objects some unit makes that never become derivable: they rest on cycles or missing items
    return {
        "units": len(problem.units),
        "objects": len(problem.objects),
        "producers_per_object": round(sum(producers) / max(1, len(producers)), 3),
        "required_inputs_per_unit": round(sum(inputs) / max(1, len(inputs)), 3),
        "max_depth": max(obj_level.values(), default=0),
        "derivable": len(obj_level),
        "cycles": _count_cycles(problem),
    }


def _count_cycles(problem: Problem) -> int:
    """Strongly connected components with more than one object in the object graph
    (input -> product through a unit): how many cyclic groups the FOON has."""
    graph: dict[int, set[int]] = {}
    for u, req in enumerate(problem.required):
        for i in req:
            graph.setdefault(i, set()).update(problem.products[u])
    index: dict[int, int] = {}
    low: dict[int, int] = {}
    on_stack: set[int] = set()
    stack: list[int] = []
    count = 0
    counter = 0
    for root in list(graph):
        if root in index:
            continue
        work = [(root, iter(graph.get(root, ())))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, it = work[-1]
            advanced = False
            for nxt in it:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(graph.get(nxt, ()))))
                    advanced = True
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                size = 0
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    size += 1
                    if w == node:
                        break
                if size > 1:
                    count += 1
    return count
