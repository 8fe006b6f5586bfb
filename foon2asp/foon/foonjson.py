"""FOON JSON: the schema of foon_api (``FOON_graph_analyser``), which FOON_view also reads.

.. code-block:: text

    {"functional_units": [
      {"input_nodes": [{"object_id": 12, "object_label": "bowl",
                        "object_states": [{"state_id": 23, "state_label": "contains"},
                                          {"state_id": 65, "state_label": "in", "relative_object": "pot"}],
                        "ingredients": ["onion"], "object_in_motion": "0"}, ...],
       "motion_node": {"motion_id": 54, "motion_label": "pour", "start_time": "Assumed", "end_time": "Assumed"},
       "output_nodes": [...]}, ...]}

The ingredients are the state ``contains`` plus the list ``ingredients``; the container is
the state ``in`` with ``relative_object``; another relation is kept as the state ``"on
[plate]"``.  :func:`parse_json` also reads foon2asp's ``{motion, inputs, outputs}`` units
and ``solve --format json`` results, so every JSON written here can serve as a FOON.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Protocol

from foon2asp.errors import InputError
from foon2asp.foon.model import Foon, FoonObject, Unit, norm

#: what the official tools write for times and the in-motion flag
ASSUMED = "Assumed"


class Ids(Protocol):
    """What :class:`foon2asp.foon.parser.IdMap` offers: one id per object label, state name, motion."""

    def get(self, kind: str, text: str) -> int: ...


def _relation(state: str) -> tuple[str, str | None]:
    """``"on [plate]"`` -> ``("on", "plate")``; ``"seasoned {salt}"`` keeps its braces."""
    if state.endswith("]") and " [" in state:
        name, _, arg = state.partition(" [")
        return name, arg[:-1]
    if state.endswith("}") and " {" in state:
        name, _, arg = state.partition(" {")
        return name, "{" + arg
    return state, None


def object_json(obj: FoonObject, ids: Ids) -> dict:
    """One node in foon_api's schema (``ids``: an :class:`~foon2asp.foon.parser.IdMap`)."""
    states = []
    for state in obj.states:
        name, rel = _relation(state)
        entry: dict = {"state_id": ids.get("S", name), "state_label": name}
        if rel is not None:
            entry["relative_object"] = rel
        states.append(entry)
    if obj.ingredients:
        states.append({"state_id": ids.get("S", "contains"), "state_label": "contains"})
    if obj.container:
        states.append({"state_id": ids.get("S", "in"), "state_label": "in", "relative_object": obj.container})
    return {
        "object_id": ids.get("O", obj.label),
        "object_label": obj.label,
        "object_states": states,
        "ingredients": list(obj.ingredients),
        "object_in_motion": "0",
    }


def unit_json(unit: Unit, ids: Ids) -> dict:
    return {
        "input_nodes": [object_json(o, ids) for o in unit.inputs],
        "motion_node": {
            "motion_id": ids.get("M", unit.motion),
            "motion_label": unit.motion,
            "start_time": ASSUMED,
            "end_time": ASSUMED,
        },
        "output_nodes": [object_json(o, ids) for o in unit.outputs],
    }


def to_foon_json(units: Iterable[Unit], ids: Ids, header: str | None = None) -> dict:
    """``{"functional_units": [...]}`` for ``units`` (``header`` goes to ``"comment"``)."""
    out: dict = {}
    if header:
        out["comment"] = header
    out["functional_units"] = [unit_json(u, ids) for u in units]
    return out


def dumps(units: Iterable[Unit], ids: Ids, header: str | None = None) -> str:
    return json.dumps(to_foon_json(units, ids, header), indent=1) + "\n"


# ---------------------------------------------------------------- reading


def _need(cond: bool, message: str, path: str, where: str) -> None:
    if not cond:
        raise InputError(f"{where}: {message}", path)


def _read_node(node: object, path: str, where: str, foon: Foon) -> FoonObject:
    _need(isinstance(node, dict), "expected an object node {object_label, object_states, ingredients}", path, where)
    assert isinstance(node, dict)
    label = node.get("object_label")
    _need(isinstance(label, str) and bool(label.strip()), "object node without an 'object_label' string", path, where)
    assert isinstance(label, str)
    if isinstance(node.get("object_id"), int | str) and str(node["object_id"]).strip().lstrip("-").isdigit():
        foon.ids["O"].setdefault(norm(label), int(node["object_id"]))
    states: list[str] = []
    container: str | None = None
    raw_states = node.get("object_states", [])
    _need(isinstance(raw_states, list), f"'object_states' of {label!r} must be a list", path, where)
    ingredients = node.get("ingredients", [])
    _need(
        isinstance(ingredients, list) and all(isinstance(i, str) for i in ingredients),
        f"'ingredients' of {label!r} must be a list of strings",
        path,
        where,
    )
    has_contents = bool(ingredients)
    for st in raw_states:
        _need(
            isinstance(st, dict) and isinstance(st.get("state_label"), str),
            f"a state of {label!r} has no 'state_label'",
            path,
            where,
        )
        name = st["state_label"].strip()
        if isinstance(st.get("state_id"), int | str) and str(st["state_id"]).strip().lstrip("-").isdigit():
            foon.ids["S"].setdefault(norm(name), int(st["state_id"]))
        rel = st.get("relative_object")
        if name.lower() in ("contains", "ingredients") and rel is None and has_contents:
            has_contents = False  # the list 'ingredients' holds them
            continue
        if rel is None:
            states.append(name)
        elif not isinstance(rel, str):
            raise InputError(f"{where}: 'relative_object' of {label!r} must be a string", path)
        elif name.lower() == "in":
            inner = rel.strip().strip("[]").strip()
            if container is not None and container != inner:
                raise InputError(f"{where}: object {label!r} is in two containers [{container}] and [{inner}]", path)
            container = inner
        elif rel.strip().startswith("{"):
            states.append(f"{name} {rel.strip()}")
        else:
            states.append(f"{name} [{rel.strip().strip('[]').strip()}]")
    return FoonObject.make(label, states, ingredients, container)


