"""The answers of the explorer page as JSON values, each from one library call on the knowledge
base: the proven tree, what to buy when there is none, the search baselines beside it, its
schedule, and its exports."""

from __future__ import annotations

import json
import re
from collections import OrderedDict

from foon2asp import api
from foon2asp.api.goal_parts import relevant_part, without_kitchen_items
from foon2asp.errors import InputError
from foon2asp.explore.params import Question
from foon2asp.explore.settings import Setup
from foon2asp.report import draw, pddl

#: the search baselines shown beside the proven tree, in order
BASELINES = ("ids", "gbfs-h1", "gbfs-h2")
#: the exports of the tree on screen: format -> (file name, media type)
EXPORTS = {
    "foon": ("task-tree.txt", "text/plain; charset=utf-8"),
    "json": ("task-tree.json", "application/json"),
    "svg": ("task-tree.svg", "image/svg+xml"),
    "pddl-domain": ("domain.pddl", "text/plain; charset=utf-8"),
    "pddl-problem": ("problem.pddl", "text/plain; charset=utf-8"),
}
#: kitchens without some items kept at once (each a knowledge base of its own)
KITCHENS_KEPT = 8
#: the library's hints worded for the page (foon2asp.errors.InputError.hint)
HINT_WORDING = {
    "motion-cost": "the objective 'cost' needs a motion-cost table: start the explorer with --motion-cost FILE",
}


def error_line(exc: InputError) -> str:
    """The one line the page shows for ``exc``: the command line's message, or the page's wording of its hint."""
    key = (exc.hint or "").partition("=")[0]
    return HINT_WORDING.get(key, str(exc))


def steps(tree: api.Tree) -> list[dict]:
    """The tree's units in executable order: motion, inputs and outputs as texts, the FOON unit id,
    and whether a person does it."""
    human = set(tree.to_dict().get("human_steps", ()))
    return [
        {
            "unit": uid,
            "motion": unit.motion,
            "inputs": [o.text for o in unit.inputs],
            "outputs": [o.text for o in unit.outputs],
            "human": uid in human,
        }
        for uid, unit in zip(tree.unit_ids, tree.units)
    ]


def picture(tree: api.Tree, prefix: str) -> str | None:
    """The tree's drawing as an SVG element for the page (ids start with ``prefix``); None without a tree."""
    if not tree.has_tree or not tree.units:
        return None
    return draw.inline_svg(str(tree.render("svg")), prefix)


def distance(found: dict, best: dict) -> dict:
    """How far ``found``'s measures are from the optimum's ``best``: differences, and for
    ``success`` the ratio (1: as likely to succeed)."""
    out: dict[str, float | None] = {}
    for name, value in best.items():
        if found.get(name) is None or value is None:
            continue
        if name == "success":
            out[name] = round(found[name] / value, 6) if value else None
        else:
            out[name] = round(found[name] - value, 6)
    return out


