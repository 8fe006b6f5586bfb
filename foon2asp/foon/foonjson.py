"""FOON JSON: the schema of foon_api (``FOON_graph_analyser``), which FOON_view also reads.

.. code-block:: text

    {"functional_units": [
      {"input_nodes": [{"object_id": 12, "object_label": "bowl",
                        "object_states": [{"state_id": 23, "state_label": "contains"},
                                          {"state_id": 65, "state_label": "in", "relative_object": "pot"}],
                        "ingredients": ["onion"], "object_in_motion": "0"}, ...],
       "motion_node": {"motion_id": 54, "motion_label": "pour", "start_time": "Assumed", "end_time": "Assumed"},
       "output_nodes": [...]}, ...]}

The container is the state ``in`` with ``relative_object``; another relation is the state
``"on [plate]"``.  :func:`parse_json` also reads foon2asp's units and results.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from functools import partial
from typing import TYPE_CHECKING

from foon2asp.errors import InputError
from foon2asp.foon.model import Foon, FoonObject, Unit, motion_key, norm, state_parts
from foon2asp.foon.reading import scan

if TYPE_CHECKING:
    from foon2asp.foon.parser import IdMap

#: what the official tools write for times and the in-motion flag
ASSUMED = "Assumed"


def object_json(obj: FoonObject, ids: IdMap) -> dict:
    """One node in foon_api's schema."""
    states = []
    for state in obj.states:
        name, arg = state_parts(state)
        entry: dict = {"state_id": ids.get("S", name), "state_label": name}
        if arg is not None:
            entry["relative_object"] = arg[1:-1] if arg[0] == "[" else arg
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


def unit_json(unit: Unit, ids: IdMap) -> dict:
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


def to_foon_json(units: Iterable[Unit], ids: IdMap, header: str | None = None) -> dict:
    """``{"functional_units": [...]}`` for ``units`` (``header`` goes to ``"comment"``)."""
    out: dict = {"comment": header} if header else {}
    out["functional_units"] = [unit_json(u, ids) for u in units]
    return out


def dumps(units: Iterable[Unit], ids: IdMap, header: str | None = None) -> str:
    return json.dumps(to_foon_json(units, ids, header), indent=1) + "\n"


# ---------------------------------------------------------------- reading


def _keep_id(foon: Foon, kind: str, text: str, value: object) -> None:
    """Keep the id ``value`` of an official file for ``text`` (the first id seen wins)."""
    if isinstance(value, int | str) and str(value).strip().lstrip("-").isdigit():
        foon.ids[kind].setdefault(norm(text), int(value))


def _node(node: object, path: str, where: str, foon: Foon) -> FoonObject:
    """One object node of foon_api's schema."""
    if not isinstance(node, dict):
        raise InputError(f"{where}: expected an object node {{object_label, object_states, ingredients}}", path)
    label = node.get("object_label")
    if not isinstance(label, str) or not label.strip():
        raise InputError(f"{where}: object node without an 'object_label' string", path)
    _keep_id(foon, "O", label, node.get("object_id"))
    raw_states = node.get("object_states", [])
    ingredients = node.get("ingredients", [])
    if not isinstance(raw_states, list):
        raise InputError(f"{where}: 'object_states' of {label!r} must be a list", path)
    if not isinstance(ingredients, list) or not all(isinstance(i, str) for i in ingredients):
        raise InputError(f"{where}: 'ingredients' of {label!r} must be a list of strings", path)
    states: list[str] = []
    container: str | None = None
    has_contents = bool(ingredients)
    for st in raw_states:
        if not isinstance(st, dict) or not isinstance(st.get("state_label"), str):
            raise InputError(f"{where}: a state of {label!r} has no 'state_label'", path)
        name = st["state_label"].strip()
        _keep_id(foon, "S", name, st.get("state_id"))
        rel = st.get("relative_object")
        if name.lower() in ("contains", "ingredients") and rel is None and has_contents:
            has_contents = False  # the list 'ingredients' holds them
        elif rel is None:
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


def _sides(
    unit: dict, keys: tuple[str, str], read: Callable[[object], FoonObject], path: str, line: int | None, where: str
) -> list[tuple[FoonObject, ...]]:
    """The objects of the two lists ``keys`` of ``unit`` (inputs, outputs), each read by ``read``."""
    sides = []
    for side in keys:
        items = unit.get(side)
        if not isinstance(items, list):
            raise InputError(f"{where}: no '{side}' list", path, line)
        sides.append(tuple(read(o) for o in items))
    return sides


def is_foon_json(data: object) -> bool:
    """Is ``data`` (parsed JSON) one FOON JSON document?"""
    return isinstance(data, dict) and "functional_units" in data


