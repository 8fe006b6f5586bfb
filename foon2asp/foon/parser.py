"""Read and write FOON text files.

Both dialects (ID-less and official, docs/formats.md) are read line by line, so files may
mix them; the ids of official files are kept (:attr:`Foon.ids`) and reused when writing.
"""

from __future__ import annotations

import gc
import itertools
import json
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TextIO

from foon2asp.errors import InputError
from foon2asp.foon import unitlist
from foon2asp.foon.foonjson import parse_json, read_json
from foon2asp.foon.model import BRACKET, Foon, FoonObject, Unit, bracket_problem, norm, state_parts
from foon2asp.foon.reading import check_line, check_text, lines_of, read_text, scan

_KINDS = frozenset("OSM")
#: the usual state line with brackets (``in\t[bowl]``, ``contains\t{a,b}``): checked without a scan
_ONE_LIST = re.compile(r"[^\[\]{}\t]*\t *(?:\[[^\[\]{}\t]*\]|\{[^\[\]{}\t]*\}) *")


def _strip_brackets(arg: str) -> str:
    arg = arg.strip()
    if arg[:1] in "[{" and arg[-1:] in "]}":
        arg = arg[1:-1]
    return arg.strip()


def _check_brackets(line: str, tab: int, path: str, lineno: int) -> None:
    """An error naming ``FILE:LINE:COLUMN`` when a field of the state line ``line`` (fields
    start after ``tab``) has brackets that do not pair up, or the argument of ``in`` or
    ``contains`` is not one bracketed list."""
    start = tab + 1
    raw = line[start:].split("\t")
    shown = " ".join(f.strip() for f in raw if f.strip())
    for part in raw:
        problem = bracket_problem(part)
        if problem is not None:
            what, at = problem
            raise InputError(f"{what} in the state {shown!r}", path, lineno, start + at + 1)
        start += len(part) + 1
    name = raw[0].strip().lower()
    if len(raw) > 1 and name in ("in", "contains", "ingredients"):
        arg = raw[1]
        inner = _strip_brackets(arg)
        m = BRACKET.search(inner)
        if m is not None:
            column = tab + 1 + len(raw[0]) + 1 + arg.find(inner) + m.start() + 1
            example = "in [bowl]" if name == "in" else f"{name} {{flour,sugar}}"
            raise InputError(
                f"nested or extra brackets in the state {shown!r} ({name!r} takes one list, e.g. {example!r})",
                path,
                lineno,
                column,
            )


@dataclass
class _Obj:
    """An object being read (mutable until the unit ends)."""

    label: str
    states: list[str] = field(default_factory=list)
    ingredients: list[str] = field(default_factory=list)
    container: str | None = None


def parse_lines(
    lines: str | Iterable[str], path: str = "<string>", foon: Foon | None = None, strict: bool = False
) -> Foon:
    """Parse FOON text (a string, or its lines) into ``foon`` (a new one by default).  A unit without
    a motion line is skipped with a warning in ``foon.warnings`` (an error when ``strict``)."""
    foon = foon if foon is not None else Foon()
    gc_enabled = gc.isenabled()
    gc.disable()  # many small long-lived objects: collection passes only cost time here
    try:
        return _parse(lines_of(lines) if isinstance(lines, str) else lines, path, foon, strict)
    finally:
        if gc_enabled:
            gc.enable()


