"""Schedules: optimal makespans against brute force, both encodings, joint tree and schedule."""

from __future__ import annotations

import itertools
import math
import random

import pytest

from foon2asp.asp import constraints
from foon2asp.asp.options import AspOptions
from foon2asp.schedule import ScheduleSpec, joint, schedule
from foon2asp.schedule import solve as solve_mod
from foon2asp.schedule.checker import check_schedule
from foon2asp.schedule.spec import HUMAN, Durations
from foon2asp.tree.tasktree import TaskTree, executable_order
from helpers import as_obj, best, brute_force, build, goal_id

try:
    import clingodl  # noqa: F401

    ENCODINGS: tuple[str, ...] = ("steps", "dl")
except ImportError:  # the dl encoding needs clingo-dl (pip install 'foon2asp[dl]')
    ENCODINGS = ("steps",)


def given(problem, goal, units, status="optimal") -> TaskTree:
    return TaskTree(goal=goal, method="given", status=status, units=executable_order(problem, units))


# ---------------------------------------------------------------- brute force


def brute_schedule(problem, units, spec):
    """(makespan in ms, fewest human units at it) over every firing order and agent assignment,
    each placed by the serial schedule generation scheme (earliest feasible start, insertion),
    which yields every active schedule; None when no agent can do some unit.  Independent of
    foon2asp.schedule.instances: needs, durations and resources come straight from the FOON."""
    agents = spec.agent_list()
    units = list(units)
    kitchen = problem.kitchen
    needs = {u: [o for o in problem.required[u] if o not in kitchen] for u in units}
    dur = {
        u: {a: spec.durations.of(k, problem.units[u].motion) for a, k in agents if spec.can(k, problem.units[u].motion)}
        for u in units
    }
    if any(not d for d in dur.values()):
        return None
    labels = {u: {o.label for o in problem.units[u].inputs} for u in units}
    best_key = (math.inf, math.inf)
    for order in itertools.permutations(units):
        made: set[int] = set()
        ok = True
        for u in order:
            if not all(o in made for o in needs[u]):
                ok = False
                break
            made.update(problem.products[u])
        if not ok:
            continue
        for choice in itertools.product(*(sorted(dur[u]) for u in order)):
            placed: list[tuple[int, str, int, int]] = []
            ends: dict[int, int] = {}
            for u, agent in zip(order, choice):
                d = dur[u][agent]
                ready = 0
                for o in needs[u]:
                    ready = max(ready, min(ends[p] for p, _, _, _ in placed if o in problem.products[p]))
                for t in sorted({ready} | {e for *_, e in placed if e >= ready}):
                    if _fits(t, d, agent, u, placed, labels, spec.resources):
                        break
                placed.append((u, agent, t, t + d))
                ends[u] = t + d
            key = (max(e for *_, e in placed), sum(1 for _, a, _, _ in placed if a.rsplit("-", 1)[0] == HUMAN))
            best_key = min(best_key, key)
    return best_key


def _fits(t, d, agent, u, placed, labels, resources) -> bool:
    for _, a, s, e in placed:
        if a == agent and s < t + d and t < e and d > 0 and s < e:
            return False
    for label, cap in resources.items():
        if label not in labels[u] or d == 0:
            continue
        points = {t} | {s for p, _, s, _ in placed if t < s < t + d}
        for x in points:
            busy = sum(1 for p, _, s, e in placed if label in labels[p] and s <= x < e)
            if busy + 1 > cap:
                return False
    return True


# ---------------------------------------------------------------- random instances

MOTIONS = ("chop", "pour", "mix")


def random_tree(rng: random.Random, n: int, knife: float = 0.5):
    """A FOON of n units forming one in-tree (each unit's product goes to one later unit),
    kitchen items k0, k1 and sometimes a shared knife; returns (problem, goal, units)."""
    units = []
    parent = {i: rng.randint(i + 1, n - 1) for i in range(n - 1)}
    for i in range(n):
        ins = [f"p{j}" for j in range(n - 1) if parent[j] == i] + [f"k{rng.randint(0, 1)}"]
        if rng.random() < knife:
            ins.append(("knife",))
        units.append((rng.choice(MOTIONS), ins, [f"p{i}"]))
    problem = build(units, ["k0", "k1", ("knife",)])
    return problem, goal_id(problem, f"p{n - 1}"), list(range(n))


