"""Reading a data folder, or FOON files with the files beside them, into a :class:`KnowledgeBase`."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from foon2asp.api.kb import KnowledgeBase
from foon2asp.api.matching import projection
from foon2asp.errors import InputError
from foon2asp.foon.demo import demo_dir
from foon2asp.foon.leaves import LEAVES
from foon2asp.foon.loaders import FILE_NAMES, Dataset, check_foon_file
from foon2asp.foon.matching import Projection, project_dataset
from foon2asp.foon.problem import Problem

#: what is lost when a file is not beside the FOON
_WITHOUT = {
    "goals": "no goals file: name goals with --goal or --goals FILE",
    "motion": "every motion gets success rate 0.5",
    "utensils": "no object is treated as a utensil",
}


def _beside(foon: Path, given: dict, warnings: list[str]) -> dict:
    """``given`` with the files not given taken from beside ``foon``; warnings for absent optional ones."""
    out = dict(given)
    for key, value in given.items():
        if value is not None:
            continue
        candidate = foon.parent / FILE_NAMES[key]
        if candidate.exists():  # a directory there is an error naming it when it is read
            out[key] = str(candidate)
        elif key == "kitchen":
            raise InputError(
                f"no {FILE_NAMES[key]} beside the FOON file (looked for {candidate});"
                " give a kitchen file, kitchen='leaves' (every object no unit makes: merged generated"
                " trees have no kitchen) or a data folder ('demo' for the demo data)",
                hint=f"kitchen={candidate}",
            )
        else:
            warnings.append(f"no {FILE_NAMES[key]} beside {foon}: {_WITHOUT[key]}")
    return out


def load(
    path: str | Path | None = None,
    *,
    foon: str | Path | Sequence[str | Path] | None = None,
    kitchen: str | Path | None = None,
    goals: str | Path | None = None,
    motion: str | Path | None = None,
    utensils: str | Path | None = None,
    utensil_rule: str = "starter",
    strict: bool = False,
    level: int = 3,
    normalize: bool = False,
    synonyms: str | Path | Mapping[str, str] | None = None,
) -> KnowledgeBase:
    """Read a data folder (``FOON.txt``, ``kitchen.json``, ``goal_nodes.json``, ``motion.txt``,
    ``utensils.txt``) or ``"demo"``; keyword files override its files.  With ``foon`` and no
    folder, the others are read from beside the first FOON file (no kitchen there is an error).
    ``kitchen="leaves"``: every object no unit makes.  ``level`` (1 labels, 2 with states and
    container, 3 also ingredients), ``normalize`` and ``synonyms``: how objects are compared."""
    seen_as = projection(level, normalize, synonyms)
    if path == "demo":
        path = demo_dir()
    if path is None and foon is None:
        raise InputError("no data given: load(DIR), load('demo') or load(foon=FILE, kitchen=FILE, ...)")
    foon_paths: str | list | None = (
        [str(f) for f in foon] if isinstance(foon, list | tuple) else (None if foon is None else str(foon))
    )
    beside: list[str] = []
    if path is None and foon_paths:
        for name in foon_paths if isinstance(foon_paths, list) else [foon_paths]:
            check_foon_file(name)  # a mistyped FOON path is named itself, not the files beside it
        first = Path(foon_paths[0] if isinstance(foon_paths, list) else foon_paths)
        found = _beside(first, {"kitchen": kitchen, "goals": goals, "motion": motion, "utensils": utensils}, beside)
        kitchen, goals, motion, utensils = found["kitchen"], found["goals"], found["motion"], found["utensils"]
    data = Dataset.load(
        path, foon=foon_paths, kitchen=kitchen, goals=goals, motion=motion, utensils=utensils, strict=strict
    )
    return knowledge_base(data, utensil_rule, beside, seen_as)


def knowledge_base(
    data: Dataset,
    utensil_rule: str = "starter",
    warnings: Sequence[str] = (),
    seen_as: Projection | None = None,
) -> KnowledgeBase:
    """The knowledge base of data read already, with the warnings about it (and ``warnings``), as
    ``seen_as`` sees it (default: level 3, texts as spelled)."""
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
