"""An independent validator for task trees, and why a tree is not valid.

It replays the units on plain objects, without the encodings or the integer problem's
fixpoint (docs/proofs/preparation.md, "The independent validator").
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from foon2asp.foon.model import FoonObject, Unit, leaves
from foon2asp.foon.problem import Problem, product_outputs, required_flags
from foon2asp.foon.treefiles import TreeFile
from foon2asp.tree.weights import lexicographic


@dataclass
class Validation:
    valid: bool
    #: the first problem found, in words (None when valid)
    problem: str | None = None
    #: an executable order of the units that can fire
    order: list[int] = field(default_factory=list)
    #: units that can never fire with these units
    stuck: list[int] = field(default_factory=list)


class _Had:
    """The kitchen items and the objects made so far (the kitchen set is not copied)."""

    def __init__(self, kitchen: frozenset[FoonObject]) -> None:
        self.kitchen, self.made = kitchen, set[FoonObject]()

    def __contains__(self, o: object) -> bool:
        return o in self.made or o in self.kitchen

    def update(self, objects: Iterable[FoonObject]) -> None:
        self.made.update(objects)


def _required(problem: Problem, u: int) -> list[FoonObject]:
    unit = problem.units[u]
    flags = required_flags(unit, problem.utensils, problem.utensil_rule)
    return [o for o, f in zip(unit.inputs, flags) if f]


def _fire_all(
    todo: Iterable[int],
    need: Callable[[int], list[FoonObject]],
    made: Callable[[int], list[FoonObject]],
    have: set | _Had,
) -> tuple[list[int], list[int]]:
    """Fire the units of ``todo`` whose needs are in ``have`` (which grows), pass after pass,
    until none can: ``(order fired, units left)``."""
    pending, order = list(todo), []
    while True:
        left = []
        for u in pending:
            if all(o in have for o in need(u)):
                order.append(u)
                have.update(made(u))
            else:
                left.append(u)
        if len(left) == len(pending):
            return order, left
        pending = left


class _Reach:
    """The validator's view of a whole FOON for many fixpoints: each unit's required inputs and
    products as numbered objects (the validator's own reading: the utensil rule, products)."""

    def __init__(self, problem: Problem) -> None:
        number: dict[FoonObject, int] = {}
        key = lambda o: number.setdefault(o, len(number))  # noqa: E731
        self.kitchen = {key(o) for o in problem.kitchen_set}
        self.needs = [sorted({key(o) for o in _required(problem, u)}) for u in range(len(problem.units))]
        self.makes = [[key(o) for o in product_outputs(problem.units[u])] for u in range(len(problem.units))]
        self.users: dict[int, list[int]] = {}
        for u, needs in enumerate(self.needs):
            for o in needs:
                self.users.setdefault(o, []).append(u)
        self.number = number

    def fixpoint(self, removed: Iterable[int] = ()) -> tuple[set[int], set[int]]:
        """The units that fire, and the objects had, when every unit but ``removed`` may fire."""
        out = set(removed)
        had = set(self.kitchen)
        missing = [sum(1 for o in needs if o not in had) for needs in self.needs]
        ready = [u for u, m in enumerate(missing) if m == 0 and u not in out]
        fired: set[int] = set()
        while ready:
            u = ready.pop()
            fired.add(u)
            for o in self.makes[u]:
                if o in had:
                    continue
                had.add(o)
                for v in self.users.get(o, ()):
                    missing[v] -= 1
                    if missing[v] == 0 and v not in out:
                        ready.append(v)
        return fired, had

    def level(self, goal: int) -> int | None:
        """The rounds of firing every unit that can fire, all at once each round, until object
        ``goal`` is had (0: a kitchen item; None: never)."""
        had = set(self.kitchen)
        pending = set(range(len(self.needs)))
        rounds = 0
        while goal not in had:
            ready = [u for u in pending if all(o in had for o in self.needs[u])]
            if not ready:
                return None
            for u in ready:
                had.update(self.makes[u])
            pending.difference_update(ready)
            rounds += 1
        return rounds


#: the views built, by the problem's id (with a weak reference that says the problem is alive)
_REACH: dict[int, tuple[weakref.ref[Problem], _Reach]] = {}


def _reach(problem: Problem) -> _Reach:
    """The validator's view of ``problem`` (built once per problem)."""
    kept = _REACH.get(id(problem))
    if kept is not None and kept[0]() is problem:
        return kept[1]
    for key in [k for k, (ref, _) in _REACH.items() if ref() is None]:
        del _REACH[key]
    found = _Reach(problem)
    _REACH[id(problem)] = (weakref.ref(problem), found)
    return found


def circular_support(cycle: Iterable[tuple[object, int]], name: Callable[[int], str]) -> str:
    """``circular support: [A] is made by UNIT, which needs [B]; ...`` for (object, unit) pairs."""
    pairs = list(cycle)
    steps = []
    for k, (o, u) in enumerate(pairs):
        nxt = pairs[(k + 1) % len(pairs)][0]
        steps.append(f"[{o}] is made by {name(u)}, which needs [{nxt}]")
    return "circular support: " + "; ".join(steps)


def find_missing_or_cycle(
    roots: Iterable[tuple[Any, Any]], makers: dict[Any, list[Any]], lacking: Callable[[Any], list[Any]]
) -> tuple[str, Any] | None:
    """Walk back from each (object not had, unit that needs it) of ``roots``, depth first, through
    the makers of an object and their inputs not had (``lacking``): ``("missing", (object, unit))``
    for an object no unit makes, ``("cycle", [(object, unit that makes it), ...])`` for an object
    met again on the path; None when neither is found (docs/proofs/preparation.md, "Diagnosis")."""
    done: set = set()
    for root, needed_by in roots:
        if root in done:
            continue
        if not makers.get(root):
            return "missing", (root, needed_by)
        path: list[list] = [[root, None]]  # [object, unit being tried for it]
        on_path = {root: 0}
        stack = [iter([(u, i) for u in makers[root] for i in lacking(u)])]
        while stack:
            step = next(stack[-1], None)
            if step is None:
                obj = path.pop()[0]
                stack.pop()
                del on_path[obj]
                done.add(obj)
                continue
            u, nxt = step
            path[-1][1] = u
            if nxt in on_path:
                return "cycle", [(o, m) for o, m in path[on_path[nxt] :]]
            if nxt in done:
                continue
            if not makers.get(nxt):
                return "missing", (nxt, u)
            on_path[nxt] = len(path)
            path.append([nxt, None])
            stack.append(iter([(m, i) for m in makers[nxt] for i in lacking(m)]))
    return None


def validate(problem: Problem, goal: FoonObject | int, units: list[int]) -> Validation:
    """Is ``goal`` derivable from the kitchen with exactly these ``units``: every unit id
    exists, every unit fires (its required inputs had) and the goal is had at the end?
    The set is judged, not the order given."""
    goal_obj = problem.objects[goal] if isinstance(goal, int) else goal
    for u in units:
        if not (isinstance(u, int) and 0 <= u < len(problem.units)):
            return Validation(False, f"unit {u!r} is not in the FOON")
    have = _Had(problem.kitchen_set)
    order, pending = _fire_all(
        dict.fromkeys(units), lambda u: _required(problem, u), lambda u: product_outputs(problem.units[u]), have
    )
    if pending:
        u = pending[0]
        missing = next(o for o in _required(problem, u) if o not in have)
        words = f"unit {u} ({problem.units[u].motion}) never fires: missing input {missing}"
        return Validation(False, words, order, pending)
    if goal_obj not in have:
        return Validation(False, f"goal {goal_obj} is not made by these units", order)
    return Validation(True, None, order)


def bounds_proof(
    problem: Problem,
    goal: int,
    units: Iterable[int],
    landmarks: Iterable[int],
    sets: Iterable[Iterable[int]] = (),
    objective: str = "units",
    cases: dict | None = None,
    level: int | None = None,
) -> str | None:
    """Why the ``bounds`` proof of a tree fails, or None when it holds (docs/proofs/solving.md).

    The proof: every landmark is needed, and every landmark set too (without its units, every
    other unit of the FOON fired, the goal is not made), so every tree uses each landmark and
    one unit of each set; the landmarks and the sets are pairwise disjoint, so every tree
    weighs at least the landmarks' weight and the lightest unit's of each set under
    ``objective`` (then the number of units).  ``cases``: an object every tree makes (the goal,
    or a required input of a landmark, not in the kitchen) and, for every unit of the FOON that
    makes it and can fire, what every tree using that unit uses (units, and disjoint sets of
    which it uses one: without them that unit cannot fire or the goal is not made); every tree
    weighs at least the lightest case.  ``level``: with ``units``, the goal's derivation level
    (rounds of firing every unit that can fire); a tree of n units makes the goal within n
    rounds.  The tree weighs the largest of these bounds, so no tree costs less."""
    marks = sorted(set(landmarks))
    groups = [sorted(set(s)) for s in sets]
    tree = sorted(set(units))
    n = len(problem.units)
    split = _split(cases)
    if isinstance(split, str):
        return split
    claimed = [*marks, *(u for s in groups for u in s), *(_split_units(split) if split else ())]
    stray = [u for u in claimed if not 0 <= u < n]
    if stray:
        return f"landmark {stray[0]} is no unit of the FOON"
    why = _disjoint(set(marks), groups)
    if why:
        return why
    w = lexicographic(problem, objective)
    weight = sum(w[u] for u in tree)
    bound = sum(w[u] for u in marks) + sum(min(w[u] for u in s) for s in groups)
    if split:
        least = _split_bound(w, set(marks), split)
        if isinstance(least, str):
            return least
        bound = max(bound, least)
    if level is not None:
        if objective != "units":
            return f"a derivation level bounds the number of units, not {objective}"
        bound = max(bound, level)
    if bound != weight:
        return f"the landmarks bound the cost by {bound}, not by the tree's {weight} ({objective})"
    reach = _reach(problem)
    target = reach.number.get(problem.objects[goal])

    def fires(removed: Iterable[int]) -> tuple[set[int], bool]:
        """The units that fire when every unit of the FOON but ``removed`` may, and is the goal made?"""
        fired, had = reach.fixpoint(removed)
        return fired, target is not None and target in had

    for removed in [[u] for u in marks] + groups:
        if fires(removed)[1]:
            what = f"unit {removed[0]} ({problem.units[removed[0]].motion})" if len(removed) == 1 else f"set {removed}"
            return f"{what} is no landmark: the goal can be made without it"
    if split:
        why = _check_split(problem, goal, set(marks), [], split, fires, fires(())[0])
        if why:
            return why
    if level is not None:
        found = None if target is None else reach.level(target)
        if found != level:
            return f"the goal's derivation level is {found}, not {level}"
    return None


#: a case of a split as the validator reads it: (unit, units, sets, a split deeper or None)
_Case = tuple[int, list[int], list[list[int]], "_Split | None"]
#: a split: (object, cases)
_Split = tuple[int, list[_Case]]


def _split(cases: dict | None) -> _Split | None | str:
    """The case split of a bounds proof (``landmark_cases``, nested by ``split``), or why it is malformed."""
    if cases is None:
        return None
    try:
        made = cases["object"]
        split: list[_Case] = []
        for c in cases["cases"]:
            deeper = _split(c["split"]) if c.get("split") is not None else None
            if isinstance(deeper, str):
                return deeper
            sets = [sorted(set(s)) for s in c.get("landmark_sets", [])]
            split.append((c["unit"], sorted(set(c.get("landmarks", []))), sets, deeper))
    except (KeyError, TypeError, AttributeError):
        return "the landmark cases are not an object with its cases (unit, landmarks, landmark_sets, split)"
    found: _Split = (made, split)
    ids = [made, *_split_units(found)]
    if not all(isinstance(u, int) and not isinstance(u, bool) for u in ids):
        return "the landmark cases name something that is no id"
    if not split:
        return "the landmark cases have no case"
    return found


def _split_units(split: _Split) -> list[int]:
    """Every unit a split names, its deeper splits' too."""
    out: list[int] = []
    for c, m, ss, deeper in split[1]:
        out += [c, *m, *(u for s in ss for u in s)]
        if deeper is not None:
            out += _split_units(deeper)
    return out


def _split_bound(w: list[int], chain: set[int], split: _Split) -> int | str:
    """What every tree that uses ``chain`` weighs by ``split``: its lightest case (a case: its
    units with ``chain`` and the lightest unit of each of its sets, or its own split's bound if
    that is more), or why the sets are not disjoint."""
    bounds = []
    for c, m, ss, deeper in split[1]:
        units = {*chain, c, *m}
        why = _disjoint(units, ss)
        if why:
            return f"the case of unit {c}: {why}"
        bound = _weighs(w, units, ss)
        if deeper is not None:
            below = _split_bound(w, units, deeper)
            if isinstance(below, str):
                return below
            bound = max(bound, below)
        bounds.append(bound)
    return min(bounds)


def _disjoint(taken: set[int], groups: list[list[int]]) -> str | None:
    """Why ``groups`` are not non-empty, pairwise disjoint and disjoint from ``taken`` (None: they are)."""
    seen = set(taken)
    for s in groups:
        if not s:
            return "a landmark set is empty"
        if not seen.isdisjoint(s):
            return f"the landmark set {s} shares units with the landmarks or another set"
        seen.update(s)
    return None


def _weighs(w: list[int], units: set[int], groups: list[list[int]]) -> int:
    """The weight of ``units`` and of the lightest unit of each group."""
    return sum(w[u] for u in units) + sum(min(w[u] for u in s) for s in groups)


def _check_split(
    problem: Problem,
    goal: int,
    chain: set[int],
    assumed: list[int],
    split: _Split,
    fires: Callable[[Iterable[int]], tuple[set[int], bool]],
    fired: set[int],
) -> str | None:
    """Why a split of the trees that use ``chain`` (among them the units ``assumed``) does not
    hold (None: it does): its object is the goal or a required input of a unit of ``chain`` and
    no kitchen item, so those trees make it; every unit that makes it and fires (``fired``) has
    a case; each case's units and sets are needed by the trees that use ``assumed`` and the
    case's unit (without them, one of those does not fire or the goal is not made); its deeper
    split holds for those trees."""
    made, cases = split
    if not 0 <= made < len(problem.objects):
        return f"object {made} of the landmark cases is no object of the FOON"
    obj = problem.objects[made]
    if obj in problem.kitchen_set:
        return f"object {made} of the landmark cases is in the kitchen"
    if made != goal and not any(obj in _required(problem, u) for u in chain):
        return f"object {made} of the landmark cases is neither the goal nor needed by a landmark"
    cased = {c for c, _, _, _ in cases}
    for v in sorted(fired):
        if v not in cased and obj in product_outputs(problem.units[v]):
            return f"unit {v} ({problem.units[v].motion}) makes object {made} but has no case"
    for c, m, ss, deeper in cases:
        using = [*assumed, c]
        for removed in [[u] for u in m if u != c] + ss:
            left, made_goal = fires(removed)
            if made_goal and all(u in left for u in using):
                what = f"unit {removed[0]}" if len(removed) == 1 else f"set {removed}"
                return f"{what} is not needed by the trees that use unit {c}: unit {c} fires and the goal is made without it"
        if deeper is not None:
            why = _check_split(problem, goal, {*chain, c, *m}, using, deeper, fires, fired)
            if why:
                return why
    return None


@dataclass
class Finding:
    """The first problem of an invalid tree."""

    #: "unknown-unit" | "missing-input" | "cycle" | "goal-not-made"; for a file that gives no units
    #: for its goal: "unreachable" (the FOON confirms there is no tree) or "no-tree" (there is one)
    kind: str
    message: str
    #: for a cycle: (object, unit) pairs -- the object is made by the unit, which
    #: needs the next pair's object; the last unit needs the first object
    cycle: list[tuple[int, int]] = field(default_factory=list)
    #: the object that is missing or not made (missing-input, goal-not-made)
    obj: int | None = None
    #: the unit that needs the missing object
    unit: int | None = None


def describe_unit(problem: Problem, u: int, tree: TreeFile | None = None, ids: list[int | None] | None = None) -> str:
    """``unit 12 (mix, step 3 at tree.txt:40)``."""
    where = ""
    if tree is not None and ids is not None and u in ids:
        tu = tree.units[ids.index(u)]
        where = f", step {tu.step}" + (f" at line {tu.line}" if tu.line else "")
    return f"unit {u} ({problem.units[u].motion}{where})"


def check_units(
    problem: Problem, goal: int, units: list[int], name: Callable[[int], str] | None = None
) -> tuple[Validation, Finding | None]:
    """Validate FOON unit ids for ``goal`` and explain the first problem (None when valid): a
    missing input (not in the kitchen, made by no unit of the tree) or circular support, walking
    back from the goal, then from each stuck unit; ``name(u)`` words a unit in messages."""
    validation = validate(problem, goal, units)
    if validation.valid:
        return validation, None
    name = name or (lambda u: describe_unit(problem, u))
    have = set(problem.kitchen).union(*(problem.products[u] for u in validation.order))
    makers: dict[int, list[int]] = {}
    for u in dict.fromkeys(units):
        for o in problem.products[u]:
            makers.setdefault(o, []).append(u)

    def lacking(u: int) -> list[int]:
        return [i for i in problem.required[u] if i not in have]

    roots = [(goal, None)] if goal not in have else []
    found = find_missing_or_cycle(roots + [(i, u) for u in validation.stuck for i in lacking(u)], makers, lacking)
    if found is None:
        return validation, Finding("goal-not-made", validation.problem or "the tree is not valid", obj=goal)
    if found[0] == "cycle":
        cycle = found[1]
        return validation, Finding("cycle", circular_support([(problem.objects[o], u) for o, u in cycle], name), cycle)
    obj, needed_by = found[1]
    if needed_by is None:
        words = f"no unit of the tree makes the goal {problem.objects[goal]}"
        return validation, Finding("goal-not-made", words, obj=goal)
    words = (
        f"missing input: {problem.objects[obj]} is needed by {name(needed_by)} "
        "but is not in the kitchen and no unit of the tree makes it"
    )
    return validation, Finding("missing-input", words, obj=obj, unit=needed_by)


def derivable_objects(problem: Problem) -> set[FoonObject]:
    """Every object derivable from the kitchen with any units of the FOON, replayed on plain
    objects: a goal outside it has no tree."""
    have = set(problem.kitchen_items)
    lacking: list[set[FoonObject]] = []
    waiting: dict[FoonObject, list[int]] = {}
    ready = []
    for u in range(len(problem.units)):
        lacking.append({o for o in _required(problem, u) if o not in have})
        for o in lacking[u]:
            waiting.setdefault(o, []).append(u)
        if not lacking[u]:
            ready.append(u)
    while ready:  # each unit fires once, when the last object it lacks is had
        for o in product_outputs(problem.units[ready.pop()]):
            if o not in have:
                have.add(o)
                for v in waiting.pop(o, ()):
                    lacking[v].discard(o)
                    if not lacking[v]:
                        ready.append(v)
    return have


def check_order(problem: Problem, goal: FoonObject | int, units: list[int]) -> str | None:
    """None if ``units`` run in the given order make the goal; else the first problem."""
    goal_obj = problem.objects[goal] if isinstance(goal, int) else goal
    have = set(problem.kitchen_items)
    for step, u in enumerate(units, 1):
        for o in _required(problem, u):
            if o not in have:
                return f"step {step} (unit {u}) needs {o}, which is not had yet"
        have.update(product_outputs(problem.units[u]))
    return None if goal_obj in have else f"goal {goal_obj} is not made"


@dataclass
class Blocked:
    """The first unit that cannot fire when its turn comes (units in the order given)."""

    step: int  # its position in the list, from 1
    unit: Unit
    #: the first required input not had at that point
    waits_for: FoonObject
    #: the position of the first later unit that makes it (None: no unit of the list does)
    made_by: int | None


@dataclass
class AloneVerdict:
    """What :func:`judge_alone` says about a list of units (positions count from 1)."""

    #: the units, as a set, make every goal from the kitchen (as :func:`validate` judges)
    valid: bool
    #: the units fire in the order given and the goals are had at the end (as :func:`check_order` judges)
    in_order: bool
    goals: tuple[FoonObject, ...]
    kitchen: list[FoonObject]
    blocked: Blocked | None = None
    #: positions of the units that can never fire with these units
    stuck: list[int] = field(default_factory=list)
    #: positions of the units that can fire, in an order in which they can (the set's fixpoint)
    order: list[int] = field(default_factory=list)
    #: circular support: (object, position of the unit that makes it and needs the next pair's
    #: object); the last unit needs the first object
    cycle: list[tuple[FoonObject, int]] = field(default_factory=list)
    #: an object a stuck unit needs that is neither in the kitchen nor made by any unit, and that unit
    missing: FoonObject | None = None
    needed_by: int | None = None
    #: goals not made by the units as a set
    unmade: list[FoonObject] = field(default_factory=list)
    #: the first problem in words (None when valid and executable in order) and its kind: ``no-goal``,
    #: ``cycle``, ``missing-input``, ``order`` (the units fire only in another order) or ``goal-not-made``
    problem: str | None = None
    kind: str | None = None
    #: the number each position has in the file (units skipped by a reader leave gaps); empty: the positions
    numbers: list[int] = field(default_factory=list)

    def step(self, position: int) -> int:
        """The number in the file of the unit at ``position`` (from 1), as messages name it."""
        return self.numbers[position - 1] if self.numbers else position


def last_products(units: list[Unit]) -> tuple[FoonObject, ...]:
    """The products of the last unit that makes any (generated trees list their units in order)."""
    for unit in reversed(units):
        if product_outputs(unit):
            return tuple(dict.fromkeys(product_outputs(unit)))
    return ()


def judge_alone(
    units: list[Unit],
    goal: FoonObject | tuple[FoonObject, ...] | None = None,
    kitchen: list[FoonObject] | None = None,
    utensils: frozenset[str] = frozenset(),
    utensil_rule: str = "starter",
    numbers: list[int] | None = None,
) -> AloneVerdict:
    """Judge a tree file's ``units`` (in file order) on its own, without a FOON: in the order
    given, then as a set.  The kitchen defaults to the units' leaves, the goal to the products of
    the last unit; ``numbers``: each unit's number in its file, for the messages."""
    start = list(kitchen) if kitchen is not None else leaves(units)
    goals = last_products(units) if goal is None else (goal if isinstance(goal, tuple) else (goal,))
    need = [[o for o, f in zip(u.inputs, required_flags(u, utensils, utensil_rule)) if f] for u in units]
    makers: dict[FoonObject, list[int]] = {}
    for k, u in enumerate(units):
        for o in product_outputs(u):
            makers.setdefault(o, []).append(k)
    verdict = AloneVerdict(False, False, goals, start, numbers=list(numbers or []))

    # in the order given
    have = set(start)
    for k, u in enumerate(units):
        lacking = [o for o in need[k] if o not in have]
        if lacking:
            later = next((m for m in makers.get(lacking[0], []) if m > k), None)
            verdict.blocked = Blocked(k + 1, u, lacking[0], None if later is None else later + 1)
            break
        have.update(product_outputs(u))
    verdict.in_order = bool(goals) and verdict.blocked is None and all(g in have for g in goals)

    # as a set
    have = set(start)
    order, pending = _fire_all(list(range(len(units))), need.__getitem__, lambda k: product_outputs(units[k]), have)
    verdict.order = [k + 1 for k in order]
    verdict.stuck = [k + 1 for k in pending]
    verdict.unmade = [g for g in goals if g not in have]
    verdict.valid = bool(goals) and not pending and not verdict.unmade
    if pending:
        k = pending[0]
        first = [(o, k) for o in need[k] if o not in have][:1]
        found = find_missing_or_cycle(first, makers, lambda m: [o for o in need[m] if o not in have])
        if found is not None and found[0] == "cycle":
            verdict.cycle = [(o, m + 1) for o, m in found[1]]
        elif found is not None:
            verdict.missing, verdict.needed_by = found[1][0], found[1][1] + 1
    verdict.kind, verdict.problem = _alone_problem(units, verdict)
    return verdict


def _alone_problem(units: list[Unit], v: AloneVerdict) -> tuple[str | None, str | None]:
    """The kind of the verdict's first problem and the problem in words (None, None: none)."""

    def name(position: int) -> str:
        return f"step {v.step(position)} ({units[position - 1].motion})"

    if not v.goals:
        if not units:
            return "no-goal", "no goal: no unit makes an object"
        bare = " | ".join(str(o) for o in units[-1].outputs)
        return "no-goal", (
            f"no goal: no unit makes an object; the last, {name(len(units))}, outputs {bare or 'nothing'},"
            " with no states, ingredients or container"
        )
    if v.cycle:
        return "cycle", circular_support(v.cycle, name)
    if v.missing is not None and v.needed_by is not None:
        return "missing-input", (
            f"missing input: {v.missing} is needed by {name(v.needed_by)} "
            "but is not in the kitchen and no unit makes it"
        )
    if v.blocked is not None:
        b = v.blocked
        later = f"which only {name(b.made_by)} makes" if b.made_by else "which no unit makes"
        return "order", f"{name(b.step)} cannot fire in the order given: it waits for {b.waits_for}, {later}"
    if v.unmade:
        return "goal-not-made", f"goal {v.unmade[0]} is not made by these units"
    return None, None