def _read_official(data: dict, path: str, foon: Foon) -> Foon:
    units = data["functional_units"]
    _need(isinstance(units, list), "'functional_units' must be a list", path, "file")
    for k, fu in enumerate(units, 1):
        where = f"functional unit {k}"
        _need(isinstance(fu, dict), "expected an object with input_nodes, motion_node, output_nodes", path, where)
        motion = fu.get("motion_node")
        _need(
            isinstance(motion, dict) and isinstance(motion.get("motion_label"), str),
            "no 'motion_node' with a 'motion_label'",
            path,
            where,
        )
        label = norm(motion["motion_label"]).rstrip("*").strip()
        _need(bool(label), "empty motion label", path, where)
        if str(motion.get("motion_id", "")).strip().lstrip("-").isdigit():
            foon.ids["M"].setdefault(label, int(motion["motion_id"]))
        sides = _sides(fu, ("input_nodes", "output_nodes"), lambda n, p, w: _read_node(n, p, w, foon), path, where)
        _need(bool(sides[0]), "a functional unit without input nodes", path, where)
        foon.add_unit(Unit(label, sides[0], sides[1]), (path, k))
    return foon


def _sides(
    unit: dict, keys: tuple[str, str], read: Callable[[object, str, str], FoonObject], path: str, where: str
) -> list[tuple[FoonObject, ...]]:
    """The objects of the two lists ``keys`` of ``unit`` (inputs, outputs), each read by
    ``read(value, path, where)``."""
    sides = []
    for side in keys:
        items = unit.get(side)
        _need(isinstance(items, list), f"no '{side}' list", path, where)
        assert isinstance(items, list)
        sides.append(tuple(read(o, path, where) for o in items))
    return sides


def _lab_object(value: object, path: str, where: str) -> FoonObject:
    _need(
        isinstance(value, dict) and isinstance(value.get("label"), str),
        "expected an object {label, states, ingredients, container}",
        path,
        where,
    )
    assert isinstance(value, dict)
    states = value.get("states") or []
    ingredients = value.get("ingredients") or []
    container = value.get("container")
    for name, items in (("states", states), ("ingredients", ingredients)):
        _need(
            isinstance(items, list) and all(isinstance(x, str) for x in items),
            f"'{name}' of {value['label']!r} must be a list of strings",
            path,
            where,
        )
    _need(container is None or isinstance(container, str), "'container' must be a string or null", path, where)
    return FoonObject.make(value["label"], states, ingredients, container)


def _lab_units(data: object) -> list | None:
    """The units of the lab's JSON: a list of units, one result, or a list of results."""
    if isinstance(data, dict) and isinstance(data.get("units"), list):
        return data["units"]
    if isinstance(data, list):
        if all(isinstance(x, dict) and "motion" in x for x in data):
            return data
        if all(isinstance(x, dict) and isinstance(x.get("units"), list) for x in data):
            return [u for x in data for u in x["units"]]
    return None


def parse_json(text: str, path: str = "<string>", foon: Foon | None = None) -> Foon:
    """FOON JSON (foon_api's schema, or the lab's units) into ``foon`` (a new one by default)."""
    foon = foon if foon is not None else Foon()
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"bad JSON: {exc.msg}", path, exc.lineno) from None
    if isinstance(data, dict) and "functional_units" in data:
        return _read_official(data, path, foon)
    if isinstance(data, list) and data and all(isinstance(d, dict) and "functional_units" in d for d in data):
        for doc in data:  # several trees (solve --format foon-json with several goals)
            _read_official(doc, path, foon)
        return foon
    units = _lab_units(data)
    if units is None:
        raise InputError(
            'expected FOON JSON ({"functional_units": [...]}), a list of units {motion, inputs, outputs}'
            " or a list of units {input_nodes, motion_node, output_nodes}",
            path,
        )
    for k, u in enumerate(units, 1):
        where = f"unit {k}"
        _need(isinstance(u, dict) and isinstance(u.get("motion"), str), "no 'motion' string", path, where)
        sides = _sides(u, ("inputs", "outputs"), _lab_object, path, where)
        _need(bool(sides[0]), "a unit without inputs", path, where)
        foon.add_unit(Unit(norm(u["motion"]).rstrip("*").strip(), sides[0], sides[1]), (path, k))
    return foon


def looks_like_json(path: str | Path, head: str) -> bool:
    """Is this FOON file JSON (by extension, else by its first character)?"""
    return str(path).lower().endswith(".json") or head.lstrip()[:1] in ("{", "[")
