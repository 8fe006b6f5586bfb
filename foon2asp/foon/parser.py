"""Read and write FOON text files.

Both dialects (ID-less and official, docs/formats.md) are read line by line, so files
may mix them; a JSON file is FOON JSON (:mod:`foon2asp.foon.foonjson`) or a unit list
(:mod:`foon2asp.foon.unitlist`).  ``in`` sets the container, ``contains`` the
ingredients, any other relation is the state ``"rel [arg]"``; brackets must pair up.
Bad lines are an :class:`InputError` naming ``FILE:LINE[:COLUMN]``.  The ids of official
files are kept (:attr:`Foon.ids`) and reused when writing the official dialect.
"""

from __future__ import annotations

import gc
import json
import re
from collections.abc import Iterable
from pathlib import Path
from typing import TextIO

from foon2asp.errors import InputError
from foon2asp.foon import unitlist
from foon2asp.foon.foonjson import looks_like_json, parse_json
from foon2asp.foon.model import Foon, FoonObject, Unit, norm
from foon2asp.foon.reading import check_line, lines_of, read_text

_KINDS = frozenset("OSM")
_RELATION_STATE = re.compile(r"^(.+?) ([\[{].*[\]}])$")


_BRACKET = re.compile(r"[\[\]{}]")
#: the usual state line with brackets (``in\t[bowl]``, ``contains\t{a,b}``): checked without a scan
_ONE_LIST = re.compile(r"[^\[\]{}\t]*\t *(?:\[[^\[\]{}\t]*\]|\{[^\[\]{}\t]*\}) *")
_CLOSING = {"[": "]", "{": "}"}
_OPENING = {"]": "[", "}": "{"}


def _strip_brackets(arg: str) -> str:
    arg = arg.strip()
    if arg[:1] in "[{" and arg[-1:] in "]}":
        arg = arg[1:-1]
    return arg.strip()


def _bracket_problem(text: str) -> tuple[str, int] | None:
    """Why the brackets of ``text`` do not pair up (``[``/``]``, ``{``/``}``), with the offset
    of the bracket at fault; None when they pair up."""
    open_: list[tuple[str, int]] = []
    for m in _BRACKET.finditer(text):
        c, at = m.group(), m.start()
        if c in _CLOSING:
            open_.append((c, at))
        elif not open_:
            return f"stray {c!r} (no {_OPENING[c]!r} before it)", at
        elif _CLOSING[open_[-1][0]] != c:
            return f"{open_[-1][0]!r} closed by {c!r}", at
        else:
            open_.pop()
    if open_:
        c, at = open_[0]
        return f"unbalanced {c!r} (no {_CLOSING[c]!r} after it)", at
    return None


def _check_brackets(line: str, tab: int, path: str, lineno: int) -> None:
    """An error naming ``FILE:LINE:COLUMN`` when a field of the state line ``line`` (fields
    start after ``tab``) has brackets that do not pair up, or the argument of ``in`` or
    ``contains`` is not one bracketed list."""
    start = tab + 1
    raw = line[start:].split("\t")
    shown = " ".join(f.strip() for f in raw if f.strip())
    for field in raw:
        problem = _bracket_problem(field)
        if problem is not None:
            what, at = problem
            raise InputError(f"{what} in the state {shown!r}", path, lineno, start + at + 1)
        start += len(field) + 1
    name = raw[0].strip().lower()
    if len(raw) > 1 and name in ("in", "contains", "ingredients"):
        arg = raw[1]
        inner = _strip_brackets(arg)
        m = _BRACKET.search(inner)
        if m is not None:
            column = tab + 1 + len(raw[0]) + 1 + arg.find(inner) + m.start() + 1
            example = "in [bowl]" if name == "in" else f"{name} {{flour,sugar}}"
            raise InputError(
                f"nested or extra brackets in the state {shown!r} ({name!r} takes one list, e.g. {example!r})",
                path,
                lineno,
                column,
            )


class _Obj:
    """An object being read (mutable until the unit ends)."""

    def __init__(self, label: str):
        self.label = label
        self.states: list[str] = []
        self.ingredients: list[str] = []
        self.container: str | None = None

    def freeze(self, memo: dict) -> FoonObject:
        """The normalised object; ``memo`` maps raw fields to objects already made."""
        key = (self.label, tuple(self.states), tuple(self.ingredients), self.container)
        obj = memo.get(key)
        if obj is None:
            obj = memo[key] = FoonObject.make(self.label, self.states, self.ingredients, self.container)
        return obj