def _parse(lines: Iterable[str], path: str, foon: Foon, strict: bool) -> Foon:
    memo: dict[tuple, FoonObject] = {}  # raw fields -> the object made of them
    inputs: list[_Obj] = []
    outputs: list[_Obj] = []
    motion: str | None = None
    start = 0
    current: _Obj | None = None

    def freeze(o: _Obj) -> FoonObject:
        key = (o.label, tuple(o.states), tuple(o.ingredients), o.container)
        obj = memo.get(key)
        if obj is None:
            obj = memo[key] = FoonObject.make(o.label, o.states, o.ingredients, o.container)
        return obj

    def finish() -> None:
        nonlocal inputs, outputs, motion, current
        if motion is not None:
            foon.add_unit(Unit(motion, tuple(map(freeze, inputs)), tuple(map(freeze, outputs))), (path, start))
        elif inputs or outputs:
            err = InputError("functional unit has no motion (M) line; unit skipped", path, start)
            if strict:
                raise err
            foon.warnings.append(str(err))
        inputs, outputs, motion, current = [], [], None, None

    for lineno, raw in enumerate(lines, 1):
        line = raw.rstrip("\r\n")
        if lineno == 1 and line.startswith("\ufeff"):
            line = line[1:]
        check_line(line, path, lineno)
        kind = line[:1]
        # O, S or M, optional digits, TAB: checked without a regular expression
        tab = line.find("\t") if kind in _KINDS else -1
        if tab < 0 or (tab > 1 and not line[1:tab].isdecimal()):
            if line.startswith("//"):
                finish()
            elif line.strip() and not line.startswith("#"):
                if kind in _KINDS and "\t" not in line:
                    raise InputError(f"expected a TAB after '{line.split()[0]}' in {line.strip()!r}", path, lineno)
                raise InputError(f"unknown line type {line.strip()[:40]!r} (expected O, S, M, // or #)", path, lineno)
            continue
        rest = line[tab + 1 :]
        fields = [f.strip() for f in rest.split("\t")] if "\t" in rest else [rest.strip()]
        if tab > 1 and fields[0]:  # an official line: keep the id of its label
            foon.ids[kind].setdefault(norm(fields[0].rstrip("*") if kind == "M" else fields[0]), int(line[1:tab]))
        if kind == "O":
            if not fields[0]:
                raise InputError("object line with an empty label", path, lineno)
            if not (inputs or outputs or motion is not None):
                start = lineno
            current = _Obj(fields[0])
            (outputs if motion is not None else inputs).append(current)
        elif kind == "S":
            if current is None:
                raise InputError("state (S) line before any object (O) line", path, lineno)
            name = fields[0]
            if not name:
                raise InputError("state line with an empty state", path, lineno)
            if BRACKET.search(rest) is not None and _ONE_LIST.fullmatch(rest) is None:
                _check_brackets(line, tab, path, lineno)
            arg = fields[1] if len(fields) > 1 and fields[1] else None
            if arg is None:
                current.states.append(name)
            elif name.lower() in ("contains", "ingredients"):
                current.ingredients.extend(_strip_brackets(arg).split(","))
            elif name.lower() == "in":
                container = _strip_brackets(arg)
                if current.container is not None and current.container != container:
                    raise InputError(
                        f"object {current.label!r} is in two containers [{current.container}] and [{container}]",
                        path,
                        lineno,
                    )
                current.container = container
            else:
                current.states.append(f"{name} {arg}")
        else:  # M
            if motion is not None:
                raise InputError("second motion (M) line in one functional unit", path, lineno)
            if not inputs:
                raise InputError("motion (M) line before any input object", path, lineno)
            motion = fields[0].rstrip("*").strip().lower()
            if not motion:
                raise InputError("motion line with an empty motion", path, lineno)
            current = None
    finish()
    return foon


def read_foon(path: str | Path, foon: Foon | None = None, strict: bool = False) -> Foon:
    """Read one FOON file: FOON text (either dialect) or FOON JSON (``.json``, or text starting with ``{``/``[``)."""
    text = read_text(path, "FOON", checked=False)  # FOON text is checked line by line
    if str(path).lower().endswith(".json") or text[:64].lstrip()[:1] in ("{", "["):
        return _json_foon(text, str(path), foon, strict)
    return parse_lines(text, str(path), foon, strict)


def _json_foon(text: str, path: str, foon: Foon | None, strict: bool) -> Foon:
    """A JSON FOON file: the unit-list form of generated trees (:mod:`foon2asp.foon.unitlist`;
    ``strict``: a unit it skips is an error), else FOON JSON (:func:`foonjson.parse_json`)."""
    try:
        value = json.loads(text)
    except (ValueError, RecursionError):
        return parse_json(text, path, foon)  # it reports the error, located
    check_text(text, path)  # what reading.located checks besides decoding
    if unitlist.is_unit_list(value) or unitlist.is_unit_lists(value):
        return unitlist.unit_list_foon(text, path, strict, foon, (value, scan(text, path)))
    if "\\" in text:  # an escape may hide a bad character from check_text: scan finds it
        scan(text, path)
    return read_json(value, path, foon)


