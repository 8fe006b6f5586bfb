"""The FOON model: objects, functional units and the network that holds them.

Object identity is label + set of states + set of ingredients + container, independent
of order (docs/proofs/preparation.md, "Object identity"); relations other than
``in``/``contains`` are states such as ``"on [plate]"`` (:func:`state_parts` splits them).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, field

#: a bracket of a state's argument (``on [plate]``, ``contains {a,b}``)
BRACKET = re.compile(r"[\[\]{}]")
_CLOSING = {"[": "]", "{": "}"}
_OPENING = {"]": "[", "}": "{"}
_RELATION_STATE = re.compile(r"^(.+?) ([\[{].*[\]}])$")


def norm(text: str) -> str:
    """Text as objects hold it: case-folded, runs of white space as one space."""
    return " ".join(str(text).split()).lower()


def motion_key(text: str) -> str:
    """A motion as units hold it: normalised, a trailing ``*`` dropped."""
    return norm(text).rstrip("*").strip()


def bracket_problem(text: str) -> tuple[str, int] | None:
    """Why the brackets of ``text`` do not pair up (``[``/``]``, ``{``/``}``), with the offset
    of the bracket at fault; None when they pair up."""
    open_: list[tuple[str, int]] = []
    for m in BRACKET.finditer(text):
        c, at = m.group(), m.start()
        if c in _CLOSING:
            open_.append((c, at))
        elif not open_:
            return f"stray {c!r} (no {_OPENING[c]!r} before it)", at
        elif _CLOSING[open_[-1][0]] != c:
            return f"{open_[-1][0]!r} closed by {c!r}", at
        else:
            open_.pop()
    if open_:
        c, at = open_[0]
        return f"unbalanced {c!r} (no {_CLOSING[c]!r} after it)", at
    return None


def state_parts(state: str) -> tuple[str, str | None]:
    """``"on [plate]"`` -> ``("on", "[plate]")``; a plain state -> ``(state, None)``.  Split only
    where both parts read back as they are (brackets pair up, the name is not ``in``/``contains``)."""
    m = _RELATION_STATE.match(state)
    if m is None or m.group(1).lower() in ("in", "contains", "ingredients"):
        return state, None
    if bracket_problem(m.group(1)) is not None or bracket_problem(m.group(2)) is not None:
        return state, None
    return m.group(1), m.group(2)


@dataclass(frozen=True, order=True)
class FoonObject:
    """An object node; fields are normalised and sorted, so ``==`` is identity."""

    label: str
    states: tuple[str, ...] = ()
    ingredients: tuple[str, ...] = ()
    container: str | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "_hash", hash((self.label, self.states, self.ingredients, self.container)))

    def __hash__(self) -> int:
        return self._hash  # type: ignore[attr-defined]

    @classmethod
    def make(
        cls,
        label: str,
        states: Iterable[str] = (),
        ingredients: Iterable[str] = (),
        container: str | None = None,
    ) -> FoonObject:
        """The object with these fields normalised (empty ones dropped) and sorted."""
        return cls(
            norm(label),
            tuple(sorted({norm(s) for s in states} - {""})),
            tuple(sorted({norm(i) for i in ingredients} - {""})),
            norm(container or "") or None,
        )

    @property
    def text(self) -> str:
        """The object as foon2asp prints it: ``label, state, ..., contains {a,b}, in [c]``."""
        return str(self)

    def is_bare(self) -> bool:
        """True for an object with no states, ingredients or container."""
        return not self.states and not self.ingredients and self.container is None

    def to_json(self) -> dict:
        return {
            "label": self.label,
            "states": list(self.states),
            "ingredients": list(self.ingredients),
            "container": self.container,
        }

    def __str__(self) -> str:
        parts = [self.label, *self.states]
        if self.ingredients:
            parts.append("contains {" + ",".join(self.ingredients) + "}")
        if self.container:
            parts.append(f"in [{self.container}]")
        return ", ".join(parts)


@dataclass(frozen=True)
class Unit:
    """A functional unit: inputs --motion--> outputs (objects in file order)."""

    motion: str
    inputs: tuple[FoonObject, ...]
    outputs: tuple[FoonObject, ...]

    def key(self) -> tuple:
        """Identity used for de-duplication: motion, set of inputs, set of outputs."""
        return (self.motion, frozenset(self.inputs), frozenset(self.outputs))

    def to_json(self) -> dict:
        return {
            "motion": self.motion,
            "inputs": [o.to_json() for o in self.inputs],
            "outputs": [o.to_json() for o in self.outputs],
        }

    def __str__(self) -> str:
        return f"{self.motion}: {'; '.join(map(str, self.inputs))} -> {'; '.join(map(str, self.outputs))}"


@dataclass
class Foon:
    """A de-duplicated FOON.  Unit ids and object ids are list indices."""

    units: list[Unit] = field(default_factory=list)
    objects: list[FoonObject] = field(default_factory=list)
    object_ids: dict[FoonObject, int] = field(default_factory=dict)
    #: source (path, line) of each unit, for messages
    origins: list[tuple[str, int]] = field(default_factory=list)
    #: one-line messages about input that was skipped
    warnings: list[str] = field(default_factory=list)
    #: ids read from official files: kind ("O" object label, "S" state name,
    #: "M" motion) -> normalised text -> id (the first id seen wins)
    ids: dict[str, dict[str, int]] = field(default_factory=lambda: {"O": {}, "S": {}, "M": {}})
    #: the complete ids for writing (see :func:`foon2asp.foon.parser.id_map`)
    id_cache: tuple | None = field(default=None, repr=False, compare=False)
    _keys: dict[tuple, int] = field(default_factory=dict, repr=False)

    def object_id(self, obj: FoonObject) -> int:
        """Id of ``obj``, adding it when new."""
        oid = self.object_ids.get(obj)
        if oid is None:
            oid = len(self.objects)
            self.objects.append(obj)
            self.object_ids[obj] = oid
        return oid

    def unit_id(self, unit: Unit) -> int | None:
        """Id of the unit equal to ``unit`` (same :meth:`Unit.key`), None when there is none."""
        return self._keys.get(unit.key())

    def add_unit(self, unit: Unit, origin: tuple[str, int] = ("", 0)) -> int:
        """Add ``unit`` unless an equal one exists; return its id."""
        key = unit.key()
        uid = self._keys.get(key)
        if uid is not None:
            return uid
        uid = len(self.units)
        self._keys[key] = uid
        self.units.append(unit)
        self.origins.append(origin)
        for obj in unit.inputs + unit.outputs:
            self.object_id(obj)
        return uid

    def labels(self) -> set[str]:
        return {o.label for o in self.objects}

    def by_label(self, label: str) -> list[FoonObject]:
        label = norm(label)
        return [o for o in self.objects if o.label == label]


#: the kitchen named this (``--kitchen leaves``, ``load(kitchen="leaves")``) is the FOON's leaves
LEAVES = "leaves"


def made(units: Iterable[Unit]) -> set[FoonObject]:
    """The objects some unit of ``units`` makes (outputs that are not bare and not its own inputs)."""
    return {o for u in units for o in u.outputs if not o.is_bare() and o not in u.inputs}


def leaves(foon: Foon | Iterable[Unit]) -> list[FoonObject]:
    """The kitchen of a FOON that comes without one: every input of a unit of ``foon`` (a FOON
    or units) that no unit makes, each once, in the order they first appear
    (docs/proofs/preparation.md, "Leaves")."""
    units = list(foon.units if isinstance(foon, Foon) else foon)
    makes = made(units)
    return list(dict.fromkeys(o for u in units for o in u.inputs if o not in makes))