def read_official(data: dict, path: str, foon: Foon | None = None) -> Foon:
    """The units of one FOON JSON document added to ``foon`` (a new one by default)."""
    foon = foon if foon is not None else Foon()
    units = data["functional_units"]
    if not isinstance(units, list):
        raise InputError("file: 'functional_units' must be a list", path)
    for k, fu in enumerate(units, 1):
        where = f"functional unit {k}"
        if not isinstance(fu, dict):
            raise InputError(f"{where}: expected an object with input_nodes, motion_node, output_nodes", path)
        motion = fu.get("motion_node")
        if not isinstance(motion, dict) or not isinstance(motion.get("motion_label"), str):
            raise InputError(f"{where}: no 'motion_node' with a 'motion_label'", path)
        label = motion_key(motion["motion_label"])
        if not label:
            raise InputError(f"{where}: empty motion label", path)
        _keep_id(foon, "M", label, motion.get("motion_id"))
        read = partial(_node, path=path, where=where, foon=foon)
        inputs, outputs = _sides(fu, ("input_nodes", "output_nodes"), read, path, None, where)
        if not inputs:
            raise InputError(f"{where}: a functional unit without input nodes", path)
        foon.add_unit(Unit(label, inputs, outputs), (path, k))
    return foon


def object_from_json(value: object, path: str, line: int | None = None, where: str | None = None) -> FoonObject:
    """An object from ``{label, states, ingredients, container}``; ``where`` starts the messages."""
    at = f"{where}: " if where else ""
    if not isinstance(value, dict):
        raise InputError(f"{at}expected an object {{label, states, ingredients, container}}", path, line)
    label = value.get("label")
    if not isinstance(label, str) or not label.strip():
        raise InputError(f"{at}object without a 'label' string", path, line)
    states = value.get("states") or []
    ingredients = value.get("ingredients") or []
    for name, items in (("states", states), ("ingredients", ingredients)):
        if not isinstance(items, list) or not all(isinstance(x, str) for x in items):
            raise InputError(f"{at}'{name}' of {label!r} must be a list of strings", path, line)
    container = value.get("container")
    if container is not None and not isinstance(container, str):
        raise InputError(f"{at}'container' of {label!r} must be a string or null", path, line)
    return FoonObject.make(label, states, ingredients, container)


def unit_from_json(value: object, path: str, where: str, line: int | None = None) -> Unit:
    """A unit ``{motion, inputs, outputs}`` as foon2asp writes it; ``where`` starts the messages."""
    if not isinstance(value, dict) or not isinstance(value.get("motion"), str):
        raise InputError(f"{where}: no 'motion' string", path, line)
    read = partial(object_from_json, path=path, line=line, where=where)
    inputs, outputs = _sides(value, ("inputs", "outputs"), read, path, line, where)
    return Unit(motion_key(value["motion"]), inputs, outputs)


def _lab_units(data: object) -> list | None:
    """The units of foon2asp's JSON: a list of units, one result, or a list of results."""
    if isinstance(data, dict) and isinstance(data.get("units"), list):
        return data["units"]
    if isinstance(data, list):
        if all(isinstance(x, dict) and "motion" in x for x in data):
            return data
        if all(isinstance(x, dict) and isinstance(x.get("units"), list) for x in data):
            return [u for x in data for u in x["units"]]
    return None


def parse_json(text: str, path: str = "<string>", foon: Foon | None = None) -> Foon:
    """FOON JSON (one document or a list of them) or foon2asp's units into ``foon`` (a new one by default)."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"bad JSON: {exc.msg}", path, exc.lineno) from None
    except RecursionError:
        raise InputError("JSON nested too deeply", path) from None
    except ValueError as exc:  # a number with more digits than Python converts
        scan(text, path)  # names its line and column
        raise InputError(f"bad JSON: {exc}", path) from None
    return read_json(data, path, foon)


def read_json(data: object, path: str = "<string>", foon: Foon | None = None) -> Foon:
    """:func:`parse_json` of the decoded value ``data``."""
    foon = foon if foon is not None else Foon()
    docs: list = data if isinstance(data, list) and data else [data]
    if all(is_foon_json(d) for d in docs):
        for doc in docs:
            read_official(doc, path, foon)
        return foon
    units = _lab_units(data)
    if units is None:
        raise InputError(
            'expected FOON JSON ({"functional_units": [...]}), a list of units {motion, inputs, outputs}'
            " or a list of units {input_nodes, motion_node, output_nodes}",
            path,
        )
    for k, u in enumerate(units, 1):
        unit = unit_from_json(u, path, f"unit {k}")
        if not unit.inputs:
            raise InputError(f"unit {k}: a unit without inputs", path)
        foon.add_unit(unit, (path, k))
    return foon