class Answers:
    """The answers of one knowledge base (loaded once, from ``setup``)."""

    def __init__(self, setup: Setup) -> None:
        self.setup = setup
        self.kb = setup.load()
        self._kitchens: OrderedDict[frozenset[str], api.KnowledgeBase] = OrderedDict()

    def answer(self, panel: str, question: Question, fmt: str | None = None) -> dict:
        """The answer ``panel`` (``tree``, ``missing``, ``baselines``, ``schedule`` or ``export``) to ``question``."""
        if question.goal is None:
            raise InputError("no goal given: name one in the goal box (goal=TEXT)")
        goal = self.kb.object_id(question.goal)  # one object, named as --goal names it
        if panel == "tree":
            return self.tree(question, goal)
        if panel == "baselines":
            return self.baselines(question, goal)
        if panel == "schedule":
            return self.schedule(question, goal)
        if panel == "missing":
            return self.missing(question, goal)
        if panel == "export" and fmt in EXPORTS:
            return self.export(question, goal, fmt)
        raise InputError(f"unknown answer {panel!r} {fmt or ''}".strip())

    def knowledge(self, question: Question) -> api.KnowledgeBase:
        """The knowledge base with the kitchen the question leaves (one made per kitchen, a few kept)."""
        key = frozenset(question.without)
        if not key:
            return self.kb
        if key in self._kitchens:
            self._kitchens.move_to_end(key)
            return self._kitchens[key]
        kb = self._kitchens[key] = without_kitchen_items(self.kb, question.without)
        while len(self._kitchens) > KITCHENS_KEPT:
            self._kitchens.popitem(last=False)
        return kb

    def request(self, question: Question) -> api.Options:
        """The library's request of the question, with the settings every answer shares."""
        return api.Options.of(**question.settings(self.setup.time_limit, self.setup.shared()))

    def tree(self, question: Question, goal: int) -> dict:
        """The proven tree: status, what proved it, its measures, steps and drawing, and the goal's
        relevant part (the choices of the page)."""
        kb = self.knowledge(question)
        solver, warnings = kb.options_and_warnings(self.request(question))
        tree = next(kb.solve_iter([goal], options=solver))
        found = tree.to_dict()
        part = relevant_part(self.kb, tree.goal_id)
        out = {
            "goal": {"id": tree.goal_id, "text": tree.goal.text, "label": tree.goal.label},
            "status": tree.status,
            "proven_by": tree.proven_by,
            "cost": tree.cost,
            "bound": tree.bound,
            "gap": tree.gap,
            "reason": found.get("reason"),
            "note": tree.note,
            "substitutions": tree.substitutions,
            "time_s": tree.time_s,
            "steps": steps(tree),
            "svg": picture(tree, "tree-"),
            "warnings": warnings,
            "part": {
                "units": part.units,
                "motions": list(part.motions),
                "kitchen": [{"text": o.text, "label": o.label} for o in part.kitchen],
            },
        }
        return out

    def missing(self, question: Question, goal: int) -> dict:
        """The fewest items to add to the question's kitchen so that the goal has a tree under its constraints."""
        kb = self.knowledge(question)
        bought = kb.missing(goal, options=kb.options(self.request(question)))
        return {"status": bought.status, "items": [o.text for o in bought.missing]}

    def baselines(self, question: Question, goal: int) -> dict:
        """IDS, GBFS-h1 and GBFS-h2 on the question's kitchen, each judged valid or not and set
        beside the proven optimum (the question's objective, without its constraints)."""
        kb = self.knowledge(question)
        seconds = question.time_limit or self.setup.time_limit
        settings = {"objective": question.objective, "time_limit": seconds, **self.setup.shared()}
        (_, row), *_ = kb.compare(goal, methods=(*BASELINES, "asp"), **settings).rows
        best = row["asp"]
        methods = []
        for name in BASELINES:
            tree = row[name]
            found = tree.to_dict()
            ours = set(best.unit_ids)
            methods.append(
                {
                    "method": name,
                    "status": tree.status,
                    "valid": tree.valid,
                    "problem": found.get("problem"),
                    "cost": tree.cost,
                    "distance": distance(tree.cost, best.cost) if tree.has_tree and best.has_tree else None,
                    "steps": steps(tree),
                    "differs": [k for k, u in enumerate(tree.unit_ids) if u not in ours],
                    "svg": picture(tree, f"{name}-"),
                    "time_s": tree.time_s,
                }
            )
        optimum = {"status": best.status, "cost": best.cost, "units": best.unit_ids}
        return {"optimum": optimum, "methods": methods}

    def schedule(self, question: Question, goal: int) -> dict:
        """The schedule of the tree on screen: its agents, each step's agent and times, the Gantt chart."""
        kb = self.knowledge(question)
        solver = kb.options(self.request(question))
        spec = self.setup.schedule_spec(question.agents)
        found = kb.schedule(goal, spec, options=solver)
        assert isinstance(found, api.Schedule)
        record = found.to_dict()
        position = {json.dumps(u.to_json()): k for k, u in enumerate(found.tree.units, 1)}
        rows = [
            {
                "step": position.get(json.dumps(e["unit"])),
                "motion": e["unit"]["motion"],
                "agent": e["agent"],
                "start": e["start"],
                "end": e["end"],
                "duration": round(e["end"] - e["start"], 3),
            }
            for e in found.entries
        ]
        svg = None
        if found.entries:
            svg = draw.inline_svg(str(found.render("svg")), "gantt-")
        return {
            "status": found.status,
            "makespan": found.makespan,
            "agents": found.agents,
            "baseline": (record.get("baseline") or {}).get("makespan"),
            "bounds": record.get("bounds"),
            "human_units": record.get("human_units"),
            "rows": rows,
            "svg": svg,
        }

    def export(self, question: Question, goal: int, fmt: str) -> dict:
        """The tree on screen (its goal's problem, for PDDL) as a file: its name, media type and text."""
        kb = self.knowledge(question)
        request = self.request(question)
        solver = kb.options(request)
        name, media = EXPORTS[fmt]
        if fmt.startswith("pddl"):
            objective = question.objective[0]
            if objective not in pddl.PDDL_OBJECTIVES:
                raise InputError(f"PDDL can state the objectives {', '.join(pddl.PDDL_OBJECTIVES)}, not {objective!r}")
            task = pddl.export(kb.solving_problem(solver), [goal], objective, request.constraints, "foon")
            text = task.domain if fmt == "pddl-domain" else task.problem
        else:
            tree = next(kb.solve_iter([goal], options=solver))
            if fmt == "svg" and not tree.units:
                raise InputError(f"no tree to draw: the goal is {tree.status}")
            text = str(tree.render(fmt))
        label = re.sub(r"[^A-Za-z0-9]+", "-", kb.object_info(goal)["label"]).strip("-")[:40] or "goal"
        return {"name": f"{label}-{name}", "media": media, "text": text}
