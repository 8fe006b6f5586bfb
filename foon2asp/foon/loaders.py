"""Loaders for the files beside a FOON: kitchen, goals, motion rates, utensils.

A data directory holds the files :data:`FILE_NAMES` names; :class:`Dataset` bundles what was read.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from foon2asp.errors import InputError
from foon2asp.foon.foonjson import object_from_json
from foon2asp.foon.model import LEAVES, Foon, FoonObject, leaves, norm
from foon2asp.foon.parser import read_foons
from foon2asp.foon.reading import (
    content_lines,
    json_list,
    line_numbers,
    lines_of,
    name_and_value,
    not_found,
    read_text,
)

#: the files of a data directory
FILE_NAMES = {
    "foon": "FOON.txt",
    "kitchen": "kitchen.json",
    "goals": "goal_nodes.json",
    "motion": "motion.txt",
    "utensils": "utensils.txt",
}
#: the demo data set in the source tree (``foon2asp.demo`` when installed)
_DEMO_SOURCE = Path(__file__).resolve().parents[2] / "data"
#: what a missing or empty motion file means
DEFAULT_RATE_NOTE = "every motion gets the default success rate 0.5"


def demo_dir() -> Path:
    """The folder holding the demo FOON.txt, kitchen.json, goal_nodes.json, motion.txt, utensils.txt."""
    try:
        # an installed namespace package is a MultiplexedPath: go through one of its files
        probe = Path(str(resources.files("foon2asp.demo").joinpath("FOON.txt")))
        if probe.is_file():
            return probe.parent
    except ModuleNotFoundError:
        pass
    return _DEMO_SOURCE


def check_foon_file(path: str | Path) -> None:
    """An error naming ``path`` when it is not a FOON file that can be read: missing, a directory, not a file."""
    path = Path(path)
    if path.is_file():
        return
    if path.is_dir():
        raise InputError("FOON file is a directory, not a file", str(path))
    if path.exists():
        raise InputError("FOON file is not a regular file", str(path))
    raise not_found(path, "FOON")


def read_foon_files(paths: list[str], strict: bool = False) -> Foon:
    """The FOON files ``paths`` merged (:func:`foon2asp.foon.parser.read_foons`); an error naming
    them when there is no functional unit in them."""
    for p in paths:
        check_foon_file(p)
    foon = read_foons(paths, strict)
    if not foon.units:
        skipped = f" ({len(foon.warnings)} skipped, first: {foon.warnings[0]})" if foon.warnings else ""
        if len(paths) == 1:
            raise InputError(f"FOON file has no functional units{skipped}", paths[0])
        raise InputError(f"none of the FOON files {', '.join(paths)} has a functional unit{skipped}")
    return foon


def read_objects(path: str | Path, what: str) -> list[tuple[FoonObject, int]]:
    """The objects of a JSON list (goal_nodes.json, kitchen.json), each with the line it starts on."""
    text = read_text(path, what)
    value, tops = json_list(text, str(path), checked=True)
    lines = line_numbers(text, tops)
    return [(object_from_json(v, str(path), line), line) for v, line in zip(value, lines)]


def read_kitchen(path: str | Path) -> list[FoonObject]:
    return [obj for obj, _ in read_objects(path, "kitchen")]


def read_goals(path: str | Path) -> list[tuple[FoonObject, int]]:
    return read_objects(path, "goals")


def read_motion(path: str | Path, warnings: list[str] | None = None) -> dict[str, float]:
    """``motion TAB success-rate`` per line, rates in (0, 1]; blank and ``#`` lines skipped.
    A file without any rate is warned about (into ``warnings``)."""
    rates: dict[str, float] = {}
    for lineno, line in content_lines(read_text(path, "motion")):
        parts = name_and_value(line)
        if len(parts) != 2:
            raise InputError(f"expected 'motion<TAB>rate', got {line.strip()!r}", str(path), lineno)
        try:
            rate = float(parts[1])
        except ValueError:
            raise InputError(f"success rate {parts[1].strip()!r} is not a number", str(path), lineno) from None
        if not 0.0 < rate <= 1.0:
            raise InputError(f"success rate {rate} is not in (0, 1]", str(path), lineno)
        rates[norm(parts[0])] = rate
    if not rates and warnings is not None:
        warnings.append(f"{path}: no success rate in the file: {DEFAULT_RATE_NOTE}")
    return rates


def read_utensils(path: str | Path, warnings: list[str] | None = None) -> frozenset[str]:
    """One utensil label per line; blank and ``#`` lines skipped, and a comment that looks
    like a label (``#mixing bowl``) warned about (into ``warnings``)."""
    out: set[str] = set()
    for lineno, line in enumerate(lines_of(read_text(path, "utensils")), 1):
        if not line.strip():
            continue
        if line.lstrip().startswith("#"):
            if line.lstrip()[1:2].isalnum() and warnings is not None:
                warnings.append(
                    f"{path}:{lineno}: line ignored: '#' starts a comment (a utensil label cannot begin with '#')"
                )
            continue
        out.add(norm(line))
    return frozenset(out)


@dataclass
class Dataset:
    """Everything read from a data directory (or individual files)."""

    foon: Foon
    kitchen: list[FoonObject]
    goals: list[tuple[FoonObject, int]] = field(default_factory=list)
    motion: dict[str, float] = field(default_factory=dict)
    utensils: frozenset[str] = frozenset()
    paths: dict[str, str] = field(default_factory=dict)
    #: warnings about the motion and utensil files (comment lines that look like labels, no rates)
    warnings: list[str] = field(default_factory=list)
    #: the files looked for beside the FOON and not there (``"goals"`` -> its path)
    looked_for: dict[str, str] = field(default_factory=dict)

    @classmethod
    def load(
        cls,
        data_dir: str | Path | None = None,
        *,
        foon: str | Path | list | None = None,
        kitchen: str | Path | None = None,
        goals: str | Path | None = None,
        motion: str | Path | None = None,
        utensils: str | Path | None = None,
        strict: bool = False,
    ) -> Dataset:
        """Read a data directory; explicit file arguments override its files.  ``FOON.txt``
        (with a unit) and ``kitchen.json`` are required, the others optional (a missing
        ``motion.txt`` is warned about); ``kitchen="leaves"`` takes the FOON's leaves."""
        base = Path(data_dir) if data_dir is not None else None
        given = {"foon": foon, "kitchen": kitchen, "goals": goals, "motion": motion, "utensils": utensils}
        paths: dict[str, str] = {}
        looked_for: dict[str, str] = {}
        for key, value in given.items():
            if value is not None:
                paths[key] = ",".join(map(str, value)) if isinstance(value, list) else str(value)
            elif base is not None and (key == "foon" or os.path.lexists(base / FILE_NAMES[key])):
                paths[key] = str(base / FILE_NAMES[key])  # a broken link is read, and named as such
            elif base is not None:
                looked_for[key] = str(base / FILE_NAMES[key])
        if base is not None and not base.is_dir():
            raise InputError(
                "data directory is a file, not a directory" if base.exists() else "data directory not found", str(base)
            )
        if "foon" not in paths:
            raise InputError(f"no {FILE_NAMES['foon']} given (use --data DIR or --foon FILE)")
        if "kitchen" not in paths and "kitchen" not in looked_for:
            raise InputError(f"no {FILE_NAMES['kitchen']} given (use --data DIR or --kitchen FILE)")
        units = read_foon_files([str(p) for p in foon] if isinstance(foon, list) else [paths["foon"]], strict)
        if "kitchen" in looked_for:
            raise InputError(
                "kitchen file not found in the data folder; give a kitchen file, or kitchen='leaves' (every object"
                " no unit makes, e.g. for merged generated trees)",
                looked_for["kitchen"],
                hint="kitchen-data",
            )
        warnings: list[str] = []
        if base is not None and "motion" not in paths:
            warnings.append(f"{base / FILE_NAMES['motion']}: no such file in the data directory: {DEFAULT_RATE_NOTE}")
        return cls(
            foon=units,
            kitchen=leaves(units) if paths["kitchen"] == LEAVES else read_kitchen(paths["kitchen"]),
            goals=read_goals(paths["goals"]) if "goals" in paths else [],
            motion=read_motion(paths["motion"], warnings) if "motion" in paths else {},
            utensils=read_utensils(paths["utensils"], warnings) if "utensils" in paths else frozenset(),
            paths=paths,
            warnings=warnings,
            looked_for=looked_for,
        )