def random_spec(rng: random.Random, kinds) -> ScheduleSpec:
    values = [0, 500, 1000, 1000, 1500, 2000, 3000]
    motions = {m: rng.choice(values) for m in MOTIONS}
    per_kind = {k: {m: rng.choice(values) for m in MOTIONS if rng.random() < 0.5} for k, _ in kinds}
    caps = {}
    for k, _ in kinds:
        if rng.random() < 0.4:
            caps[k] = frozenset(rng.sample(MOTIONS, 2))
    resources = {"knife": 1} if rng.random() < 0.6 else {}
    return ScheduleSpec(tuple(kinds), Durations(motions, per_kind), caps, resources)


AGENT_SETS = [(("robot", 1),), (("arm", 2),), (("arm", 1), ("human", 1)), (("arm", 2), ("human", 1))]


@pytest.mark.parametrize("seed", range(20))
def test_optimal_makespan_equals_brute_force(seed):
    rng = random.Random(seed)
    kinds = AGENT_SETS[seed % len(AGENT_SETS)]
    n = 4 if sum(k for _, k in kinds) == 3 else 5
    problem, goal, units = random_tree(rng, n)
    spec = random_spec(rng, kinds)
    want = brute_schedule(problem, units, spec)
    tree = given(problem, goal, units)
    for encoding in ENCODINGS:
        r = schedule(problem, tree, spec, encoding=encoding, shortcut=False)
        if want is None:
            assert r.status == "unschedulable" and r.makespan is None and "no agent can do" in r.reason
            continue
        assert r.status == "optimal", (encoding, r.stats)
        assert (r.makespan, len(r.human)) == want, encoding
        assert check_schedule(problem, r.to_dict(), spec) is None
        b = r.bounds
        assert b is not None and max(b.chain, b.work) <= b.lower <= r.makespan <= r.baseline


def test_shortcut_gives_the_same_answer():
    rng = random.Random(7)
    for k in range(6):
        problem, goal, units = random_tree(rng, 6, knife=0.0)
        spec = ScheduleSpec(AGENT_SETS[k % 2])
        tree = given(problem, goal, units)
        fast, slow = schedule(problem, tree, spec), schedule(problem, tree, spec, shortcut=False)
        assert fast.makespan == slow.makespan and fast.status == slow.status == "optimal"
        assert check_schedule(problem, fast.to_dict(), spec) is None


def test_a_unit_nobody_can_do_is_unschedulable():
    problem, goal, units = random_tree(random.Random(1), 3)
    motions = {problem.units[u].motion for u in units}
    spec = ScheduleSpec((("arm", 2),), capabilities={"arm": frozenset(set(MOTIONS) - {min(motions)})})
    r = schedule(problem, given(problem, goal, units), spec)
    assert r.status == "unschedulable" and r.makespan is None and r.entries == []
    d = r.to_dict()
    assert d["makespan"] is None and d["schedule"] == [] and d["bounds"] == {} and min(motions) in d["reason"]


def test_unreachable_goal():
    problem = build([("m", ["a"], ["g"])], ["k"])
    tree = TaskTree(goal=goal_id(problem, "g"), method="given", status="unreachable")
    for together in (False, True):
        r = schedule(problem, tree, joint=together)
        assert r.status == "unreachable" and r.to_dict()["makespan"] is None


def test_goal_in_the_kitchen_takes_no_time():
    problem = build([("m", ["k"], ["g"])], ["k", "g"])
    r = schedule(problem, given(problem, goal_id(problem, "g"), []))
    assert r.status == "optimal" and r.makespan == 0 and r.entries == []


def test_an_object_made_twice_is_had_when_the_first_maker_ends():
    """As the rib tree of ../shared/foon: the last unit makes again what the second one needs."""
    problem = build(
        [
            ("put", ["k"], ["tray"]),
            ("bake", ["tray"], ["baked"]),
            ("take", ["baked"], ["g", "tray"]),
        ],
        ["k"],
    )
    g = goal_id(problem, "g")
    tree = given(problem, g, [0, 1, 2])
    spec = ScheduleSpec((("arm", 2),))
    for encoding in ENCODINGS:
        r = schedule(problem, tree, spec, encoding=encoding, shortcut=False)
        assert r.status == "optimal" and r.makespan == 3000
        assert check_schedule(problem, r.to_dict(), spec) is None
    assert brute_schedule(problem, [0, 1, 2], spec) == (3000, 0)


