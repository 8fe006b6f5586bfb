"""Reading user files safely: UTF-8 text and JSON with limits, every error located in the file.

Every reader of a user file goes through :func:`read_text` (or :func:`check_text`) and JSON
through :func:`loads`: a bad byte, a control or separator character, too deep nesting or
too long a number is one :class:`~foon2asp.errors.InputError` naming ``FILE:LINE:COLUMN``.
"""

from __future__ import annotations

import json
import os
import re
from collections.abc import Iterator
from pathlib import Path

from foon2asp.errors import BAD_CHAR, InputError, char_name

#: the line ends of user files: LF, CRLF and a lone CR (never VT, FF, NEL or U+2028)
LINE_END = re.compile("\r\n|\r|\n")
#: larger files are refused before they are read
MAX_FILE_BYTES = 512 * 1024 * 1024
MAX_DEPTH = 100
MAX_NUMBER_CHARS = 100

#: the escapes that stand for a bad character (a line break, \r or \n, is left to the readers)
_HIDDEN = re.compile(r"\\[ubf]")
_TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|[\[\]{}]|-?[0-9][0-9.eE+\-]*|-?[A-Za-z]+', re.S)


def position(text: str, pos: int) -> tuple[int, int]:
    """Line and column (both from 1) of offset ``pos`` in ``text``."""
    return text.count("\n", 0, pos) + 1, pos - text.rfind("\n", 0, pos)


def lines_of(text: str) -> Iterator[str]:
    """The lines of ``text``, one at a time, split at LF, CRLF or CR only (not at VT, FF, NEL, U+2028)."""
    start = 0
    for m in LINE_END.finditer(text):
        yield text[start : m.start()]
        start = m.end()
    yield text[start:]


def content_lines(text: str) -> Iterator[tuple[int, str]]:
    """``(line number, line)`` of the lines of ``text`` that are neither blank nor ``#`` comments."""
    for lineno, line in enumerate(lines_of(text), 1):
        body = line.strip()
        if body and not body.startswith("#"):
            yield lineno, line


def name_and_value(line: str) -> list[str]:
    """A ``name<TAB>value`` line split at its last TAB (at its last blank when it has none)."""
    return line.rsplit("\t", 1) if "\t" in line else line.rsplit(None, 1)


def clipped(text: str, keep: int = 40) -> str:
    """``text`` for a message: its first ``keep`` characters and ``...`` when it is longer."""
    return text if len(text) <= keep else text[:keep] + "..."


def check_line(line: str, path: str, lineno: int) -> None:
    """An error naming the first control, separator or surrogate character of ``line``."""
    m = BAD_CHAR.search(line)
    if m is not None:
        raise InputError(f"{char_name(m.group(0))} is not allowed", path, lineno, m.start() + 1)


def check_text(text: str, path: str) -> None:
    """:func:`check_line` for a whole text (TAB and the line ends LF, CR are allowed)."""
    m = BAD_CHAR.search(text.replace("\r", "\n") if "\r" in text else text)
    if m is not None:
        raise InputError(f"{char_name(m.group(0))} is not allowed", path, *position(text, m.start()))


def not_found(path: str | Path, what: str) -> InputError:
    """The error for the ``what`` file ``path`` that is not there: ``goals file not found``, or
    ``goals file is a broken link (to TARGET)`` when ``path`` is a link to nothing."""
    if os.path.islink(path):
        try:
            target = os.readlink(path)
        except OSError:
            target = "?"
        return InputError(f"{what} file is a broken link (to {target})", str(path))
    return InputError(f"{what} file not found", str(path))


