"""Seeded synthetic FOONs: copies of a given one, or hard FOONs with real choice.

:func:`synthesize` makes a FOON N times the size of a given one, with the same
shape.  Copy ``k`` (0..N-1) of the base FOON renames every label, ingredient
and container to ``"LABEL~k"`` (copy 0 keeps the names), so each copy has the
base's producers per object, inputs per unit, depths and cycles; the kitchen
and the utensils are copied the same way, motions are shared.  Cross-links
then tie the copies together: for a fraction ``cross`` of the units of
copies 1.., an extra unit is added that makes the same outputs from the same
inputs except one required input taken from another (random) copy.  That
adds alternative producers and cycles across copies, as a merged FOON of
many recipe sets has, while the averages stay close to the base.

:func:`generate` makes a FOON from scratch with knobs for choice (producers
per object, shared intermediates, depth, cycles, ...), and :data:`PRESETS`
names seeded instances of it (:func:`preset`): ``tiny`` and ``small`` for
tests, ``hard-4k`` and ``hard-10k`` for the benchmark (bench/hard.py).
Generated on demand, never stored as data.
"""

from __future__ import annotations

import json
import random
from dataclasses import dataclass
from pathlib import Path

from foon2asp.errors import InputError
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
    """A synthetic data set (the same parts as :class:`~foon2asp.foon.loaders.Dataset`)."""

    foon: Foon
    kitchen: list[FoonObject]
    goals: list[FoonObject]
    motion: dict[str, float]
    utensils: frozenset[str]
    #: the preset's name, if any (names the goals in messages)
    name: str = ""

    def problem(self, utensil_rule: str = "starter") -> Problem:
        return Problem(self.foon, self.kitchen, self.motion, self.utensils, utensil_rule)

    def dataset(self) -> Dataset:
        """The same data as a :class:`~foon2asp.foon.loaders.Dataset` (what loading :meth:`write`'s folder gives)."""
        goals = [(g, i) for i, g in enumerate(self.goals, 1)]
        where = {"goals": f"<goals of {self.name or 'the synthetic FOON'}>"}
        return Dataset(self.foon, list(self.kitchen), goals, dict(self.motion), self.utensils, where)

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


# --- hard FOONs with real choice --------------------------------------------

_STATES = (
    "chopped sliced diced mixed cooked heated mashed whisked fried boiled baked ground peeled grated blended cooled"
).split()
_CONTAINERS = ("bowl", "pan", "pot", "plate", "tray", "jar", "cup", "mixing bowl")
_TOOLS = ("knife", "spoon", "whisk", "spatula", "ladle", "fork", "peeler", "grater")
_MOTIONS = (
    "chop slice dice mix stir cook heat mash whisk fry boil bake grind peel grate blend pour cool season"
    " knead roll spread sprinkle fold"
).split()

#: a count: a (lo, hi) range drawn uniformly, or a float mean (1 + geometric extra)
Count = tuple[int, int] | float


def _count(spec: Count, rng: random.Random) -> int:
    if isinstance(spec, tuple | list):
        return rng.randint(int(spec[0]), int(spec[1]))
    mean = float(spec)
    if mean <= 1:
        return 1
    n = 1
    while rng.random() > 1.0 / mean:  # geometric: P(stop) = 1 / mean
        n += 1
    return n


def _mean(spec: Count) -> float:
    if isinstance(spec, tuple | list):
        return (spec[0] + spec[1]) / 2
    return max(1.0, float(spec))


