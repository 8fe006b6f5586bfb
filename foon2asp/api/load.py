"""Reading a data folder, or FOON files with the files beside them, into a :class:`KnowledgeBase`;
FOON files read, merged, compared loosely and written, and ASP program files read."""

from __future__ import annotations

import io
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

from foon2asp.api.kb import KnowledgeBase
from foon2asp.api.request import check_keywords
from foon2asp.api.results import write_file
from foon2asp.asp.constraints import read_file
from foon2asp.errors import InputError
from foon2asp.foon import foonjson, parser, unitlist
from foon2asp.foon.loaders import FILE_NAMES, Dataset, check_foon_file, demo_dir
from foon2asp.foon.matching import Projection, Texts, parse_synonyms, project_dataset, read_synonyms
from foon2asp.foon.model import LEAVES, Foon
from foon2asp.foon.problem import Problem
from foon2asp.foon.substitutes import LINE_BREAKS

#: the formats :func:`write_foon` writes: the official dialect with ids, the dialect without ids, FOON JSON,
#: the unit-list JSON of generated trees (:mod:`foon2asp.foon.unitlist`)
FOON_FORMATS = ("foon", "foon-plain", "foon-json", "units-json")

#: what is lost when a file is not beside the FOON
_WITHOUT = {
    "goals": "no goals file: name goals with --goal or --goals FILE",
    "motion": "every motion gets success rate 0.5",
    "utensils": "no object is treated as a utensil",
}


@dataclass(frozen=True)
class Reading:
    """How the files beside a FOON are read and its objects compared: the keywords of :func:`load`
    (and of :func:`foon2asp.api.consolidate`) besides the FOON and the goals."""

    #: a kitchen file, or ``"leaves"``: every object no unit makes
    kitchen: str | Path | None = None
    motion: str | Path | None = None
    utensils: str | Path | None = None
    #: when a utensil holding one ingredient is not a required input (``foon2asp.api.UTENSIL_RULES``)
    utensil_rule: str = "starter"
    #: a unit skipped with a warning is an error
    strict: bool = False
    #: FOON's hierarchy level objects are compared at: 1 labels, 2 with states and container, 3 also ingredients
    level: int = 3
    #: texts compared case-folded, white space collapsed, the last word singular
    normalize: bool = False
    #: ``name = canonical name`` lines (a file) or a mapping: names compared as one
    synonyms: str | Path | Mapping[str, str] | None = None

    @classmethod
    def of(cls, keywords: dict[str, Any]) -> Reading:
        """The reading the keywords of ``keywords`` name, taken out of it."""
        return cls(**{f.name: keywords.pop(f.name) for f in fields(cls) if f.name in keywords})

    def projection(self) -> Projection:
        """How objects are compared (checked before any FOON is read; :class:`foon2asp.foon.matching.Projection`)."""
        level, normalize, synonyms = self.level, self.normalize, self.synonyms
        if isinstance(level, bool) or level not in (1, 2, 3):
            raise InputError(f"--level must be 1, 2 or 3, not {level!r}")
        if synonyms is None:
            table: dict[str, str] = {}
        elif isinstance(synonyms, Mapping):
            for text in (t for pair in synonyms.items() for t in pair):
                if not isinstance(text, str) or any(c in LINE_BREAKS for c in text):
                    raise InputError(f"synonyms: a name must be a string without line breaks, not {text!r}")
            text = "".join(f"{name} = {canonical}\n" for name, canonical in synonyms.items())
            table = parse_synonyms(text, "synonyms", normalize)
        else:
            table = read_synonyms(synonyms, normalize)
        return Projection(level, Texts(normalize, table))


