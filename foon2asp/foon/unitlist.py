"""The unit-list JSON form of task trees, as tree generators write them.

docs/llm-trees.md describes the form and its quirks.  A unit without inputs, motion or outputs
is skipped with a warning (an :class:`InputError` when ``strict``); repeated units are merged
into the first, with one warning; other problems and the limits (:data:`MAX_TEXT_CHARS`,
:data:`MAX_ITEMS`) are an :class:`InputError` naming file, line, unit and field.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Sequence

from foon2asp.errors import InputError
from foon2asp.foon.model import Foon, FoonObject, Unit, motion_key
from foon2asp.foon.reading import clipped, first_line, json_list, line_numbers, scan

#: the keys of one unit, in the order generators write them
KEYS = ("input_nodes", "motion_node", "output_nodes")

#: the most characters of a label, state, ingredient, container or motion
MAX_TEXT_CHARS = 1_000
#: the most entries of a list: states or ingredients of an object, nodes of one side of a unit
MAX_ITEMS = 1_000

#: keys that mark the other JSON forms: foon2asp's units and results, FOON JSON
_OTHER_KEYS = frozenset({"motion", "inputs", "outputs", "units", "functional_units"})


def is_unit_list(value: object) -> bool:
    """Is ``value`` (parsed JSON) the unit-list form: a non-empty list of objects, some with a
    key of :data:`KEYS`, none with a key of the other JSON forms?"""
    if not isinstance(value, list) or not value or not all(isinstance(v, dict) for v in value):
        return False
    if any(_OTHER_KEYS.intersection(v) for v in value):
        return False
    return any(any(k in v for k in KEYS) for v in value)


def is_unit_lists(value: object) -> bool:
    """Is ``value`` several trees in the unit-list form: a non-empty list of lists, each a
    unit list or empty, one at least a unit list (``solve --format units-json`` of several goals)?"""
    if not isinstance(value, list) or not value or not all(isinstance(v, list) for v in value):
        return False
    return all(not v or is_unit_list(v) for v in value) and any(v for v in value)


def _text(value: object, path: str, line: int | None, where: str, field: str) -> str:
    """A string field within :data:`MAX_TEXT_CHARS`."""
    if not isinstance(value, str):
        raise InputError(f"{where}: {field} must be a string", path, line)
    if len(value) > MAX_TEXT_CHARS:
        raise InputError(
            f"{where}: {field} {clipped(value)!r} has {len(value):,} characters (at most {MAX_TEXT_CHARS:,})",
            path,
            line,
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
    where = f"{where} ({clipped(label)!r})"
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
    return motion_key(_text(value, path, line, where, "'motion_node'"))


def read_unit(
    value: object, path: str, line: int | None, k: int, tree: int | None = None
) -> tuple[Unit | None, str | None]:
    """Unit ``k`` (from 1; of tree ``tree`` of several): ``(unit, None)``, or ``(None, why)`` when it
    cannot be used."""
    where = _where(k, tree)
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


def _where(k: int, tree: int | None) -> str:
    return f"tree {tree}, unit {k}" if tree is not None else f"unit {k}"


#: a unit read: (unit, its number in the list from 1, the line it starts on)
Located = tuple[Unit, int, int]
#: the entries of one list, each with the line it starts on, and the list's first line
_Entries = tuple[list[tuple[object, int]], int]


def _read(
    entries: list[tuple[object, int]], path: str, strict: bool, tree: int | None
) -> tuple[list[Located], list[str]]:
    """The distinct usable units of one list's ``entries``, and the warnings."""
    warnings: list[str] = []
    out: list[Located] = []
    first: dict[tuple, int] = {}
    repeats: list[tuple[int, int]] = []
    for k, (value, line) in enumerate(entries, 1):
        unit, why = read_unit(value, path, line, k, tree)
        if unit is None:
            where = _where(k, tree)
            if strict:
                raise InputError(f"{where} cannot be used: {why}", path, line)
            warnings.append(str(InputError(f"{where} cannot be used: {why} (skipped)", path, line)))
        elif (j := first.setdefault(unit.key(), k)) != k:
            repeats.append((k, j))
        else:
            out.append((unit, k, line))
    if repeats:
        shown = ", ".join(f"unit {k} repeats unit {j}" for k, j in repeats[:5])
        more = f", ... ({len(repeats) - 5} more)" if len(repeats) > 5 else ""
        n = len(repeats)
        of = f" in tree {tree}" if tree is not None else ""
        warnings.append(f"{path}: {n} repeated unit{'s' if n > 1 else ''}{of} merged ({shown}{more})")
    return out, warnings