def test_zero_durations_do_not_support_each_other():
    """Units of duration 0 at one instant still fire in an order (no mutual support)."""
    problem = build(
        [("a", ["k"], ["x"]), ("b", ["x"], ["y"]), ("c", ["y"], ["g", "x"])],
        ["k"],
    )
    spec = ScheduleSpec((("arm", 2),), Durations({"a": 0, "b": 0, "c": 1000}))
    tree = given(problem, goal_id(problem, "g"), [0, 1, 2])
    for encoding in ENCODINGS:
        r = schedule(problem, tree, spec, encoding=encoding, shortcut=False)
        assert r.status == "optimal" and r.makespan == 1000
        assert check_schedule(problem, r.to_dict(), spec) is None


def test_fewest_human_units_break_ties():
    problem = build([("m", ["k"], ["a"]), ("m", ["k"], ["b"]), ("m", ["a", "b"], ["g"])], ["k"])
    spec = ScheduleSpec((("arm", 1), ("human", 1)), Durations({"m": 1000}, {"human": {"m": 1000}}))
    tree = given(problem, goal_id(problem, "g"), [0, 1, 2])
    for encoding in ENCODINGS:
        r = schedule(problem, tree, spec, encoding=encoding, shortcut=False)
        assert (r.makespan, len(r.human)) == (2000, 1) == brute_schedule(problem, [0, 1, 2], spec)
        assert r.success() == pytest.approx(0.5**2)  # the person's unit succeeds for sure


def test_time_limit_gives_a_feasible_schedule():
    rng = random.Random(3)
    problem, goal, units = random_tree(rng, 7, knife=0.0)
    spec = ScheduleSpec((("arm", 2),), Durations({"chop": 1500, "pour": 2500, "mix": 1000}))
    r = schedule(problem, given(problem, goal, units), spec, time_limit=0.0, shortcut=False)
    assert r.status in ("feasible", "optimal") and r.makespan <= r.baseline
    assert check_schedule(problem, r.to_dict(), spec) is None


# ---------------------------------------------------------------- joint


def longer_tree_shorter_chain():
    """g from a 3-unit chain, or from 4 units: three independent ones and a join."""
    chain = [("k", "a1"), ("a1", "a2"), ("a2", "g")]
    join = [("k", "b1"), ("k", "b2"), ("k", "b3")]
    units = [("m", [i], [o]) for i, o in chain + join]
    return build([*units, ("m", ["b1", "b2", "b3"], ["g"])], ["k"])


JOINT_WAYS = {
    "tree by tree": None,
    "tree by tree, least work first": lambda mp: mp.setattr(joint, "candidate_trees", lambda *a, **k: ([], False)),
    "one encoding": lambda mp: mp.setattr(solve_mod, "_by_trees", lambda *a, **k: (None, False, None)),
}


@pytest.mark.parametrize("encoding, way", [(e, w) for e in ENCODINGS for w in JOINT_WAYS])
def test_joint_is_strictly_shorter_with_a_larger_tree(encoding, way, monkeypatch):
    if JOINT_WAYS[way]:
        JOINT_WAYS[way](monkeypatch)
    problem = longer_tree_shorter_chain()
    g = goal_id(problem, "g")
    _, smallest = best(problem, g, lambda m: m["units"])
    tree = given(problem, g, list(smallest[0]))
    assert len(tree.units) == 3
    spec = ScheduleSpec((("arm", 3),))
    r = schedule(problem, tree, spec, joint=True, encoding=encoding, shortcut=False)
    assert r.status == "optimal" and r.joint
    assert r.makespan == 2000 < r.fixed.makespan == 3000
    assert sorted(r.tree.units) == [3, 4, 5, 6]
    d = r.to_dict()
    assert d["fixed_tree"] == {"status": "optimal", "makespan": 3.0, "units": 3} and d["joint"] is True
    assert check_schedule(problem, d, spec) is None
    # one arm: the smaller tree is as short, and the tree objective (units) breaks the tie
    r1 = schedule(problem, tree, ScheduleSpec(), joint=True, encoding=encoding, shortcut=False)
    assert r1.makespan == 3000 and sorted(r1.tree.units) == [0, 1, 2]


