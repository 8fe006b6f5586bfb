"""The unit-list JSON form of task trees, as tree generators write them.

.. code-block:: text

    [{"input_nodes": [{"label": "banana", "states": ["whole"], "ingredients": [], "container": null},
                      {"label": "knife", "states": [], "ingredients": [], "container": null}],
      "motion_node": "peel",
      "output_nodes": [{"label": "banana", "states": ["peeled"], "ingredients": [], "container": null}]},
     ...]

Read as written: ``motion_node`` is a string or an object with ``label`` (or
``motion_label``); ``states`` and ``ingredients`` null or missing are empty;
``container`` missing or null is none.  Objects are made with
:meth:`FoonObject.make`, so their identity is label + set of states + set of
ingredients + container, independent of order and case; labels are not
otherwise changed (``blueberry`` and ``blueberries`` stay two objects).

A unit without ``input_nodes``, ``motion_node`` or ``output_nodes`` (missing,
null, an empty motion or no input at all) cannot be used: it is skipped with a
warning naming the file, line and unit (an :class:`InputError` when
``strict``).  Units that repeat an earlier unit (:meth:`Unit.key`) are merged
into the first, with one warning saying how many.  Other problems, and the
limits (:data:`MAX_TEXT_CHARS` characters per label, state, ingredient,
container and motion; :data:`MAX_ITEMS` entries per list), are one
:class:`InputError` naming the file, the line of the unit, the unit and the
field.  Units are numbered from 1 in messages.

:func:`to_unit_list` and :func:`dumps` write the same form back
(``container`` null when there is none), so ``read_unit_list(dumps(units))``
gives the units again.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Sequence
from pathlib import Path

from foon2asp.errors import InputError
from foon2asp.foon.loaders import _json_elements
from foon2asp.foon.model import Foon, FoonObject, Unit, norm
from foon2asp.foon.safetext import check_text, read_text

#: the keys of one unit, in the order generators write them
KEYS = ("input_nodes", "motion_node", "output_nodes")

#: the most characters of a label, state, ingredient, container or motion
MAX_TEXT_CHARS = 1_000
#: the most entries of a list: states or ingredients of an object, nodes of one side of a unit
MAX_ITEMS = 1_000

#: keys that mark the other JSON forms: foon2asp's units and results, FOON JSON
_OTHER_KEYS = frozenset({"motion", "inputs", "outputs", "units", "functional_units"})


def is_unit_list(value: object) -> bool:
    """Is ``value`` (parsed JSON) the unit-list form?

    A non-empty list of objects, some having ``motion_node``, ``input_nodes`` or
    ``output_nodes``, none having the keys of foon2asp's ``{motion, inputs,
    outputs}`` units, its results (``units``) or FOON JSON (``functional_units``).
    """
    if not isinstance(value, list) or not value or not all(isinstance(v, dict) for v in value):
        return False
    if any(_OTHER_KEYS.intersection(v) for v in value):
        return False
    return any(any(k in v for k in KEYS) for v in value)


def _short(text: str, keep: int = 40) -> str:
    return repr(text if len(text) <= keep else text[:keep] + "...")


def _text(value: object, path: str, line: int | None, where: str, field: str) -> str:
    """A string field within :data:`MAX_TEXT_CHARS`."""
    if not isinstance(value, str):
        raise InputError(f"{where}: {field} must be a string", path, line)
    if len(value) > MAX_TEXT_CHARS:
        raise InputError(
            f"{where}: {field} {_short(value)} has {len(value):,} characters (at most {MAX_TEXT_CHARS:,})", path, line
        )
    return value


def _items(value: object, path: str, line: int | None, where: str, field: str) -> list:
    """A list field (null or missing: empty) within :data:`MAX_ITEMS` entries."""
    if value is None:
        return []
    if not isinstance(value, list):
        raise InputError(f"{where}: {field} must be a list", path, line)
    if len(value) > MAX_ITEMS:
        raise InputError(f"{where}: {field} has {len(value):,} entries (at most {MAX_ITEMS:,})", path, line)
    return value


def read_node(value: object, path: str, line: int | None, where: str) -> FoonObject:
    """One object ``{label, states, ingredients, container}`` (``where``: e.g. ``unit 3, input_nodes[1]``)."""
    if not isinstance(value, dict):
        raise InputError(f"{where}: expected an object {{label, states, ingredients, container}}", path, line)
    if value.get("label") is None:
        hint = " (an 'object_label' is FOON JSON: such nodes belong in {\"functional_units\": [...]})"
        raise InputError(f"{where}: object without a 'label'" + (hint if "object_label" in value else ""), path, line)
    label = _text(value["label"], path, line, where, "'label'")
    if not label.strip():
        raise InputError(f"{where}: empty 'label'", path, line)
    where = f"{where} ({_short(label)})"
    fields = {}
    for name in ("states", "ingredients"):
        items = _items(value.get(name), path, line, where, f"'{name}'")
        fields[name] = [_text(x, path, line, where, f"an entry of '{name}'") for x in items]
    container = value.get("container")
    if container is not None:
        container = _text(container, path, line, where, "'container'")
    return FoonObject.make(label, fields["states"], fields["ingredients"], container)


def _motion(value: object, path: str, line: int | None, where: str) -> str:
    if isinstance(value, dict):
        inner = value.get("label", value.get("motion_label"))
        if inner is None:
            raise InputError(f"{where}: 'motion_node' is an object without a 'label'", path, line)
        value = inner
    return norm(_text(value, path, line, where, "'motion_node'")).rstrip("*").strip()


def read_unit(value: object, path: str, line: int | None, k: int) -> tuple[Unit | None, str | None]:
    """Unit ``k`` (from 1): ``(unit, None)``, or ``(None, why)`` when it cannot be used."""
    where = f"unit {k}"
    if not isinstance(value, dict):
        raise InputError(f"{where}: expected an object {{input_nodes, motion_node, output_nodes}}", path, line)
    missing = [key for key in KEYS if value.get(key) is None]
    if missing:
        return None, "no " + ", no ".join(f"'{key}'" for key in missing)
    motion = _motion(value["motion_node"], path, line, where)
    sides = []
    for side in ("input_nodes", "output_nodes"):
        nodes = _items(value[side], path, line, where, f"'{side}'")
        sides.append(tuple(read_node(n, path, line, f"{where}, {side}[{i}]") for i, n in enumerate(nodes)))
    if not motion:
        return None, "an empty 'motion_node'"
    if not sides[0]:
        return None, "no input node"
    return Unit(motion, sides[0], sides[1]), None


def _elements(value_or_text: object, path: str) -> list[tuple[object, int | None]]:
    """The top-level entries, each with the line it starts on (None when given a value)."""
    if isinstance(value_or_text, str):
        check_text(value_or_text, path)
        return list(_json_elements(value_or_text, path))
    if not isinstance(value_or_text, list):
        raise InputError("expected a JSON list of units {input_nodes, motion_node, output_nodes}", path)
    return [(v, None) for v in value_or_text]


def read_units(
    value_or_text: object, path: str, strict: bool = False
) -> tuple[list[tuple[Unit, int, int | None]], list[str]]:
    """``(unit, k, line)`` per distinct unit in file order (``k`` from 1), and the warnings."""
    warnings: list[str] = []
    out: list[tuple[Unit, int, int | None]] = []
    first: dict[tuple, int] = {}
    repeats: list[tuple[int, int]] = []
    for k, (value, line) in enumerate(_elements(value_or_text, path), 1):
        unit, why = read_unit(value, path, line, k)
        if unit is None:
            err = InputError(f"unit {k} cannot be used: {why} (skipped)", path, line)
            if strict:
                raise InputError(f"unit {k} cannot be used: {why}", path, line)
            warnings.append(str(err))
            continue
        key = unit.key()
        if key in first:
            repeats.append((k, first[key]))
            continue
        first[key] = k
        out.append((unit, k, line))
    if repeats:
        shown = ", ".join(f"unit {k} repeats unit {j}" for k, j in repeats[:5])
        more = f", ... ({len(repeats) - 5} more)" if len(repeats) > 5 else ""
        n = len(repeats)
        warnings.append(f"{path}: {n} repeated unit{'s' if n > 1 else ''} merged ({shown}{more})")
    return out, warnings


def read_unit_list(value_or_text: object, path: str, strict: bool = False) -> tuple[list[Unit], list[str]]:
    """The distinct usable units of a unit list (JSON text or its parsed value) and the warnings."""
    units, warnings = read_units(value_or_text, path, strict)
    return [u for u, _, _ in units], warnings


def read_unit_list_file(path: str | Path, strict: bool = False) -> tuple[list[Unit], list[str]]:
    """:func:`read_unit_list` of a file."""
    return read_unit_list(read_text(path, "tree"), str(path), strict)


def unit_list_foon(value_or_text: object, path: str, strict: bool = False, foon: Foon | None = None) -> Foon:
    """The units of a unit list added to ``foon`` (a new one by default); each unit's origin is
    ``(path, line)`` (the unit's number when no line is known); the warnings go to ``foon.warnings``."""
    foon = foon if foon is not None else Foon()
    units, warnings = read_units(value_or_text, path, strict)
    for unit, k, line in units:
        foon.add_unit(unit, (path, line if line is not None else k))
    foon.warnings.extend(warnings)
    return foon


# ---------------------------------------------------------------- writing


def unit_entry(unit: Unit) -> dict:
    """One unit in the unit-list form."""
    return {
        "input_nodes": [o.to_json() for o in unit.inputs],
        "motion_node": unit.motion,
        "output_nodes": [o.to_json() for o in unit.outputs],
    }


def to_unit_list(units: Iterable[Unit]) -> list[dict]:
    return [unit_entry(u) for u in units]


def dumps(units: Sequence[Unit] | Iterable[Unit]) -> str:
    """The unit-list JSON of ``units`` (one line per unit)."""
    entries = [json.dumps(e, ensure_ascii=False) for e in to_unit_list(units)]
    return "[\n" + ",\n".join(entries) + "\n]\n" if entries else "[]\n"