def parse_lines(lines: Iterable[str], path: str = "<string>", foon: Foon | None = None, strict: bool = False) -> Foon:
    """Parse FOON text from ``lines`` into ``foon`` (a new one by default).  A unit without a
    motion line is skipped with a warning in ``foon.warnings`` (an error when ``strict``)."""
    foon = foon if foon is not None else Foon()
    gc_enabled = gc.isenabled()
    gc.disable()  # many small long-lived objects: collection passes only cost time here
    try:
        return _parse(lines, path, foon, strict)
    finally:
        if gc_enabled:
            gc.enable()


def _parse(lines: Iterable[str], path: str, foon: Foon, strict: bool) -> Foon:
    memo: dict = {}
    inputs: list[_Obj] = []
    outputs: list[_Obj] = []
    motion: str | None = None
    start = 0
    current: _Obj | None = None
    ids = foon.ids

    def finish(lineno: int) -> None:
        nonlocal inputs, outputs, motion, current, start
        if inputs or outputs or motion is not None:
            if motion is None:
                err = InputError("functional unit has no motion (M) line; unit skipped", path, start)
                if strict:
                    raise err
                foon.warnings.append(str(err))
                inputs, outputs, current = [], [], None
                return
            unit = Unit(motion, tuple(o.freeze(memo) for o in inputs), tuple(o.freeze(memo) for o in outputs))
            foon.add_unit(unit, (path, start))
        inputs, outputs, motion, current = [], [], None, None

    lineno = 0
    for lineno, raw in enumerate(lines, 1):
        line = raw.rstrip("\r\n")
        if lineno == 1 and line.startswith("\ufeff"):
            line = line[1:]
        check_line(line, path, lineno)
        kind = line[:1]
        # O, S or M, optional digits, TAB: checked without a regular expression
        tab = line.find("\t") if kind in _KINDS else -1
        if tab < 0 or (tab > 1 and not line[1:tab].isdecimal()):
            if not line.strip():
                continue
            if line.startswith("//"):
                finish(lineno)
                continue
            if line.startswith("#"):
                continue
            if kind in "OSM" and "\t" not in line:
                raise InputError(f"expected a TAB after '{line.split()[0]}' in {line.strip()!r}", path, lineno)
            raise InputError(f"unknown line type {line.strip()[:40]!r} (expected O, S, M, // or #)", path, lineno)
        rest = line[tab + 1 :]
        fields = [f.strip() for f in rest.split("\t")] if "\t" in rest else [rest.strip()]
        if tab > 1 and fields[0]:  # an official line: keep the id of its label
            name = fields[0].rstrip("*") if kind == "M" else fields[0]
            ids[kind].setdefault(norm(name), int(line[1:tab]))
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
            if _BRACKET.search(rest) is not None and _ONE_LIST.fullmatch(rest) is None:
                _check_brackets(line, tab, path, lineno)
            arg = fields[1] if len(fields) > 1 and fields[1] else None
            if arg is None:
                current.states.append(name)
            elif name.lower() in ("contains", "ingredients"):
                current.ingredients.extend(i for i in _strip_brackets(arg).split(","))
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
            label = fields[0].rstrip("*").strip()
            if not label:
                raise InputError("motion line with an empty motion", path, lineno)
            motion = label.lower()
            current = None
    finish(lineno + 1)
    return foon


def read_foon(path: str | Path, foon: Foon | None = None, strict: bool = False) -> Foon:
    """Read one FOON file: FOON text (either dialect) or FOON JSON (``.json``, or text starting with ``{``/``[``)."""
    text = read_text(path, "FOON", checked=False)  # FOON text is checked line by line
    if looks_like_json(path, text[:64]):
        return _json_foon(text, str(path), foon, strict)
    return parse_lines(lines_of(text), str(path), foon, strict)


def _json_foon(text: str, path: str, foon: Foon | None, strict: bool) -> Foon:
    """A JSON FOON file: the unit-list form of generated trees (:mod:`foon2asp.foon.unitlist`;
    ``strict``: a unit it skips is an error), else FOON JSON (:func:`foonjson.parse_json`)."""
    if text.lstrip()[:1] == "[":
        try:
            value = json.loads(text)
        except (ValueError, RecursionError):
            value = None  # the readers below report it, located
        if unitlist.is_unit_list(value) or unitlist.is_unit_lists(value):
            return unitlist.unit_list_foon(text, path, strict, foon)
    return parse_json(text, path, foon)