def generate(
    units: int = 4000,
    producers: Count = (1, 4),
    shared: float = 0.25,
    depth: int = 12,
    cycles: float = 0.02,
    kitchen: int = 150,
    goals: int = 20,
    seed: int = 0,
    inputs: Count = (2, 3),
    chain: float = 0.5,
    shared_pool: float = 0.03,
    byproduct: float = 0.6,
    byproduct_use: float = 0.1,
    utensil_pairs: float = 0.05,
    dead: int = 3,
    unreachable_goal: bool = True,
) -> Synthetic:
    """A FOON with real choice, deterministic for a given ``seed``.

    * **kitchen**: ``kitchen`` raw items (``ing17, raw``), containers
      (``bowl, empty``) and bare tools (``knife``).
    * **made objects** over ``depth`` layers, about ``units / mean(producers)``
      of them, none bare; each gets ``producers`` units (the total is trimmed
      or padded to exactly ``units``).
    * **inputs** (``inputs`` of them) of a producer of a layer-L object: with
      probability ``shared`` one of a pool of popular intermediates
      (``shared_pool`` of the made objects, from the lower two thirds of the
      layers: the trees of many goals overlap there); else with probability
      ``chain`` an object of layer L-1 (deep trees); else any lower layer or
      the kitchen (short cuts: cheap producers beside expensive ones).  Plus
      one tool, which passes through as a bare output.
    * **by-products**: with probability ``byproduct`` a unit also makes a
      unit-specific ``container, used``; a later unit needs one with
      probability ``byproduct_use`` (forced, single-producer sub-chains).
    * **cycles**: a fraction ``cycles`` of the units takes one input from the
      same or a higher layer (back edges), and ``dead`` gadgets (X needs Y,
      Y needs X) make objects nobody can derive.
    * **utensil rule**: in a fraction ``utensil_pairs`` of the units
      ``bowl contains {x}`` sits beside ``x ..., in [bowl]``.
    * **goals**: ``goals`` derivable made objects with at least two producers
      from the upper two thirds of the layers, a mix of derivation levels;
      plus (``unreachable_goal``) one dead object.
    """
    rng = random.Random(seed)
    motion = {m: round(rng.uniform(0.35, 1.0), 3) for m in _MOTIONS}
    raw = [FoonObject.make(f"ing{i}", [rng.choice(["raw", "whole", "fresh"])]) for i in range(kitchen)]
    tools = [FoonObject.make(t) for t in _TOOLS]
    kitchen_objects = raw + [FoonObject.make(c, ["empty"]) for c in _CONTAINERS] + tools

    n_main = max(depth, int(round(units / _mean(producers))))
    per_layer = [n_main // depth + (1 if i < n_main % depth else 0) for i in range(depth)]
    layers: list[list[FoonObject]] = [list(raw)]
    level_of: dict[FoonObject, int] = {o: 0 for o in raw}
    serial = 0
    for layer_no in range(1, depth + 1):
        layer = []
        for _ in range(per_layer[layer_no - 1]):
            serial += 1
            states = [rng.choice(_STATES)]
            if rng.random() < 0.3:
                states.append(rng.choice(_STATES))
            ingredients = [f"ing{rng.randrange(kitchen)}" for _ in range(rng.randint(0, 3))]
            container = rng.choice(_CONTAINERS) if rng.random() < 0.7 else None
            obj = FoonObject.make(f"food{serial}", states, ingredients, container)
            layer.append(obj)
            level_of[obj] = layer_no
        layers.append(layer)
    made = [o for layer in layers[1:] for o in layer]
    low = [o for layer in layers[1 : max(2, (2 * depth) // 3)] for o in layer]
    pool = rng.sample(low, max(1, min(len(low), int(shared_pool * len(made)))))

    # producers per made object, trimmed or padded to exactly `units` in total
    counts = {o: _count(producers, rng) for o in made}
    total = sum(counts.values())
    order = list(made)
    rng.shuffle(order)
    i = 0
    while total > units and i < 10 * len(order):
        o = order[i % len(order)]
        if counts[o] > 1:
            counts[o] -= 1
            total -= 1
        i += 1
    i = 0
    while total < units:
        counts[order[i % len(order)]] += 1
        total += 1
        i += 1

    foon = Foon()
    byproducts: list[FoonObject] = []

    def pick_input(layer_no: int) -> FoonObject:
        if rng.random() < shared:
            below = [o for o in pool if level_of[o] < layer_no]
            if below:
                return rng.choice(below)
        if layer_no > 1 and rng.random() < chain:
            return rng.choice(layers[layer_no - 1])
        if byproducts and rng.random() < byproduct_use:
            b = rng.choice(byproducts)
            if level_of[b] < layer_no:
                return b
        return rng.choice(layers[rng.randrange(0, layer_no)])

    for layer_no in range(1, depth + 1):
        for obj in layers[layer_no]:
            for _ in range(counts[obj]):
                ins: list[FoonObject] = []
                for _k in range(_count(inputs, rng)):
                    x = pick_input(layer_no)
                    if x not in ins and x != obj:
                        ins.append(x)
                if not ins:
                    ins.append(rng.choice(raw))
                if rng.random() < cycles:
                    x = rng.choice(layers[rng.randrange(layer_no, depth + 1)])  # a back edge
                    if x != obj and x not in ins:
                        ins.append(x)
                tool = rng.choice(tools)
                ins.append(tool)
                outs = [obj, tool]  # the tool passes through: a bare output, not a product
                held = [x for x in ins if x.container in _CONTAINERS]
                if held and rng.random() < utensil_pairs:
                    x = rng.choice(held)
                    assert x.container is not None
                    ins.append(FoonObject.make(x.container, [], [x.label]))
                if rng.random() < byproduct:
                    b = FoonObject.make(rng.choice(_CONTAINERS), ["used"], [f"trace{len(byproducts)}"])
                    outs.append(b)
                    level_of[b] = layer_no
                    byproducts.append(b)
                foon.add_unit(Unit(rng.choice(_MOTIONS), tuple(ins), tuple(outs)), ("generate", 0))

    dead_objects = []
    for d in range(dead):
        x = FoonObject.make(f"dead{d}x", ["cooked"], [], "pot")
        y = FoonObject.make(f"dead{d}y", ["mixed"], [], "bowl")
        base = rng.choice(made)
        foon.add_unit(Unit("cook", (y, base, tools[0]), (x, tools[0])), ("generate", 0))
        foon.add_unit(Unit("mix", (x, rng.choice(raw)), (y,)), ("generate", 0))
        dead_objects.append(x)

    goal_objects = _pick_goals(foon, set(kitchen_objects), made, level_of, goals, rng, depth)
    if unreachable_goal and dead_objects:
        goal_objects.append(dead_objects[0])
    return Synthetic(foon, kitchen_objects, goal_objects, motion, frozenset(_CONTAINERS))


def _pick_goals(
    foon: Foon,
    kitchen: set[FoonObject],
    made: list[FoonObject],
    level_of: dict[FoonObject, int],
    n: int,
    rng: random.Random,
    depth: int,
) -> list[FoonObject]:
    # least-fixpoint derivation levels over all units (to pick goals of mixed depth)
    problem = Problem(foon, list(kitchen), utensils=frozenset(_CONTAINERS))
    level_ids = problem.derivation_levels()[0]
    levels = {obj: level_ids[i] for obj, i in foon.object_ids.items() if i in level_ids}
    producers: dict[FoonObject, int] = {}
    for unit in foon.units:
        for o in unit.outputs:
            if not o.is_bare():
                producers[o] = producers.get(o, 0) + 1
    cands = [o for o in made if o in levels and level_of[o] >= max(2, depth // 3) and producers.get(o, 0) >= 2]
    if not cands:
        cands = [o for o in made if o in levels]
    by_level: dict[int, list[FoonObject]] = {}
    for o in cands:
        by_level.setdefault(levels[o], []).append(o)
    for v in by_level.values():
        rng.shuffle(v)
    out: list[FoonObject] = []
    while len(out) < n and any(by_level.values()):
        for k in sorted(by_level):
            if by_level[k] and len(out) < n:
                out.append(by_level[k].pop())
    return out


#: named, seeded instances of :func:`generate` (keyword arguments)
PRESETS: dict[str, dict] = {
    # brute-force size: parts of at most ~30 units, for exhaustive checks in tests
    "tiny": dict(
        units=60, producers=(1, 3), shared=0.3, depth=4, cycles=0.05, kitchen=12, goals=6, seed=1, inputs=(1, 2),
        shared_pool=0.15, dead=1,
    ),
    # the same structure as the hard ones, small enough for tests (parts of 200-300 units)
    "small": dict(
        units=400, producers=(1, 4), shared=0.3, depth=8, cycles=0.03, kitchen=30, goals=10, seed=2,
        shared_pool=0.06, dead=2,
    ),
    # the sizes: 1-4 producers per made object, shared intermediates, a few cycles
    "hard-4k": dict(
        units=4000, producers=(1, 4), shared=0.25, depth=12, cycles=0.02, kitchen=150, byproduct=0.8, goals=20,
        seed=3,
    ),
    "hard-10k": dict(
        units=10000, producers=(1, 4), shared=0.25, depth=14, cycles=0.02, kitchen=300, byproduct=0.8, goals=30,
        seed=4,
    ),
}  # fmt: skip


def preset(name: str) -> Synthetic:
    """The named instance of :data:`PRESETS` (``generate(**PRESETS[name])``)."""
    if name not in PRESETS:
        raise InputError(f"unknown preset {name!r} (have {', '.join(PRESETS)})")
    syn = generate(**PRESETS[name])
    syn.name = name
    return syn
