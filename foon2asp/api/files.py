"""Files the library reads and writes besides a data folder: FOON files (read and merged, written
in a FOON dialect or FOON JSON), ASP programs and output files."""

from __future__ import annotations

import io
from collections.abc import Iterable, Mapping
from pathlib import Path

from foon2asp.api.matching import joined, projection
from foon2asp.asp.constraints import read_file
from foon2asp.errors import InputError
from foon2asp.foon import foonjson, parser, unitlist
from foon2asp.foon.model import Foon

#: the formats :func:`write_foon` writes: the official dialect with ids, the dialect without ids, FOON JSON,
#: the unit-list JSON of generated trees (:mod:`foon2asp.foon.unitlist`)
FOON_FORMATS = ("foon", "foon-plain", "foon-json", "units-json")


def writable_dir(path: str | Path) -> Path:
    """``path`` as a directory, created with its parents (an error names the path)."""
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create the output directory: {exc.strerror or exc}", str(out)) from None
    if not out.is_dir():
        raise InputError("output path is not a directory", str(out))
    return out


def write_file(path: str | Path, text: str | bytes) -> None:
    """Write ``text`` to ``path``, creating its directory (an error names the path)."""
    out = Path(path)
    if out.parent != Path("."):
        writable_dir(out.parent)
    try:
        if isinstance(text, bytes):
            out.write_bytes(text)
        else:
            out.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot write the output file: {exc.strerror or exc}", str(out)) from None


def read_foons(paths: Iterable[str | Path], strict: bool = False) -> Foon:
    """FOON files (text, FOON JSON or unit-list JSON) merged into one FOON, duplicate units once,
    with ``.warnings``; ``strict``: a unit skipped with a warning is an error."""
    names = [str(p) for p in paths]
    for name in names:
        if not Path(name).is_file():
            raise InputError("FOON file not found", name)
    return parser.read_foons(names, strict)


def match_foon(
    foon: Foon,
    level: int = 3,
    normalize: bool = False,
    synonyms: str | Path | Mapping[str, str] | None = None,
) -> tuple[Foon, dict[str, list[str]]]:
    """``foon`` as hierarchy ``level`` with ``normalize``/``synonyms`` sees it (see :func:`load`):
    units equal there are one unit; and the spellings joined (first spelling -> every spelling)."""
    found = projection(level, normalize, synonyms)
    if found.identity:
        return foon, {}
    out = found.foon(foon)
    return out, joined(found)


def write_foon(foon: Foon, path: str | Path, fmt: str = "foon", header: str | None = None) -> None:
    """Write ``foon`` to ``path`` (its directory created) in a format of :data:`FOON_FORMATS`."""
    if fmt not in FOON_FORMATS:
        raise InputError(f"unknown FOON format {fmt!r} (have {', '.join(FOON_FORMATS)})")
    if fmt == "foon-json":
        text = foonjson.dumps(foon.units, parser.id_map(foon), header)
    elif fmt == "units-json":
        text = unitlist.dumps(foon.units)
    else:
        out = io.StringIO()
        parser.write_foon(foon, out, header=header, dialect="plain" if fmt == "foon-plain" else "official")
        text = out.getvalue()
    write_file(path, text)


def read_program(path: str | Path) -> str:
    """The text of an ASP program file (for :meth:`KnowledgeBase.query`)."""
    return read_file(str(path), "ASP program file")