def _lists(text: str, path: str, parsed: tuple[object, list[int]] | None) -> tuple[list[_Entries], bool]:
    """The lists of a unit list (one) or of a list of unit lists, and whether there are several."""
    value, tops = json_list(text, path, parsed=parsed)
    first = first_line(text)
    lines = line_numbers(text, tops)
    if not is_unit_lists(value):
        return [(list(zip(value, lines)), first)], False
    # each inner list's elements, their lines counted in one pass over the text
    offsets = [[pos + at for at in scan(text[pos:end], path)] for pos, end in zip(tops, [*tops[1:], len(text)])]
    every = iter(line_numbers(text, [o for inner in offsets for o in inner]))
    out = [(list(zip(inner, [next(every) for _ in at])), line) for inner, at, line in zip(value, offsets, lines)]
    return out, True


def read_unit_lists(
    text: str, path: str, strict: bool = False, parsed: tuple[object, list[int]] | None = None
) -> tuple[list[tuple[list[Located], int]], list[str]]:
    """The trees of a unit list (one tree) or of a list of unit lists (one each): per tree its
    distinct usable units ``(unit, k, line)`` in file order (``k`` from 1) and its first line;
    and all the warnings.  ``parsed``: the value and offsets :func:`located` gave for ``text``."""
    lists, several = _lists(text, path, parsed)
    trees: list[tuple[list[Located], int]] = []
    warnings: list[str] = []
    for t, (entries, line) in enumerate(lists, 1):
        units, more = _read(entries, path, strict, t if several else None)
        trees.append((units, line))
        warnings += more
    return trees, warnings


def unit_list_foon(
    text: str,
    path: str,
    strict: bool = False,
    foon: Foon | None = None,
    parsed: tuple[object, list[int]] | None = None,
) -> Foon:
    """The units of a unit list (or of a list of them) added to ``foon`` (a new one by default),
    each with its origin ``(path, line)``; the warnings go to ``foon.warnings``.  ``parsed``: as
    :func:`read_unit_lists` takes it."""
    foon = foon if foon is not None else Foon()
    trees, warnings = read_unit_lists(text, path, strict, parsed)
    for units, _ in trees:
        for unit, _, line in units:
            foon.add_unit(unit, (path, line))
    foon.warnings.extend(warnings)
    return foon


# ---------------------------------------------------------------- writing


def to_unit_list(units: Iterable[Unit]) -> list[dict]:
    """``units`` in the unit-list form."""
    return [
        {
            "input_nodes": [o.to_json() for o in u.inputs],
            "motion_node": u.motion,
            "output_nodes": [o.to_json() for o in u.outputs],
        }
        for u in units
    ]


def _block(lines: list[str]) -> str:
    """A JSON list of the encoded ``lines``, one per line."""
    return "[\n" + ",\n".join(lines) + "\n]" if lines else "[]"


def dumps(units: Iterable[Unit]) -> str:
    """The unit-list JSON of ``units`` (one line per unit)."""
    return _block([json.dumps(e, ensure_ascii=False) for e in to_unit_list(units)]) + "\n"


def dumps_trees(trees: Sequence[Sequence[Unit]]) -> str:
    """One tree as :func:`dumps` writes it; several as a JSON list of unit lists (one line per unit)."""
    if len(trees) == 1:
        return dumps(trees[0])
    return _block([dumps(tree).rstrip("\n") for tree in trees]) + "\n"