def test_joint_search_stops_bounding_trees_when_the_time_is_up():
    """The trees' bounds count against the time: none is bounded, or scheduled, after it is up."""
    times = iter([1.0, 1.0, 0.0])
    bounded: list = []

    def bound(cand):
        bounded.append(cand)
        return (0, 0, ())

    def never(*args):
        raise AssertionError("no tree is scheduled once the time is up")

    trees = [((i,), ()) for i in range(5)]
    search = joint.JointSearch(never, lambda r: (0,), bound, lambda: next(times))
    assert search.over(trees) == (None, False)
    assert bounded == trees[:2]


def random_choice_foon(rng: random.Random):
    """A small FOON with choice: g needs x and y, each made two ways (one or two units)."""
    units = [("m", ["x", "y"], ["g"])]
    for obj in ("x", "y"):
        units.append((rng.choice(MOTIONS), ["k0"], [obj]))
        units.append((rng.choice(MOTIONS), ["k1"], [obj + "1"]))
        units.append((rng.choice(MOTIONS), [obj + "1"], [obj]))
    return build(units, ["k0", "k1"])


@pytest.mark.parametrize("seed, way", [(s, list(JOINT_WAYS)[s % 3]) for s in range(12)])
def test_joint_equals_brute_force_over_every_tree(seed, way, monkeypatch):
    """Tree by tree (foon2asp.schedule.joint): the trees listed, or asked for least work
    first; and tree and schedule in one encoding."""
    if JOINT_WAYS[way]:
        JOINT_WAYS[way](monkeypatch)
    rng = random.Random(100 + seed)
    problem = random_choice_foon(rng)
    g = goal_id(problem, "g")
    kinds = AGENT_SETS[seed % 3]
    spec = random_spec(rng, kinds)
    spec = ScheduleSpec(spec.agents, spec.durations, {}, {})
    # a schedule's first makers of what is needed form a tree of their own, as short: with one
    # product per unit, the trees where no object has two makers suffice
    trees = [t for t in brute_force(problem, g) if len({o for u in t for o in problem.products[u]}) == len(t)]
    want = min(brute_schedule(problem, t, spec)[0] for t in trees)
    _, smallest = best(problem, g, lambda m: m["units"])
    tree = given(problem, g, list(smallest[0]))
    for encoding in ENCODINGS:
        r = schedule(problem, tree, spec, joint=True, encoding=encoding, shortcut=False)
        assert r.status == "optimal" and r.makespan == want, encoding
        # one agent: least work first, unless the way forced is the one encoding
        one = len(spec.agent_list()) == 1 and way != "one encoding"
        assert r.stats["joint"] == ("tree by tree, least work first" if one else way) or spec.has_human()
        assert r.makespan <= r.fixed.makespan == brute_schedule(problem, tree.units, spec)[0]
        assert check_schedule(problem, r.to_dict(), spec) is None


def tangled_foon(rng: random.Random):
    """A small FOON with choice, units of two products, objects made by several units (also
    by units every tree holds) and cycles: kitchen k0, k1; objects a, b, c; goal g."""
    made = ["a", "b", "c"]
    while True:
        units = []
        for _ in range(rng.randint(5, 6)):
            ins = rng.sample(["k0", "k1", *made], rng.randint(1, 2))
            outs = rng.sample([o for o in [*made, "g"] if o not in ins], rng.randint(1, 2))
            units.append((rng.choice(MOTIONS), ins, outs))
        if not any("g" in outs for _, _, outs in units):
            continue
        problem = build(units, ["k0", "k1"])
        g = goal_id(problem, "g")
        trees = brute_force(problem, g)
        if len(trees) >= 2 and max(len(t) for t in trees) <= 5:
            return problem, g, trees


