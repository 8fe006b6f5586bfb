"""User constraints: ASP files, rule texts and convenience flags as programs.

A flag is a fact that ``encodings/parts/constraints.lp`` reads; its motion or label enters as
an escaped string constant; files and ``--rule`` texts are
checked on their own, an error naming the file (or rule) and line.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

import clingo
import clingo.ast

from foon2asp.asp.facts import q
from foon2asp.asp.predicates import refuse_host_code, rule_warnings
from foon2asp.errors import InputError
from foon2asp.foon.reading import not_found, read_text

#: ``<block>:LINE:COL[-COL]: error: text`` or ``FILE:LINE:...`` as clingo writes them
_LOCATION = re.compile(r"^(?P<where>.*?):(?P<line>\d+):(?P<col>\d+)(?:-\d+(?::\d+)?)?: (?P<kind>\w+): (?P<text>.*)$")


def normalise(text: str) -> str:
    """Labels and motions as the FOON model stores them: single spaces, lower case."""
    return " ".join(str(text).split()).lower()


def motion_name(text: str) -> str:
    """A motion as the FOON model stores it (normalised, a trailing ``*`` dropped)."""
    text = normalise(text)
    return text[:-1].rstrip() if text.endswith("*") else text


def forbid_motion(motion: str) -> str:
    """No unit of the tree has motion ``motion`` (a fact for ``encodings/parts/constraints.lp``)."""
    return f"forbid_motion({q(motion_name(motion))}).\n"


def forbid_object(label: str) -> str:
    """No unit of the tree has an input or output labelled ``label``."""
    return f"forbid_object({q(normalise(label))}).\n"


def require_motion(motion: str) -> str:
    """Some unit of the tree has motion ``motion``."""
    return f"require_motion({q(motion_name(motion))}).\n"


def require_object(label: str) -> str:
    """Some unit of the tree has an input or output labelled ``label``."""
    return f"require_object({q(normalise(label))}).\n"


def max_units(n: int) -> str:
    """The tree has at most ``n`` units."""
    if not isinstance(n, int) or n < 0:
        raise InputError(f"--max-units must be a whole number >= 0, not {n!r}")
    return f"max_units({n}).\n"


#: the facts of the convenience flags (encodings/parts/constraints.lp) -> the problem's fact
#: predicates the rules on them read
FLAG_READS: dict[str, tuple[str, ...]] = {
    "forbid_motion": ("motion",),
    "require_motion": ("motion",),
    "forbid_object": ("input", "output", "label"),
    "require_object": ("input", "output", "label"),
    "max_units": (),
}


def _clean(text: str) -> str:
    text = text.replace("[#inc_base];", "").replace("[#inc_base]", "")
    return " ".join(text.split())


def _entries(messages: list[str]) -> list[tuple[re.Match | None, str]]:
    """clingo messages split into entries (location match, full text)."""
    entries: list[list] = []
    for message in messages:
        for line in message.splitlines():
            m = _LOCATION.match(line.strip())
            if m or not entries:
                entries.append([m, line.strip()])
            else:
                entries[-1][1] += " " + line.strip()
    return [(m, text) for m, text in entries]


def clingo_error(messages: list[str], name: str) -> InputError:
    """One-line InputError for clingo's messages about program ``name``:
    ``NAME:3: syntax error, unexpected . (column 5)``, notes appended."""
    entries = _entries(messages)
    if not entries:
        return InputError("clingo rejected the program", name)
    first, whole = entries[0]
    if first is None:
        return InputError(_clean(whole), name)
    text = _clean(whole[first.start("text") :])
    notes = [_clean(t[m.start("text") :]) for m, t in entries[1:] if m and m["kind"] == "note"]
    if notes:
        text += " (" + "; ".join(notes) + ")"
    return InputError(f"{text} (column {first['col']})", name, int(first["line"]))


def check_syntax(name: str, text: str) -> None:
    """Parse and ground ``text`` alone (grounding finds unsafe variables); a located InputError if clingo
    rejects it, or if it would run host code (:func:`~foon2asp.asp.predicates.refuse_host_code`)."""
    refuse_host_code(name, text)
    messages: list[str] = []
    ctl = clingo.Control(["--warn=none"], logger=lambda code, msg: messages.append(msg), message_limit=20)
    try:
        ctl.add("base", [], text)
        ctl.ground([("base", [])])
    except RuntimeError:
        err = clingo_error(messages, name)
        last = max(1, len(text.splitlines()))
        if err.line is not None and err.line > last:
            err.line = last  # clingo places an error at the end of the text on the line after it
            err.message = re.sub(r" \(column \d+\)$", " (at the end)", err.message)
        if "unexpected EOF" in err.message:
            err.message += "; is a '.' missing at the end?"
        raise err from None


#: the convenience flags: (ConstraintSpec field, flag, the program of one value)
_FLAGS = (
    ("forbid_motion", "--forbid-motion", forbid_motion),
    ("forbid_object", "--forbid-object", forbid_object),
    ("require_motion", "--require-motion", require_motion),
    ("require_object", "--require-object", require_object),
)


@dataclass
class ConstraintSpec:
    """The values of the constraint options of a command."""

    files: tuple[str, ...] = ()
    rules: tuple[str, ...] = ()
    forbid_motion: tuple[str, ...] = ()
    forbid_object: tuple[str, ...] = ()
    require_motion: tuple[str, ...] = ()
    require_object: tuple[str, ...] = ()
    max_units: int | None = None
    #: programs given directly as (name, text)
    extra: list[tuple[str, str]] = field(default_factory=list)

    def __bool__(self) -> bool:
        return any(value not in ((), [], None) for value in vars(self).values())

    def programs(self) -> list[tuple[str, str]]:
        """All constraints as (name, text) programs for ``AspOptions.programs``: user files named
        by their path and rules ``--rule #N`` (from 1), checked for errors, then the generated
        programs named after their flag."""
        out = user_programs(self.files, self.rules)
        for name, text in out:
            check_syntax(name, text)
        for name, text in self.extra:
            refuse_host_code(name, text)
        for key, flag, make in _FLAGS:
            for value in getattr(self, key):
                if not normalise(value):
                    raise InputError(f"{flag} needs a non-empty name")
                out.append((f"{flag} {value}", make(value)))
        if self.max_units is not None:
            out.append(("--max-units", max_units(self.max_units)))
        return out + list(self.extra)

    def names(self) -> tuple[list[str], list[str]]:
        """Motions and object labels the convenience flags mention (normalised)."""
        motions = [motion_name(m) for m in (*self.forbid_motion, *self.require_motion)]
        labels = [normalise(x) for x in (*self.forbid_object, *self.require_object)]
        return motions, labels


#: programs read from standard input (``-``) or a pipe (``<(...)``), which can be read only once
_STREAMS: dict[str, str] = {}


def read_file(path: str, what: str = "constraint file") -> str:
    """The text of an ASP file; ``what`` names it in errors (a constraint file, a program).

    ``-`` is standard input and a pipe (``--constraint <(...)``, ``/dev/fd/63``) is read like a
    file; both are read once and remembered, as they cannot be read again."""
    path = str(path)
    if path in _STREAMS:
        return _STREAMS[path]
    if path == "-":
        if sys.stdin is None or sys.stdin.isatty():
            raise InputError(f"{what} '-' is standard input, and it is a terminal: pipe the program into it")
        data = sys.stdin.buffer.read()
        try:
            text = _STREAMS[path] = data.decode("utf-8").removeprefix("\ufeff")
        except UnicodeDecodeError as exc:
            raise InputError(f"not UTF-8 text: byte 0x{data[exc.start]:02x} at byte offset {exc.start}", "-") from None
        return text
    p = Path(path)
    if p.is_dir():
        raise InputError(f"{what} is a directory, not a file", path)
    if not p.exists():
        raise not_found(path, what.removesuffix(" file"))
    text = read_text(p, what.removesuffix(" file"), checked=False)
    if not p.is_file():
        _STREAMS[path] = text
    return text


def user_programs(files: Iterable[str] = (), rules: Iterable[str] = ()) -> list[tuple[str, str]]:
    """The user's files (named by their path) and rules (``--rule #N``, from 1) as (name, text), unchecked."""
    out = [(str(path), read_file(path)) for path in files]
    return out + [(f"--rule #{n}", rule) for n, rule in enumerate(rules, 1)]


def unknown_names(problem, spec: ConstraintSpec) -> list[str]:
    """Warnings for flag values that match no motion or label, and for predicates the user's files
    and rules use that are defined nowhere."""
    motions, labels = spec.names()
    have_m = {u.motion for u in problem.units}
    have_l = problem.foon.labels()
    out = [f"no unit has motion {m!r}" for m in motions if m not in have_m]
    out += [f"no object is labelled {lab!r}" for lab in labels if lab not in have_l]
    return out + rule_warnings(user_programs(spec.files, spec.rules) + list(spec.extra))