def read_text(path: str | Path, what: str, checked: bool = True) -> str:
    """The UTF-8 text of the ``what`` file ``path`` (a leading byte-order mark dropped), checked
    by :func:`check_text` unless ``checked`` is False."""
    path = Path(path)
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise InputError(f"{what} file is too large ({size} bytes; at most {MAX_FILE_BYTES})", str(path))
        with open(path, "rb") as fh:
            data = fh.read(size + 1)
            if len(data) > size:  # not a regular file, or one still growing
                data += fh.read(MAX_FILE_BYTES + 1 - len(data))
    except FileNotFoundError:
        raise not_found(path, what) from None
    except IsADirectoryError:
        raise InputError(f"{what} file is a directory", str(path)) from None
    except OSError as exc:
        raise InputError(f"cannot read {what} file: {exc.strerror or exc}", str(path)) from None
    if len(data) > MAX_FILE_BYTES:
        raise InputError(f"{what} file is too large (more than {MAX_FILE_BYTES} bytes)", str(path))
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = len(data[data.rfind(b"\n", 0, exc.start) + 1 : exc.start].decode("utf-8", "replace")) + 1
        raise InputError(
            f"not UTF-8 text: byte 0x{data[exc.start]:02x} at byte offset {exc.start} ({exc.reason})",
            str(path),
            line,
            column,
        ) from None
    text = text.removeprefix("\ufeff")
    if checked:
        check_text(text, str(path))
    return text


def scan(text: str, path: str) -> list[int]:
    """Refuse nesting deeper than :data:`MAX_DEPTH`, numbers longer than
    :data:`MAX_NUMBER_CHARS` and strings holding bad characters; return the offsets of the
    values at depth 1 (the elements of a top-level list)."""
    depth = 0
    tops: list[int] = []
    for m in _TOKEN.finditer(text):
        tok = m.group(0)
        if depth == 1 and tok not in "]}":
            tops.append(m.start())
        if tok[0] == '"':
            if _HIDDEN.search(tok):
                try:
                    value = json.loads(tok)
                except ValueError:
                    continue  # json.loads reports it with its position
                bad = BAD_CHAR.search(value)
                if bad is not None:
                    raise InputError(f"string holds {char_name(bad.group(0))}", path, *position(text, m.start()))
        elif tok in "[{":
            depth += 1
            if depth > MAX_DEPTH:
                raise InputError(f"JSON nested deeper than {MAX_DEPTH} levels", path, *position(text, m.start()))
        elif tok in "]}":
            depth -= 1
        elif len(tok) > MAX_NUMBER_CHARS and not tok.lstrip("-")[0].isalpha():
            raise InputError(f"number longer than {MAX_NUMBER_CHARS} characters", path, *position(text, m.start()))
    return tops


def located(text: str, path: str, checked: bool = False) -> tuple[object, list[int]]:
    """The JSON value of ``text`` (from file ``path``), decoded once, and the offsets of its
    elements when it is a list; ``checked``: the text already passed :func:`check_text`."""
    if not checked:
        check_text(text, path)
    tops = scan(text, path)
    try:
        return json.loads(text), tops
    except json.JSONDecodeError as exc:
        raise InputError(f"bad JSON: {exc.msg}", path, exc.lineno, exc.colno) from None


def first_line(text: str) -> int:
    """The line (from 1) of the first character of ``text`` that is not white space."""
    return text.count("\n", 0, len(text) - len(text.lstrip())) + 1


def json_list(
    text: str, path: str, checked: bool = False, parsed: tuple[object, list[int]] | None = None
) -> tuple[list, list[int]]:
    """The JSON list of ``text`` and the offsets of its elements, as :func:`located` gives them
    (or ``parsed``, what it gave); an error at the first line when the value is not a list."""
    value, tops = parsed or located(text, path, checked)
    if not isinstance(value, list):
        raise InputError("expected a JSON list of objects", path, first_line(text))
    return value, tops


def loads(text: str, path: str, checked: bool = False) -> object:
    """The JSON value of ``text`` (see :func:`located`)."""
    return located(text, path, checked)[0]


def line_numbers(text: str, offsets: list[int]) -> list[int]:
    """The line (from 1) of each of the ascending ``offsets`` of ``text``."""
    lines, line, counted = [], 1, 0
    for pos in offsets:
        line += text.count("\n", counted, pos)
        counted = pos
        lines.append(line)
    return lines


def load(path: str | Path, what: str) -> tuple[str, object]:
    """The checked text of the JSON file ``path`` and its value."""
    text = read_text(path, what)
    return text, loads(text, str(path), checked=True)
