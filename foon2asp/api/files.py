"""Files the library reads and writes besides a data folder: FOON files (read and merged, written
in a FOON dialect or FOON JSON), ASP programs, drawings of tree files, and output files."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from foon2asp.analysis.check import read_and_check
from foon2asp.api.kb import KnowledgeBase
from foon2asp.asp.constraints import read_file
from foon2asp.errors import InputError
from foon2asp.foon import foonjson, parser
from foon2asp.foon.model import Foon
from foon2asp.report import draw

#: the formats :func:`write_foon` writes: the official dialect with ids, the dialect without ids, FOON JSON
FOON_FORMATS = ("foon", "foon-plain", "foon-json")


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
    """FOON files (text in either dialect, or FOON JSON) merged into one FOON, duplicate units once;
    ``strict``: a unit skipped with a warning is an error.  The warnings are ``.warnings``."""
    names = [str(p) for p in paths]
    for name in names:
        if not Path(name).is_file():
            raise InputError("FOON file not found", name)
    return parser.read_foons(names, strict)


def write_foon(foon: Foon, path: str | Path, fmt: str = "foon", header: str | None = None) -> None:
    """Write ``foon`` to ``path`` (its directory created) in a format of :data:`FOON_FORMATS`."""
    if fmt not in FOON_FORMATS:
        raise InputError(f"unknown FOON format {fmt!r} (have {', '.join(FOON_FORMATS)})")
    if Path(path).parent != Path("."):
        writable_dir(Path(path).parent)
    try:
        with open(path, "w", encoding="utf-8") as fh:
            if fmt == "foon-json":
                fh.write(foonjson.dumps(foon.units, parser.id_map(foon), header))
            else:
                parser.write_foon(foon, fh, header=header, dialect="plain" if fmt == "foon-plain" else "official")
    except OSError as exc:
        raise InputError(f"cannot write the output file: {exc.strerror or exc}", str(path)) from None


def read_program(path: str | Path) -> str:
    """The text of an ASP program file (for :meth:`KnowledgeBase.query`)."""
    return read_file(str(path))


def draw_file(
    tree: str | Path,
    output: str | Path,
    *,
    fmt: str | None = None,
    kb: KnowledgeBase | None = None,
    goal: str | None = None,
) -> int:
    """Draw every tree of a tree file (any format :meth:`KnowledgeBase.check` reads) into ``output``;
    the format follows the extension unless ``fmt`` names one.  With ``kb`` the trees are checked:
    the goal (``goal``, else as :meth:`KnowledgeBase.check` finds it) is gold, kitchen items green,
    a blocking cycle red.  Returns how many trees were drawn."""
    fmt = fmt or draw.format_of(output)
    if fmt != "dot":
        draw.require_dot()
    data, problem = (kb.data, kb.problem) if kb is not None else (None, None)
    trees, reports = read_and_check(tree, data, problem, goal)
    Path(output).write_bytes(draw.render(draw.file_graph(trees, reports, problem), fmt))
    return len(trees)
