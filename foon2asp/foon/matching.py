"""Looser matching: FOON's hierarchy levels, label normalisation and synonyms, as a projection.

Level 1 compares labels, level 2 also states and container, level 3 also ingredients
(foon2asp's identity).  :class:`Projection` maps each object to the one its level sees and a
FOON to the FOON of the projected units; texts compare by a :class:`Texts` key.
docs/matching.md says why these choices.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Iterable
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path
from typing import Any

from foon2asp.errors import InputError
from foon2asp.foon.loaders import Dataset
from foon2asp.foon.model import Foon, FoonObject, Unit, norm, state_parts
from foon2asp.foon.reading import content_lines, read_text
from foon2asp.foon.substitutes import Substitute

LEVELS = (1, 2, 3)

#: a word the singular is looked up for (letters, inner hyphens or apostrophes)
_WORD = re.compile(r"[^\W\d_]+(?:['-][^\W\d_]+)*")


@lru_cache(maxsize=1)
def _engine() -> Any:
    """inflect's engine, imported on first use (only ``--normalize`` needs it) with typeguard's
    ``@typechecked`` as the identity (docs/proofs/preparation.md, "Singular nouns")."""
    if sys.modules.get("inflect") is None:
        try:
            import typeguard
        except ImportError:  # pragma: no cover - an inflect without typeguard
            _import_inflect()
        else:
            saved = typeguard.typechecked
            setattr(typeguard, "typechecked", _no_check)  # noqa: B010
            try:
                _import_inflect()
            finally:
                setattr(typeguard, "typechecked", saved)  # noqa: B010
    return sys.modules["inflect"].engine()


def _import_inflect() -> None:
    """Import inflect, the optional dependency of ``--normalize`` (the ``normalize`` extra)."""
    try:
        import inflect  # noqa: F401
    except ImportError:
        raise InputError(
            "--normalize needs the inflect package: pip install 'foon2asp[normalize]' (or inflect)"
        ) from None


def _no_check(target: Any = None, **_: Any) -> Any:
    """``typeguard.typechecked`` as the identity (see :func:`_engine`)."""
    return target if target is not None else (lambda f: f)


@lru_cache(maxsize=65536)
def noun_key(word: str) -> str:
    """The singular of an English noun as ``inflect`` makes it, the same for both forms: a
    plural's ``singular_noun``, a singular's the ``singular_noun`` of its ``plural_noun``
    (so ``smoothie`` and ``smoothies`` both key ``smoothy``); ``word`` itself for words
    inflect has no plural for, or that are not words."""
    if not _WORD.fullmatch(word):
        return word
    engine = _engine()
    one = engine.singular_noun(word)
    if not one:
        plural = engine.plural_noun(word)
        one = engine.singular_noun(plural) if plural else False
    return one if isinstance(one, str) and one else word


def key_last(text: str) -> str:
    """``text`` with :func:`noun_key` of its last word (``"fresh blueberries"`` -> ``"fresh blueberry"``)."""
    head, _, last = text.rpartition(" ")
    one = noun_key(last)
    return text if one == last else (f"{head} {one}" if head else one)


@dataclass(frozen=True)
class LevelUnit(Unit):
    """A unit projected to level 1 or 2: its products are listed (``made``), not read
    off the outputs (a projected output may be bare though it was made)."""

    made: frozenset[FoonObject] = frozenset()


class Texts:
    """The comparison key of a text: normalised, optionally in the singular, then synonyms."""

    def __init__(self, normalize: bool = False, synonyms: dict[str, str] | None = None):
        self.normalize = normalize
        #: key -> canonical key (both sides normalised as keys are)
        self.synonyms = dict(synonyms or {})
        self._memo: dict[str, str] = {}

    @property
    def plain(self) -> bool:
        """Are texts compared as foon2asp always compares them?"""
        return not self.normalize and not self.synonyms

    def base(self, text: str) -> str:
        """The key before synonyms: normalised text, the last word singular with ``normalize``."""
        text = norm(text)
        return key_last(text) if self.normalize and text else text

    def key(self, text: str) -> str:
        """The key of a label, ingredient, container or plain state."""
        got = self._memo.get(text)
        if got is None:
            base = self.base(text)
            got = self._memo[text] = self.synonyms.get(base, base)
        return got

    def state_key(self, state: str) -> str:
        """The key of a state; a relation state (``on [plates]``) keys its related objects as labels."""
        name, arg = state_parts(state)
        if arg is None:
            return self.key(state)
        inner = ",".join(self.key(part) for part in arg[1:-1].split(","))
        return f"{self.key(name)} {arg[0]}{inner}{arg[-1]}"


def parse_synonyms(text: str, path: str = "<synonyms>", normalize: bool = False) -> dict[str, str]:
    """Synonyms from lines ``name = canonical name`` (``#`` comments) as key -> canonical key,
    both keyed as :class:`Texts` keys them, chains resolved (``a = b``, ``b = c``: a -> c).
    A name given two canonical names, or a cycle, is an error naming the file and line."""
    texts = Texts(normalize)
    table: dict[str, str] = {}
    lines: dict[str, int] = {}
    for lineno, line in content_lines(text):
        body = line.strip()
        name, eq, canonical = body.partition("=")
        if not eq:
            raise InputError(f"expected 'name = canonical name', got {body[:60]!r}", path, lineno)
        name, canonical = texts.base(name), texts.base(canonical)
        if not name or not canonical:
            raise InputError("a synonym needs a name on both sides of '='", path, lineno)
        if name == canonical:
            continue
        if name in table and table[name] != canonical:
            raise InputError(
                f"{name!r} is already a synonym of {table[name]!r} (line {lines[name]}), not also of {canonical!r}",
                path,
                lineno,
            )
        table[name] = canonical
        lines.setdefault(name, lineno)
    resolved: dict[str, str] = {}
    for name in table:
        seen = [name]
        target = table[name]
        while target in table:
            if target in seen:
                cycle = " = ".join([*seen[seen.index(target) :], target])
                raise InputError(f"synonyms form a cycle: {cycle}", path, lines[name])
            seen.append(target)
            target = table[target]
        resolved[name] = target
    return resolved


def read_synonyms(path: str | Path, normalize: bool = False) -> dict[str, str]:
    """The synonyms file ``path`` (see :func:`parse_synonyms`)."""
    return parse_synonyms(read_text(path, "synonyms"), str(path), normalize)


class Projection:
    """Objects and units as a hierarchy level with a text key sees them."""

    def __init__(self, level: int = 3, texts: Texts | None = None):
        if level not in LEVELS:
            raise InputError(f"--level must be 1, 2 or 3, not {level!r}")
        self.level = level
        self.texts = texts or Texts()
        #: level 3 with plain texts: every object is itself
        self.identity = level == 3 and self.texts.plain
        self._labels: dict[str, str] = {}  # key -> first spelling (labels, ingredients, containers)
        self._states: dict[str, str] = {}  # key -> first spelling (states)
        self._memo: dict[FoonObject, FoonObject] = {}
        #: first spelling -> every spelling joined into it, first first (only texts with others)
        self.texts_joined: dict[str, list[str]] = {}
        #: projected object -> the texts of the objects it stands for, in the order seen
        self.sources: dict[FoonObject, list[str]] = {}

    def _spell(self, table: dict[str, str], key: str, text: str) -> str:
        first = table.setdefault(key, text)
        if first != text:
            joined = self.texts_joined.setdefault(first, [first])
            if text not in joined:
                joined.append(text)
        return first

    def label(self, text: str) -> str:
        """The spelling of a label (ingredient, container) as the projection writes it."""
        text = norm(text)
        return text if self.texts.plain else self._spell(self._labels, self.texts.key(text), text)

    def state(self, text: str) -> str:
        """The spelling of a state as the projection writes it."""
        text = norm(text)
        return text if self.texts.plain else self._spell(self._states, self.texts.state_key(text), text)

    def object(self, obj: FoonObject) -> FoonObject:
        """The object ``obj`` is at this level (the same object for all objects equal at the level)."""
        if self.identity:
            return obj
        got = self._memo.get(obj)
        if got is None:
            states: tuple[str, ...] = ()
            ingredients: tuple[str, ...] = ()
            container = None
            if self.level >= 2:
                states = tuple(sorted({self.state(s) for s in obj.states}))
                container = self.label(obj.container) if obj.container else None
            if self.level == 3:
                ingredients = tuple(sorted({self.label(i) for i in obj.ingredients}))
            got = self._memo[obj] = FoonObject(self.label(obj.label), states, ingredients, container)
            self.sources.setdefault(got, []).append(obj.text)
        return got

    def objects(self, objs: Iterable[FoonObject]) -> list[FoonObject]:
        """Each projected object once, in first-seen order."""
        return list(dict.fromkeys(self.object(o) for o in objs))

    def unit(self, unit: Unit) -> Unit:
        """``unit`` at this level: inputs and outputs projected (each once); at levels 1 and 2
        a :class:`LevelUnit` listing its products."""
        ins = tuple(self.objects(unit.inputs))
        outs = tuple(self.objects(unit.outputs))
        if self.level == 3:
            return Unit(unit.motion, ins, outs)
        made = frozenset(self.object(o) for o in unit.outputs if not o.is_bare()).difference(ins)
        return LevelUnit(unit.motion, ins, outs, made)

    def foon(self, foon: Foon) -> Foon:
        """The FOON of the projected units (units equal at the level are one unit; a unit
        merged from several makes what any of them makes)."""
        if self.identity:
            return foon
        out = Foon(warnings=list(foon.warnings), ids={kind: dict(t) for kind, t in foon.ids.items()})
        for unit, origin in zip(foon.units, foon.origins):
            projected = self.unit(unit)
            before = len(out.units)
            uid = out.add_unit(projected, origin)
            kept = out.units[uid]
            if uid < before and isinstance(projected, LevelUnit) and isinstance(kept, LevelUnit):
                if not projected.made <= kept.made:
                    out.units[uid] = replace(kept, made=kept.made | projected.made)
        return out

    def utensils(self, utensils: Iterable[str]) -> frozenset[str]:
        """Utensil labels spelled as the projection spells labels."""
        return frozenset(self.label(u) for u in utensils)

    def substitutes(self, substitutes: Iterable[Substitute]) -> tuple[Substitute, ...]:
        """Substitutes with their labels spelled as the projection spells labels (pairs that
        become one keep the cheaper cost; a label that becomes its own substitute is dropped)."""
        out: dict[tuple[str, str], Substitute] = {}
        for s in substitutes:
            needed, used = self.label(s.needed), self.label(s.used)
            if needed != used and ((needed, used) not in out or s.cost < out[(needed, used)].cost):
                out[(needed, used)] = Substitute(needed, used, s.cost)
        return tuple(out.values())


def project_dataset(
    data: Dataset, level: int = 3, normalize: bool = False, synonyms: dict[str, str] | None = None
) -> tuple[Dataset, Projection]:
    """``data`` with its FOON, kitchen, goals and utensils projected (the FOON first, so
    its spellings win), and the projection (to map further objects the same way)."""
    projection = Projection(level, Texts(normalize, synonyms))
    if projection.identity:
        return data, projection
    foon = projection.foon(data.foon)
    return (
        replace(
            data,
            foon=foon,
            kitchen=projection.objects(data.kitchen),
            goals=[(projection.object(o), line) for o, line in data.goals],
            utensils=projection.utensils(data.utensils),
        ),
        projection,
    )
