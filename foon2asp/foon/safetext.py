"""Reading user text safely: UTF-8 with located errors, no control or separator characters.

Every reader of a user file goes through :func:`read_text` or :func:`check_text`: a bad
byte or control character is one :class:`~foon2asp.errors.InputError` naming
``FILE:LINE:COLUMN`` and the character; a byte-order mark at the start is skipped.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

from foon2asp.errors import BAD_CHAR, InputError, char_name

#: the line ends of user files: LF, CRLF and a lone CR (never VT, FF, NEL or U+2028)
LINE_END = re.compile("\r\n|\r|\n")

#: larger files are refused before they are read (JSON and line files are small)
MAX_FILE_BYTES = 512 * 1024 * 1024


def position(text: str, pos: int) -> tuple[int, int]:
    """Line and column (both from 1) of offset ``pos`` in ``text``."""
    line = text.count("\n", 0, pos) + 1
    column = pos - (text.rfind("\n", 0, pos) + 1) + 1
    return line, column


def lines_of(text: str) -> list[str]:
    """The lines of ``text`` split at LF, CRLF or CR only (``str.splitlines`` also splits at
    VT, FF, NEL, U+2028, which would hide them)."""
    return LINE_END.split(text)


def content_lines(text: str) -> Iterator[tuple[int, str]]:
    """``(line number, line)`` of the lines of ``text`` that are neither blank nor ``#`` comments."""
    for lineno, line in enumerate(lines_of(text), 1):
        body = line.strip()
        if body and not body.startswith("#"):
            yield lineno, line


def name_and_value(line: str) -> list[str]:
    """A ``name<TAB>value`` line split at its last TAB (at its last blank when it has none)."""
    return line.rsplit("\t", 1) if "\t" in line else line.rsplit(None, 1)


def check_line(line: str, path: str, lineno: int) -> None:
    """An error naming the first control, separator or surrogate character of ``line``."""
    m = BAD_CHAR.search(line)
    if m is not None:
        raise InputError(f"{char_name(m.group(0))} is not allowed", path, lineno, m.start() + 1)


def check_text(text: str, path: str) -> None:
    """An error naming the first control, separator or surrogate character of ``text``
    (TAB and the line ends LF, CR are allowed)."""
    m = BAD_CHAR.search(text.replace("\r", "\n") if "\r" in text else text)
    if m is not None:
        line, column = position(text, m.start())
        raise InputError(f"{char_name(m.group(0))} is not allowed", path, line, column)


def decode_error(data: bytes, exc: UnicodeDecodeError, path: str) -> InputError:
    """A located message for bytes that are not UTF-8 (``exc.start`` indexes ``data``)."""
    start = exc.start
    line = data.count(b"\n", 0, start) + 1
    line_start = data.rfind(b"\n", 0, start) + 1
    column = len(data[line_start:start].decode("utf-8", "replace")) + 1
    return InputError(
        f"not UTF-8 text: byte 0x{data[start]:02x} at byte offset {start} ({exc.reason})", path, line, column
    )


def read_bytes(path: str | Path, what: str, limit: int = MAX_FILE_BYTES) -> bytes:
    path = Path(path)
    try:
        size = path.stat().st_size
        if size > limit:
            raise InputError(f"{what} file is too large ({size} bytes; at most {limit})", str(path))
        with open(path, "rb") as fh:
            data = fh.read(limit + 1)
    except FileNotFoundError:
        raise InputError(f"{what} file not found", str(path)) from None
    except IsADirectoryError:
        raise InputError(f"{what} file is a directory", str(path)) from None
    except OSError as exc:
        raise InputError(f"cannot read {what} file: {exc.strerror or exc}", str(path)) from None
    if len(data) > limit:
        raise InputError(f"{what} file is too large (more than {limit} bytes)", str(path))
    return data


def decode(data: bytes, path: str) -> str:
    """UTF-8 ``data`` as text (a leading byte-order mark dropped), checked by :func:`check_text`."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise decode_error(data, exc, path) from None
    if text.startswith("\ufeff"):
        text = text[1:]
    check_text(text, path)
    return text


def read_text(path: str | Path, what: str, limit: int = MAX_FILE_BYTES) -> str:
    """The checked UTF-8 text of a user file (see :func:`decode`)."""
    return decode(read_bytes(path, what, limit), str(path))