def load(
    path: str | Path | None = None,
    *,
    foon: str | Path | Sequence[str | Path] | None = None,
    goals: str | Path | None = None,
    **reading: Any,
) -> KnowledgeBase:
    """Read a data folder or ``"demo"``, or ``foon`` files with the files beside them (docs/api.md);
    ``reading``: the fields of :class:`Reading`."""
    check_keywords(reading, [f.name for f in fields(Reading)], "load(): ")
    how = Reading(**reading)
    seen_as = how.projection()
    if path == "demo":
        path = demo_dir()
    if path is None and foon is None:
        raise InputError("no data given: load(DIR), load('demo') or load(foon=FILE, kitchen=FILE, ...)")
    given = None if foon is None else [str(f) for f in foon] if isinstance(foon, list | tuple) else str(foon)
    files = {"kitchen": how.kitchen, "goals": goals, "motion": how.motion, "utensils": how.utensils}
    beside: list[str] = []
    looked_for: dict[str, str] = {}
    if path is None and given:
        foons = [given] if isinstance(given, str) else given
        for name in foons:
            check_foon_file(name)  # a mistyped FOON path is named itself, not the files beside it
        first = Path(foons[0])
        for key in [k for k, v in files.items() if v is None]:
            candidate = first.parent / FILE_NAMES[key]
            if os.path.lexists(candidate):  # a directory or a broken link there is an error naming it when read
                files[key] = str(candidate)
            elif key == "kitchen":
                raise InputError(
                    f"no {FILE_NAMES[key]} beside the FOON file (looked for {candidate});"
                    " give a kitchen file, kitchen='leaves' (every object no unit makes: merged generated"
                    " trees have no kitchen) or a data folder ('demo' for the demo data)",
                    hint=f"kitchen={candidate}",
                )
            else:
                looked_for[key] = str(candidate)
                beside.append(f"no {FILE_NAMES[key]} beside {first}: {_WITHOUT[key]}")
    data = Dataset.load(path, foon=given, strict=how.strict, **files)
    data.looked_for.update(looked_for)
    return knowledge_base(data, how.utensil_rule, beside, seen_as)


def knowledge_base(
    data: Dataset, utensil_rule: str = "starter", warnings: Sequence[str] = (), seen_as: Projection | None = None
) -> KnowledgeBase:
    """The knowledge base of data read already, with the warnings about it (and ``warnings``), as ``seen_as`` sees it."""
    seen_as = seen_as or Projection()
    if not seen_as.identity:
        data, seen_as = project_dataset(data, seen_as.level, seen_as.texts.normalize, seen_as.texts.synonyms)
    problem = Problem.from_dataset(data, utensil_rule)
    found = list(data.foon.warnings) + list(data.warnings) + list(warnings)
    unknown = problem.unknown_motions()
    if data.motion and unknown:
        found.append(
            f"{len(unknown)} motion(s) not in {data.paths.get('motion') or 'the motion file'} get success rate 0.5:"
            f" {', '.join(unknown[:5])}"
        )
    if not data.kitchen:
        kitchen = data.paths.get("kitchen")
        where = "" if kitchen in (None, LEAVES) else f"{kitchen}: "
        why = " (every object of the FOON is made by some unit)" if kitchen == LEAVES else ""
        found.append(f"{where}the kitchen is empty{why}: no unit can start, so every goal is unreachable")
    return KnowledgeBase(data, problem, tuple(found), seen_as)


def read_foons(paths: Iterable[str | Path], strict: bool = False) -> Foon:
    """FOON files (text, FOON JSON or unit-list JSON) merged into one FOON, duplicate units once,
    with ``.warnings``; ``strict``: a unit skipped with a warning is an error."""
    names = [str(p) for p in paths]
    for name in names:
        check_foon_file(name)
    return parser.read_foons(names, strict)


def match_foon(
    foon: Foon, level: int = 3, normalize: bool = False, synonyms: str | Path | Mapping[str, str] | None = None
) -> tuple[Foon, dict[str, list[str]]]:
    """``foon`` as ``level``, ``normalize`` and ``synonyms`` see it (:func:`load`), and the spellings joined."""
    found = Reading(level=level, normalize=normalize, synonyms=synonyms).projection()
    if found.identity:
        return foon, {}
    return found.foon(foon), {first: list(every) for first, every in found.texts_joined.items()}


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