@pytest.mark.parametrize("seed", range(16))
def test_joint_over_tangled_foons_equals_brute_force(seed, monkeypatch):
    """Every valid tree scheduled by brute force: the joint answer has the least makespan,
    then the fewest human units, then the fewest units; tree by tree and the one encoding agree."""
    rng = random.Random(500 + seed)
    problem, g, trees = tangled_foon(rng)
    kinds = AGENT_SETS[seed % 3]
    spec = random_spec(rng, kinds)
    spec = ScheduleSpec(spec.agents, spec.durations, spec.capabilities, {})
    scored = [(brute_schedule(problem, t, spec), len(t)) for t in trees]
    scored = [(ms, human, n) for (k, n) in scored if k is not None for ms, human in [k]]
    smallest = min(trees, key=len)
    tree = given(problem, g, list(smallest))
    answers = []
    for way in ("tree by tree", "one encoding"):
        with monkeypatch.context() as mp:
            if JOINT_WAYS[way]:
                JOINT_WAYS[way](mp)
            r = schedule(problem, tree, spec, joint=True, shortcut=False)
        if not scored or min(scored)[0] == math.inf:
            assert r.status == "unschedulable", way
            continue
        assert r.status == "optimal", (way, r.stats)
        assert (r.makespan, len(r.human), len(r.tree.units)) == min(scored), way
        assert check_schedule(problem, r.to_dict(), spec) is None
        answers.append(r.makespan)
    assert len(set(answers)) <= 1


def forbidding_case(seed: int):
    """A tangled FOON, a spec, and constraints that cut its best joint tree: a motion of that
    tree forbidden (and sometimes a cap on the units), some tree still allowed; also the best
    answer without the constraints."""
    rng = random.Random(700 + seed)
    while True:
        problem, g, trees = tangled_foon(rng)
        spec = random_spec(rng, AGENT_SETS[1 + seed % 2])  # two arms, or an arm and a person
        spec = ScheduleSpec(spec.agents, spec.durations, {}, {})
        scored = {t: brute_schedule(problem, t, spec) for t in trees}
        free = min(((*k, len(t), t) for t, k in scored.items() if k is not None), default=None)
        if free is None:
            continue
        motion = rng.choice(sorted({problem.units[u].motion for u in free[3]}))
        most = rng.choice([None, None, len(free[3]), len(free[3]) + 1])
        allowed = [
            t
            for t in trees
            if scored[t] is not None
            and all(problem.units[u].motion != motion for u in t)
            and (most is None or len(t) <= most)
        ]
        if allowed:
            want = min((*scored[t], len(t)) for t in allowed)
            return problem, g, spec, motion, most, allowed, want, free[:3]


@pytest.mark.parametrize("seed", range(16))
def test_joint_under_forbidding_constraints_equals_brute_force(seed, monkeypatch):
    """--forbid-motion and --max-units: tree by tree and the one encoding (the constraints as
    programs) agree with brute force over the allowed trees."""
    problem, g, spec, motion, most, allowed, want, _ = forbidding_case(seed)
    options = AspOptions(
        programs=constraints.ConstraintSpec(forbid_motion=(motion.upper(),), max_units=most).programs()
    )
    tree = given(problem, g, list(min(allowed, key=len)))
    for way in ("tree by tree", "one encoding"):
        with monkeypatch.context() as mp:
            if JOINT_WAYS[way]:
                JOINT_WAYS[way](mp)
            r = schedule(problem, tree, spec, joint=True, shortcut=False, options=options)
        assert r.status == "optimal", (way, r.stats)
        assert r.stats["joint"] == way or spec.has_human(), (way, r.stats)  # a person: ties, one encoding
        assert (r.makespan, len(r.human), len(r.tree.units)) == want, way
        assert all(problem.units[u].motion != motion for u in r.tree.units)
        assert most is None or len(r.tree.units) <= most


def test_joint_with_a_forbidden_object_or_a_required_motion():
    """Forbidding b2 leaves only the chain; requiring a motion keeps the larger tree; both tree
    by tree."""
    problem = longer_tree_shorter_chain()
    g = goal_id(problem, "g")
    tree = given(problem, g, [0, 1, 2])
    spec = ScheduleSpec((("arm", 3),))
    free = schedule(problem, tree, spec, joint=True, shortcut=False)
    assert free.makespan == 2000 and sorted(free.tree.units) == [3, 4, 5, 6]
    no_b2 = AspOptions(programs=constraints.ConstraintSpec(forbid_object=("B2",)).programs())
    r = schedule(problem, tree, spec, joint=True, shortcut=False, options=no_b2)
    assert r.status == "optimal" and r.makespan == 3000 and sorted(r.tree.units) == [0, 1, 2]
    assert r.stats["joint"] == "tree by tree"
    need_m = AspOptions(programs=constraints.ConstraintSpec(require_motion=("m",)).programs())
    r = schedule(problem, tree, spec, joint=True, shortcut=False, options=need_m)
    assert r.status == "optimal" and r.makespan == 2000 and r.stats["joint"].startswith("tree by tree")


