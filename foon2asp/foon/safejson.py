"""JSON from users, with limits: nesting depth, number length, file size; located errors.

Every JSON reader of foon2asp uses :func:`loads`: before ``json.loads`` (which recurses
per nesting level and converts numbers of any length) a linear scan reports the first
excess, or a string escaping to a control, separator or surrogate character, as
``FILE:LINE:COLUMN``.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from foon2asp.errors import BAD_CHAR, InputError, char_name
from foon2asp.foon.safetext import check_text, position, read_text

MAX_DEPTH = 100
MAX_NUMBER_CHARS = 100

_TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|[\[\]{}]|-?[0-9][0-9.eE+\-]*', re.S)


def scan(text: str, path: str, max_depth: int = MAX_DEPTH, max_number: int = MAX_NUMBER_CHARS) -> None:
    """Refuse too deep nesting, too long numbers and strings holding bad characters."""
    depth = 0
    for m in _TOKEN.finditer(text):
        tok = m.group(0)
        c = tok[0]
        if c == '"':
            if "\\u" in tok:
                try:
                    value = json.loads(tok)
                except ValueError:
                    continue  # json.loads reports it with its position
                bad = BAD_CHAR.search(value)
                if bad is not None:
                    line, column = position(text, m.start())
                    raise InputError(f"string holds {char_name(bad.group(0))}", path, line, column)
        elif c in "[{":
            depth += 1
            if depth > max_depth:
                line, column = position(text, m.start())
                raise InputError(f"JSON nested deeper than {max_depth} levels", path, line, column)
        elif c in "]}":
            depth -= 1
        elif len(tok) > max_number:
            line, column = position(text, m.start())
            raise InputError(f"number longer than {max_number} characters", path, line, column)


def loads(text: str, path: str, checked: bool = False) -> object:
    """The JSON value of ``text`` (from file ``path``, for messages); ``checked``: the text
    already passed :func:`~foon2asp.foon.safetext.check_text`."""
    if not checked:
        check_text(text, path)
    scan(text, path)
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"bad JSON: {exc.msg}", path, exc.lineno, exc.colno) from None
    except (ValueError, RecursionError) as exc:  # pragma: no cover - the scan refuses these first
        raise InputError(f"bad JSON: {exc}", path) from None


def list_elements(text: str, path: str, start: int | None = None) -> list[tuple[object, int, int]]:
    """The elements of a JSON list, each with the line and the position it starts at.
    ``start``: the position of a list's ``[`` in ``text`` (already checked by :func:`loads`);
    None: the top-level value of ``text``, checked here, which must be a list."""
    if start is None:
        loads(text, path, checked=True)
        start = len(text) - len(text.lstrip())
        if text[start : start + 1] != "[":
            raise InputError("expected a JSON list of objects", path, text.count("\n", 0, start) + 1)
    dec = json.JSONDecoder()
    pos = start + 1
    line, counted = text.count("\n", 0, start) + 1, start
    out: list[tuple[object, int, int]] = []
    while True:
        while pos < len(text) and text[pos] in " \t\r\n,":
            pos += 1
        if pos >= len(text) or text[pos] == "]":
            return out
        value, end = dec.raw_decode(text, pos)
        line += text.count("\n", counted, pos)
        counted = pos
        out.append((value, line, pos))
        pos = end


def load(path: str | Path, what: str) -> tuple[str, object]:
    """The checked text of the JSON file ``path`` and its value."""
    text = read_text(path, what)
    return text, loads(text, str(path), checked=True)