def read_foons(paths: Iterable[str | Path], strict: bool = False) -> Foon:
    """Read several FOON files into one merged, de-duplicated FOON."""
    foon = Foon()
    for path in paths:
        read_foon(path, foon, strict)
    return foon


def object_fields(obj: FoonObject) -> list[tuple[str, str | None]]:
    """The state lines of ``obj`` as (state name, argument): states, then contents, then container."""
    fields = [state_parts(s) for s in obj.states]
    if obj.ingredients:
        fields.append(("contains", "{" + ",".join(obj.ingredients) + "}"))
    if obj.container:
        fields.append(("in", f"[{obj.container}]"))
    return fields


class IdMap:
    """One id per object label, state name and motion, for the official dialect: the ids
    ``known`` (first per label, unless another label holds it), then fresh ids above the
    largest for the other ``labels`` in sorted order, so the same FOON always gets the same ids."""

    def __init__(self, known: dict[str, dict[str, int]], labels: dict[str, set[str]]):
        self.table: dict[str, dict[str, int]] = {}
        for kind in ("O", "S", "M"):
            table = self.table[kind] = {}
            taken: set[int] = set()
            for text, i in known.get(kind, {}).items():
                if i not in taken and text not in table:
                    table[text] = i
                    taken.add(i)
            fresh = sorted(labels.get(kind, set()) - table.keys())
            table.update(zip(fresh, itertools.count(max(table.values(), default=0) + 1)))

    def get(self, kind: str, text: str) -> int:
        """The id of ``text`` (a new one, above all others, for text not seen before)."""
        table, text = self.table[kind], norm(text)
        if text not in table:
            table[text] = max(table.values(), default=0) + 1
        return table[text]


def id_map(foon: Foon) -> IdMap:
    """The ids of ``foon`` for the official dialect (cached until the FOON grows)."""
    key = (len(foon.units), len(foon.objects), sum(len(t) for t in foon.ids.values()))
    if foon.id_cache is None or foon.id_cache[0] != key:
        states = {name for obj in foon.objects for name, _ in object_fields(obj)}
        labels = {"O": {o.label for o in foon.objects}, "S": states, "M": {u.motion for u in foon.units}}
        foon.id_cache = (key, IdMap(foon.ids, labels))
    return foon.id_cache[1]


def object_lines(obj: FoonObject, ids: IdMap | None = None) -> list[str]:
    """The O and S lines of ``obj``: official with ``ids``, else ID-less."""
    lines = [f"O\t{obj.label}" if ids is None else f"O{ids.get('O', obj.label)}\t{obj.label}\t0"]
    for name, arg in object_fields(obj):
        kind = "S" if ids is None else f"S{ids.get('S', name)}"
        lines.append(f"{kind}\t{name}\t{arg}" if arg else f"{kind}\t{name}")
    return lines


def unit_lines(unit: Unit, ids: IdMap | None = None) -> list[str]:
    """The lines of ``unit``, closed by ``//`` (official with ``ids``, else ID-less)."""
    motion = f"M\t{unit.motion}" if ids is None else f"M{ids.get('M', unit.motion)}\t{unit.motion}\tAssumed\tAssumed"
    lines = [line for obj in unit.inputs for line in object_lines(obj, ids)] + [motion]
    return lines + [line for obj in unit.outputs for line in object_lines(obj, ids)] + ["//"]


def format_units(units: Iterable[Unit], header: str | None = None, ids: IdMap | None = None) -> str:
    """FOON text for ``units``, each closed by ``//``: the official dialect with ``ids``, else ID-less."""
    lines = [f"# {header}", "//"] if header else ["//"]
    lines += [line for unit in units for line in unit_lines(unit, ids)]
    return "\n".join(lines) + "\n"


def write_foon(foon: Foon, out: TextIO, header: str | None = None, dialect: str = "official") -> None:
    """Write ``foon`` in ``dialect`` (``official``: with the ids of :func:`id_map`; ``plain``: ID-less)."""
    out.write(format_units(foon.units, header, id_map(foon) if dialect == "official" else None))
