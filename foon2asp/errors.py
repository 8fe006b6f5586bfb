"""Errors about user input: always reported as one line naming file, line and column."""

from __future__ import annotations

import re

#: characters never accepted in input text or labels: C0/C1 controls (TAB aside; line ends
#: split lines), DEL, lone surrogates, the Unicode line and paragraph separators
BAD_CHAR = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u2028\u2029\ud800-\udfff]")

#: what :func:`escape` rewrites: the bad characters, the line ends, and the characters that are
#: invisible or reorder the text around them (soft hyphen, zero-width characters, bidirectional
#: marks, embeddings, overrides and isolates, word joiners, the byte-order mark, tags)
_SHOWN = re.compile(
    "[\x00-\x1f\x7f-\x9f\xad\u061c\u180e\u200b-\u200f\u2028-\u202e\u2060-\u206f\ud800-\udfff"
    "\ufeff\ufff9-\ufffb\U000e0000-\U000e007f]"
)

#: the most characters of a value a message echoes (:func:`shown`), and of a whole message
MAX_ECHO = 200
MAX_MESSAGE = 2000


def escape(text: str) -> str:
    """``text`` with control, separator, surrogate, invisible and bidirectional characters shown as
    escapes (``\\x0b``, ``\\u2028``, ``\\u202e``)."""

    def one(m: re.Match) -> str:
        c = ord(m.group(0))
        return f"\\x{c:02x}" if c < 0x100 else f"\\u{c:04x}" if c < 0x10000 else f"\\U{c:08x}"

    return _SHOWN.sub(one, text)


def clip(text: str, keep: int = MAX_ECHO) -> str:
    """``text`` cut to its first ``keep`` characters, ``...`` added when it was longer."""
    return text if len(text) <= keep else text[:keep] + "..."


def shown(value: object, keep: int = MAX_ECHO) -> str:
    """A value a message echoes: quoted as ``repr`` quotes it, at most ``keep`` characters (then
    ``...``), every invisible or control character escaped."""
    return escape(repr(clip(str(value), keep)))


def one_line(text: str) -> str:
    """A message as one line: line ends as spaces, characters escaped (:func:`escape`), at most
    :data:`MAX_MESSAGE` characters."""
    return clip(escape(text.replace("\r\n", " ").replace("\n", " ")), MAX_MESSAGE)


def char_name(ch: str) -> str:
    """A bad character as users see it in a message: ``U+0000 (NUL)``-like."""
    names = {0: "NUL", 0x7F: "DEL", 0x85: "NEL", 0x2028: "LINE SEPARATOR", 0x2029: "PARAGRAPH SEPARATOR"}
    code = ord(ch)
    if 0xD800 <= code <= 0xDFFF:
        return f"U+{code:04X} (lone surrogate)"
    if code in names:
        return f"U+{code:04X} ({names[code]})"
    return f"U+{code:04X} (control character)"


class InputError(Exception):
    """Bad input. ``str(err)`` is a one-line message ``FILE:LINE[:COLUMN]: what``.

    ``hint`` (``KEY`` or ``KEY=VALUE``) lets a front end word the remedy in its own terms (the
    command line names its flags: :data:`foon2asp.cli.main.FLAG_WORDING`); the message itself
    speaks of values.
    """

    def __init__(
        self,
        message: str,
        path: str | None = None,
        line: int | None = None,
        column: int | None = None,
        *,
        hint: str | None = None,
    ):
        super().__init__(message)
        self.message = message
        self.path = path
        self.line = line
        self.column = column
        self.hint = hint

    def __str__(self) -> str:
        where = ""
        if self.path is not None:
            where = escape(clip(str(self.path)))
            if self.line is not None:
                where += f":{self.line}"
                if self.column is not None:
                    where += f":{self.column}"
            where += ": "
        return where + one_line(self.message)


def strict_error(warnings: list[str], strict: str = "strict") -> InputError:
    """The error that warnings about a request are when ``strict`` (the option's name) is on: the
    first warning, and how many more there are."""
    more = f"; {len(warnings) - 1} more warning(s)" if len(warnings) > 1 else ""
    return InputError(f"{warnings[0]} ({strict}: warnings are errors{more})")


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised like an interrupt so that the same clean-up runs (exit status 143)."""


def forget_unhandled_interrupt() -> None:
    """Clear CPython's note that a KeyboardInterrupt left code run from a string (``exec`` of a
    string, as dataclasses and namedtuple run while a module is imported), which it keeps even
    when the interrupt is caught later: at exit it would make the process kill itself with SIGINT
    instead of exiting with the status the command chose. Running any string clears the note."""
    exec("")


def interrupt_behind(exc: BaseException) -> BaseException:
    """The interrupt that ``exc`` wraps, else ``exc``: Python 3.11 turns an exception raised while a
    class is made (in ``__set_name__``, as a dataclass's fields) into a RuntimeError caused by it."""
    cause = exc.__cause__
    return cause if isinstance(exc, RuntimeError) and isinstance(cause, KeyboardInterrupt) else exc