def test_forbidding_cases_bite():
    """The cases above are not trivial: a tree the constraints forbid is the best without them,
    and in some the best allowed one is worse."""
    cases = [forbidding_case(seed) for seed in range(16)]
    assert sum(case[6] > case[7] for case in cases) >= 4


@pytest.mark.parametrize("way", list(JOINT_WAYS))
def test_joint_adds_an_earlier_maker_of_what_a_needed_unit_makes(way, monkeypatch):
    """p (slow) makes x and y and is in every tree; q makes x sooner: the tree with q as well
    is one unit larger and one second shorter on two arms."""
    if JOINT_WAYS[way]:
        JOINT_WAYS[way](monkeypatch)
    problem = build(
        [
            ("slow", ["k"], ["x", "y"]),
            ("fast", ["k"], ["x"]),
            ("m", ["x"], ["z"]),
            ("m", ["y", "z"], ["g"]),
        ],
        ["k"],
    )
    g = goal_id(problem, "g")
    spec = ScheduleSpec((("arm", 2),), Durations({"slow": 3000, "fast": 1000, "m": 1000}))
    tree = given(problem, g, [0, 2, 3])
    assert brute_schedule(problem, [0, 2, 3], spec) == (5000, 0)
    assert brute_schedule(problem, [0, 1, 2, 3], spec) == (4000, 0)
    r = schedule(problem, tree, spec, joint=True, shortcut=False)
    assert r.status == "optimal" and r.makespan == 4000 and r.fixed.makespan == 5000
    assert sorted(r.tree.units) == [0, 1, 2, 3]
    assert check_schedule(problem, r.to_dict(), spec) is None


def test_joint_avoids_a_unit_nobody_can_do():
    # the arm cannot cut: the smallest tree is unschedulable, joint takes the other one
    chain = build(
        [("m", ["k"], ["a1"]), ("cut", ["a1"], ["g"]), ("m", ["k"], ["b1"]), ("m", ["b1"], ["g"])],
        ["k"],
    )
    g2 = goal_id(chain, "g")
    spec2 = ScheduleSpec((("arm", 1),), capabilities={"arm": frozenset({"m"})})
    r = schedule(chain, given(chain, g2, [0, 1]), spec2, joint=True)
    assert r.fixed.status == "unschedulable" and r.status == "optimal" and sorted(r.tree.units) == [2, 3]
    assert check_schedule(chain, r.to_dict(), spec2) is None


def test_joint_rejects_the_depth_objective():
    from foon2asp.asp.options import AspOptions
    from foon2asp.errors import InputError

    problem = longer_tree_shorter_chain()
    tree = given(problem, goal_id(problem, "g"), [0, 1, 2])
    with pytest.raises(InputError, match="joint scheduling"):
        schedule(problem, tree, joint=True, options=AspOptions(objective=("depth",)))


# ---------------------------------------------------------------- labels stay data


def test_labels_with_quotes_and_asp_text_stay_data():
    odd = 'knife "x"). #show. \\ :- a.'
    problem = build(
        [
            ('cut "it").', ["k", (odd,)], ["a"]),
            ('cut "it").', ["k", (odd,)], ["b"]),
            ("mix", ["a", "b"], ["g"]),
        ],
        ["k", (odd,)],
    )
    spec = ScheduleSpec((("arm", 2),), resources={as_obj((odd,)).label: 1})
    tree = given(problem, goal_id(problem, "g"), [0, 1, 2])
    for encoding in ENCODINGS:
        r = schedule(problem, tree, spec, encoding=encoding, shortcut=False)
        assert r.status == "optimal" and r.makespan == 3000  # the odd knife is one: the cuts take turns
        assert check_schedule(problem, r.to_dict(), spec) is None


# ---------------------------------------------------------------- ../shared/foon