def read_foons(paths: Iterable[str | Path], strict: bool = False) -> Foon:
    """Read several FOON files into one merged, de-duplicated FOON."""
    foon = Foon()
    for path in paths:
        read_foon(path, foon, strict)
    return foon


def parse_text(text: str, path: str = "<string>", strict: bool = False) -> Foon:
    return parse_lines(lines_of(text), path, strict=strict)


def state_parts(state: str) -> tuple[str, str | None]:
    """``"on [plate]"`` -> ``("on", "[plate]")``; a plain state -> ``(state, None)``.  Split only
    where both parts read back as they are (brackets pair up, the name is not ``in``/``contains``)."""
    m = _RELATION_STATE.match(state)
    if m is None or m.group(1).lower() in ("in", "contains", "ingredients"):
        return state, None
    if _bracket_problem(m.group(1)) is not None or _bracket_problem(m.group(2)) is not None:
        return state, None
    return m.group(1), m.group(2)


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
    read (first per label, unless another label holds it), then fresh ids above the largest
    in sorted label order, so the same FOON always gets the same ids."""

    def __init__(self, known: dict[str, dict[str, int]], labels: dict[str, set[str]]):
        self.table: dict[str, dict[str, int]] = {}
        for kind in ("O", "S", "M"):
            table: dict[str, int] = {}
            taken: set[int] = set()
            for text, i in known.get(kind, {}).items():
                if i not in taken and text not in table:
                    table[text] = i
                    taken.add(i)
            nxt = max(taken, default=0) + 1
            for text in sorted(labels.get(kind, set()) - table.keys()):
                table[text] = nxt
                nxt += 1
            self.table[kind] = table

    def get(self, kind: str, text: str) -> int:
        """The id of ``text`` (a new one, above all others, for text not seen before)."""
        table = self.table[kind]
        text = norm(text)
        i = table.get(text)
        if i is None:
            i = table[text] = max(table.values(), default=0) + 1
        return i


def foon_labels(foon: Foon) -> dict[str, set[str]]:
    """The object labels, state names and motions of ``foon``."""
    states: set[str] = set()
    for obj in foon.objects:
        states.update(name for name, _ in object_fields(obj))
    return {"O": {o.label for o in foon.objects}, "S": states, "M": {u.motion for u in foon.units}}


def id_map(foon: Foon) -> IdMap:
    """The ids of ``foon`` for the official dialect (cached until the FOON grows)."""
    key = (len(foon.units), len(foon.objects), sum(len(t) for t in foon.ids.values()))
    cached = foon.id_cache
    if cached is None or cached[0] != key:
        cached = foon.id_cache = (key, IdMap(foon.ids, foon_labels(foon)))
    return cached[1]


def object_lines(obj: FoonObject, ids: IdMap | None = None) -> list[str]:
    """The O and S lines of ``obj``: official with ``ids``, else ID-less."""
    if ids is None:
        lines = [f"O\t{obj.label}"]
        lines += [f"S\t{name}\t{arg}" if arg else f"S\t{name}" for name, arg in object_fields(obj)]
        return lines
    lines = [f"O{ids.get('O', obj.label)}\t{obj.label}\t0"]
    for name, arg in object_fields(obj):
        sid = ids.get("S", name)
        lines.append(f"S{sid}\t{name}\t{arg}" if arg else f"S{sid}\t{name}")
    return lines


def unit_lines(unit: Unit, ids: IdMap | None = None) -> list[str]:
    """The lines of ``unit``, closed by ``//`` (official with ``ids``, else ID-less)."""
    lines: list[str] = []
    for obj in unit.inputs:
        lines += object_lines(obj, ids)
    lines.append(
        f"M\t{unit.motion}" if ids is None else f"M{ids.get('M', unit.motion)}\t{unit.motion}\tAssumed\tAssumed"
    )
    for obj in unit.outputs:
        lines += object_lines(obj, ids)
    lines.append("//")
    return lines


def format_units(units: Iterable[Unit], header: str | None = None, ids: IdMap | None = None) -> str:
    """FOON text for ``units``, each closed by ``//``: the official dialect with ``ids``, else ID-less."""
    lines = [f"# {header}"] if header else []
    lines.append("//")
    for unit in units:
        lines += unit_lines(unit, ids)
    return "\n".join(lines) + "\n"


def write_foon(foon: Foon, out: TextIO, header: str | None = None, dialect: str = "official") -> None:
    """Write ``foon`` in ``dialect`` (``official``: with the ids of :func:`id_map`; ``plain``: ID-less)."""
    out.write(format_units(foon.units, header, id_map(foon) if dialect == "official" else None))