def test_both_encodings_agree_on_shared_goals(shared_foon_dir):
    import foon2asp

    kb = foon2asp.load(shared_foon_dir)
    spec = ScheduleSpec((("arm", 2),))
    for label in ("greek salad", "macaroni and cheese", "coleslaw", "rib"):
        tree = kb.solve(label).raw
        got = {}
        for encoding in ENCODINGS:
            r = schedule(kb.problem, tree, spec, encoding=encoding, shortcut=False, time_limit=60)
            assert r.status == "optimal", (label, encoding)
            assert check_schedule(kb.problem, r.to_dict(), spec) is None
            got[encoding] = r.makespan
        assert len(set(got.values())) == 1, (label, got)


def remade_tree(rng: random.Random, n: int):
    """A FOON of n units where unit i makes p_i from earlier products, and sometimes makes an
    earlier product again (an object with two makers in the tree, one of which may wait for
    the unit that needs it); returns (problem, goal, units): every unit in the tree."""
    units = []
    for i in range(n):
        ins = [f"p{j}" for j in range(i) if rng.random() < 0.5] or ["k"]
        outs = [f"p{i}"]
        if i >= 2 and rng.random() < 0.5:
            outs.append(f"p{rng.randrange(i - 1)}")
        units.append((rng.choice(MOTIONS), ins, outs))
    units.append(("mix", [f"p{j}" for j in range(n)], ["g"]))
    problem = build(units, ["k"])
    return problem, goal_id(problem, "g"), list(range(n + 1))


def test_a_maker_that_waits_for_the_consumer_cannot_supply_it():
    from foon2asp.schedule.instances import instance, tails

    # B needs p, made by A and by C; C needs what B makes, so B must wait for A
    problem = build([("a", ["k"], ["p"]), ("b", ["p"], ["q"]), ("c", ["q"], ["p"]), ("d", ["p", "q"], ["g"])], ["k"])
    inst = instance(problem, [0, 1, 2, 3], ScheduleSpec())
    assert inst.preds == {0: (), 1: (0,), 2: (1,), 3: (1,)}
    assert tails(inst)[0] == 3000  # a, b, then c or d


@pytest.mark.parametrize("seed", range(24))
def test_objects_made_twice_keep_bounds_and_optimum_exact(seed):
    """Precedence through a maker that waits for the consumer (Instance.preds) tightens the
    bounds; they stay below the brute-force optimum, and the optimum equals it."""
    from foon2asp.schedule.instances import instance
    from foon2asp.schedule.lower_bounds import bounds

    rng = random.Random(300 + seed)
    problem, goal, units = remade_tree(rng, 4)
    kinds = ((("arm", 2),), (("arm", 1), ("human", 1)), (("arm", 3),))[seed % 3]
    spec = random_spec(rng, kinds)
    spec = ScheduleSpec(spec.agents, spec.durations, {}, spec.resources)
    want = brute_schedule(problem, units, spec)
    assert want is not None
    assert bounds(instance(problem, units, spec)).lower <= want[0]
    for encoding in ENCODINGS:
        r = schedule(problem, given(problem, goal, units), spec, encoding=encoding, shortcut=False)
        assert r.status == "optimal" and (r.makespan, len(r.human)) == want, encoding
        assert check_schedule(problem, r.to_dict(), spec) is None


def test_every_tree_bound_is_at_most_every_trees_optimal_makespan():
    """The joint search's floor (landmarks and energetic reasoning over every candidate unit)
    never exceeds the least makespan of any tree, each scheduled by brute force."""
    from foon2asp.schedule.instances import earliest, instance
    from foon2asp.schedule.joint import every_tree_bound

    positive = 0
    for seed in range(16):
        rng = random.Random(500 + seed)
        problem, g, trees = tangled_foon(rng)
        spec = random_spec(rng, AGENT_SETS[seed % 3])
        spec = ScheduleSpec(spec.agents, spec.durations, spec.capabilities, {})
        made = [k[0] for k in (brute_schedule(problem, t, spec) for t in trees) if k is not None]
        inst = instance(problem, problem.units_for((g,)), spec)
        bound = every_tree_bound(inst, (g,), problem.products, earliest(inst), 0)
        assert made and bound <= min(made), (seed, bound, made)
        positive += bound > 0
    assert positive >= 10
