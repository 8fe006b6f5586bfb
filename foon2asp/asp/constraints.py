"""User constraints: ASP files, rule texts and convenience flags as programs.

Everything here becomes a list of ``(name, text)`` programs for
:attr:`foon2asp.asp.options.AspOptions.programs`.  The convenience flags
(``--forbid-motion`` and friends) are generated ASP text in which every motion
or label is written with :func:`foon2asp.asp.facts.q`, so a label is always a
string constant and can never add code.  Files and ``--rule`` texts are the
user's own code; they are checked on their own first, so a syntax error or an
unsafe variable is reported as one line naming the file (or rule) and line.

The rules speak the vocabulary of docs/vocabulary.md: ``use(U)`` is a unit of
the tree, ``motion(U,M)``, ``input(U,O)``, ``output(U,O)``, ``label(O,L)``.
A predicate a user program uses that nothing defines -- no shipped encoding, no
fact foon2asp writes, no user program -- is a misspelling that would silently
match nothing; :func:`rule_warnings` names it, where it is and the closest
defined predicates.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

import clingo
import clingo.ast

from foon2asp.asp import encodings
from foon2asp.asp.facts import q
from foon2asp.errors import InputError, escape

#: ``<block>:LINE:COL[-COL]: error: text`` or ``FILE:LINE:...`` as clingo writes them
_LOCATION = re.compile(r"^(?P<where>.*?):(?P<line>\d+):(?P<col>\d+)(?:-\d+(?::\d+)?)?: (?P<kind>\w+): (?P<text>.*)$")


def normalise(text: str) -> str:
    """Labels and motions as the FOON model stores them: single spaces, lower case."""
    return " ".join(str(text).split()).lower()


def motion_name(text: str) -> str:
    """A motion as the FOON model stores it (normalised, a trailing ``*`` dropped)."""
    text = normalise(text)
    return text[:-1].rstrip() if text.endswith("*") else text


_motion = motion_name


def forbid_motion(motion: str) -> str:
    """No unit of the tree has motion ``motion``."""
    return f":- use(U), motion(U,{q(_motion(motion))}).\n"


def forbid_object(label: str) -> str:
    """No unit of the tree has an input or output labelled ``label``."""
    lab = q(normalise(label))
    return f":- use(U), input(U,O), label(O,{lab}).\n:- use(U), output(U,O), label(O,{lab}).\n"


def require_motion(motion: str) -> str:
    """Some unit of the tree has motion ``motion``."""
    return f":- #count {{ U : use(U), motion(U,{q(_motion(motion))}) }} = 0.\n"


def require_object(label: str) -> str:
    """Some unit of the tree has an input or output labelled ``label``."""
    lab = q(normalise(label))
    return f":- #count {{ U : use(U), input(U,O), label(O,{lab}); U : use(U), output(U,O), label(O,{lab}) }} = 0.\n"


def max_units(n: int) -> str:
    """The tree has at most ``n`` units."""
    if not isinstance(n, int) or n < 0:
        raise InputError(f"--max-units must be a whole number >= 0, not {n!r}")
    return f":- #count {{ U : use(U) }} > {n}.\n"


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
    """One-line InputError for clingo's messages about program ``name``.

    ``<block>:3:5-6: error: syntax error, unexpected .`` becomes
    ``NAME:3: syntax error, unexpected . (column 5)``; notes such as
    ``'X' is unsafe`` are appended.
    """
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
    """Parse and ground ``text`` alone; raise a located InputError if clingo rejects it.

    Grounding alone catches unsafe variables, which clingo reports only at
    grounding time.  The user's rules meet no facts here, so this is cheap.
    """
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
        return bool(
            self.files
            or self.rules
            or self.forbid_motion
            or self.forbid_object
            or self.require_motion
            or self.require_object
            or self.max_units is not None
            or self.extra
        )

    def programs(self) -> list[tuple[str, str]]:
        """The (name, text) programs, user files and rules checked for errors."""
        return programs(
            self.files,
            self.rules,
            self.forbid_motion,
            self.forbid_object,
            self.require_motion,
            self.require_object,
            self.max_units,
        ) + list(self.extra)

    def names(self) -> tuple[list[str], list[str]]:
        """Motions and object labels the convenience flags mention (normalised)."""
        motions = [_motion(m) for m in (*self.forbid_motion, *self.require_motion)]
        labels = [normalise(x) for x in (*self.forbid_object, *self.require_object)]
        return motions, labels


def read_file(path: str) -> str:
    p = Path(path)
    if not p.is_file():
        raise InputError("constraint file not found", path)
    try:
        return p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read constraint file: {exc}", path) from None


def user_programs(files: Iterable[str] = (), rules: Iterable[str] = ()) -> list[tuple[str, str]]:
    """The user's files (named by their path) and rules (``--rule #N``, from 1) as (name, text), unchecked."""
    out = [(str(path), read_file(path)) for path in files]
    return out + [(f"--rule #{n}", rule) for n, rule in enumerate(rules, 1)]


def programs(
    files: Iterable[str] = (),
    rules: Iterable[str] = (),
    forbid_motions: Iterable[str] = (),
    forbid_objects: Iterable[str] = (),
    require_motions: Iterable[str] = (),
    require_objects: Iterable[str] = (),
    max_unit_count: int | None = None,
) -> list[tuple[str, str]]:
    """All constraints as (name, text) programs for ``AspOptions.programs``.

    User files are named by their path and rules ``--rule #N`` (from 1), so
    errors point at them; generated programs are named after their flag.
    """
    out = user_programs(files, rules)
    for name, text in out:
        check_syntax(name, text)
    generated = [
        ("--forbid-motion", forbid_motion, forbid_motions),
        ("--forbid-object", forbid_object, forbid_objects),
        ("--require-motion", require_motion, require_motions),
        ("--require-object", require_object, require_objects),
    ]
    for flag, make, values in generated:
        for value in values:
            if not normalise(value):
                raise InputError(f"{flag} needs a non-empty name")
            out.append((f"{flag} {value}", make(value)))
    if max_unit_count is not None:
        out.append(("--max-units", max_units(max_unit_count)))
    return out


@dataclass(frozen=True)
class Shrinking:
    """Programs that only forbid: motions and object labels no unit of the tree may have, and
    a most number of units.  A subset of an allowed tree is allowed too."""

    motions: frozenset[str]
    labels: frozenset[str]
    max_units: int | None


def shrinking(programs: Iterable[tuple[str, str]]) -> Shrinking | None:
    """What ``programs`` forbid when every one of them is a ``--forbid-motion``,
    ``--forbid-object`` or ``--max-units`` program made by :func:`programs`; None otherwise."""
    motions: set[str] = set()
    labels: set[str] = set()
    most: int | None = None
    for name, text in programs:
        flag, _, value = name.partition(" ")
        if flag == "--forbid-motion" and text == forbid_motion(value):
            motions.add(_motion(value))
        elif flag == "--forbid-object" and text == forbid_object(value):
            labels.add(normalise(value))
        elif name == "--max-units" and (n := _cap(text)) is not None:
            most = n if most is None else min(most, n)
        else:
            return None
    return Shrinking(frozenset(motions), frozenset(labels), most)


def _cap(text: str) -> int | None:
    """The number of a :func:`max_units` program (None: some other text)."""
    digits = text.rpartition("> ")[2].rstrip(".\n")
    return int(digits) if digits.isdigit() and text == max_units(int(digits)) else None


def unknown_names(problem, spec: ConstraintSpec) -> list[str]:
    """Warnings for flag values that match no motion or object label of the FOON, and for
    predicates the user's files and rules use that are defined nowhere (:func:`rule_warnings`)."""
    motions, labels = spec.names()
    have_m = {u.motion for u in problem.units}
    have_l = problem.foon.labels()
    out = [f"no unit has motion {m!r}" for m in motions if m not in have_m]
    out += [f"no object is labelled {lab!r}" for lab in labels if lab not in have_l]
    return out + rule_warnings(user_programs(spec.files, spec.rules) + list(spec.extra))


# --------------------------------------------------------------------------- predicates used and defined

#: a predicate: name and arity
Signature = tuple[str, int]

#: the facts :func:`foon2asp.asp.facts.facts` writes (docs/vocabulary.md, "Facts")
FACTS: frozenset[Signature] = frozenset(
    {
        ("object", 1),
        ("label", 2),
        ("state", 2),
        ("ingredient", 2),
        ("container", 2),
        ("unit", 1),
        ("motion", 2),
        ("success", 2),
        ("neglog", 2),
        ("input", 2),
        ("required", 2),
        ("output", 2),
        ("product", 2),
        ("kitchen", 1),
        ("goal_node", 2),
        ("goal", 1),
    }
)


@dataclass
class Predicates:
    """What one program defines and uses."""

    #: predicates in a rule head (of a fact, a choice, a disjunction, a head aggregate), ``#external`` or ``#defined``
    defined: set[Signature] = field(default_factory=set)
    #: predicates in a body (conditions and aggregate elements too), ``#show``, ``#heuristic``, ``#project``,
    #: with where each is first used (line, column)
    used: dict[Signature, tuple[int, int]] = field(default_factory=dict)


def _signatures(symbol: clingo.ast.AST) -> list[Signature]:
    """The predicates of an atom's symbol: ``p(X)``, ``-p(X)`` (as ``p``), ``p(1;2)``."""
    kind = symbol.ast_type
    if kind == clingo.ast.ASTType.Function and symbol.name:
        return [(symbol.name, len(symbol.arguments))]
    if kind == clingo.ast.ASTType.UnaryOperation:
        return _signatures(symbol.argument)
    if kind == clingo.ast.ASTType.Pool:
        return [s for arg in symbol.arguments for s in _signatures(arg)]
    if kind == clingo.ast.ASTType.SymbolicTerm and symbol.symbol.type == clingo.SymbolType.Function:
        return [(symbol.symbol.name, len(symbol.symbol.arguments))]
    return []


class _Walk:
    """Collects :class:`Predicates` from the statements of one program."""

    def __init__(self) -> None:
        self.found = Predicates()

    def define(self, sigs: Iterable[Signature]) -> None:
        self.found.defined.update(sigs)

    def use(self, sigs: Iterable[Signature], location: clingo.ast.Location) -> None:
        for sig in sigs:
            self.found.used.setdefault(sig, (location.begin.line, location.begin.column))

    def statement(self, stm: clingo.ast.AST) -> None:
        kind = stm.ast_type
        T = clingo.ast.ASTType
        if kind == T.Rule:
            self.visit(stm.head, head=True)
            self.visit(stm.body)
        elif kind == T.External:
            self.define(_signatures(stm.atom.symbol))
            self.visit(stm.body)
        elif kind == T.Defined:
            self.define([(stm.name, stm.arity)])
        elif kind in (T.ShowSignature, T.ProjectSignature):
            if stm.name:
                self.use([(stm.name, stm.arity)], stm.location)
        elif kind in (T.Heuristic, T.ProjectAtom):
            self.use(_signatures(stm.atom.symbol), stm.location)
            self.visit(stm.body)
        elif kind in (T.ShowTerm, T.Minimize, T.Edge):
            self.visit(stm.body)

    def visit(self, node, head: bool = False) -> None:
        """Atoms in ``node`` (an AST or a sequence of them): defined in a head position, else used."""
        if isinstance(node, (list, clingo.ast.ASTSequence)):
            for item in node:
                self.visit(item, head)
            return
        if not isinstance(node, clingo.ast.AST):
            return
        T = clingo.ast.ASTType
        kind = node.ast_type
        if kind == T.Literal:
            if node.atom.ast_type != T.SymbolicAtom:
                self.visit(node.atom, head)  # an aggregate or a theory atom; a comparison holds no atom
            elif head and node.sign == clingo.ast.Sign.NoSign:
                self.define(_signatures(node.atom.symbol))
            else:
                self.use(_signatures(node.atom.symbol), node.location)
        elif kind == T.ConditionalLiteral:
            self.visit(node.literal, head)
            self.visit(node.condition)
        elif kind == T.HeadAggregateElement:
            self.visit(node.condition, head)  # a conditional literal: the atom is defined, its condition used
        elif kind in (T.BodyAggregateElement, T.TheoryAtomElement):
            self.visit(node.condition)
        elif kind in (T.Aggregate, T.BodyAggregate, T.HeadAggregate, T.Disjunction, T.TheoryAtom):
            self.visit(node.elements, head)


def predicates(text: str) -> Predicates:
    """The predicates program ``text`` defines and uses (clingo's parser; RuntimeError on a syntax error)."""
    walk = _Walk()
    clingo.ast.parse_string(text, walk.statement, logger=lambda code, msg: None)
    return walk.found


def _parsed(text: str) -> Predicates | None:
    try:
        return predicates(text)
    except RuntimeError:
        return None  # a syntax error, reported as an error where the program is checked


@cache
def shipped_predicates() -> dict[str, Predicates]:
    """Each shipped encoding's :class:`Predicates`, by name (``tree``, ``units``, ...)."""
    return {name: predicates(encodings.encoding(name)) for name in encodings.names()}


@cache
def known_predicates() -> frozenset[Signature]:
    """Every predicate foon2asp defines or writes: the facts, the shipped encodings' heads,
    and what the encodings read, which foon2asp writes as facts (``objective/2``, ``dom/2``, ...)."""
    known = set(FACTS)
    for found in shipped_predicates().values():
        known |= found.defined | set(found.used)
    return frozenset(known)


def signature_text(sig: Signature) -> str:
    return f"{sig[0]}/{sig[1]}"


def closest(sig: Signature, defined: Iterable[Signature]) -> str:
    """``; did you mean motion/2?``: the defined predicates whose names are closest to ``sig``'s
    (difflib; those nearly as close as the closest), of its arity where the name has it; or ""."""
    arities: dict[str, set[int]] = {}
    for name, arity in defined:
        arities.setdefault(name, set()).add(arity)
    near = difflib.get_close_matches(sig[0], sorted(arities), n=3, cutoff=0.75)
    if not near:
        return ""
    best = difflib.SequenceMatcher(None, sig[0], near[0]).ratio()
    near = [n for n in near if difflib.SequenceMatcher(None, sig[0], n).ratio() >= best - 0.1]
    texts = [signature_text((n, a)) for n in near for a in ([sig[1]] if sig[1] in arities[n] else sorted(arities[n]))]
    texts = texts[:3]
    return "; did you mean " + (texts[0] if len(texts) == 1 else ", ".join(texts[:-1]) + " or " + texts[-1]) + "?"


def undefined(name: str, sig: Signature, where: tuple[int, int], defined: Iterable[Signature]) -> str:
    """The warning about ``sig``, used in program ``name`` at ``where``, that nothing defines."""
    line, column = where
    return f"{escape(name)}:{line}:{column}: {signature_text(sig)} is defined nowhere{closest(sig, defined)}"


def rule_warnings(programs: Iterable[tuple[str, str]], defined: Iterable[Signature] = ()) -> list[str]:
    """One warning for each predicate a user program (name, text) uses that is defined nowhere:
    not in :func:`known_predicates`, ``defined``, or the heads of any of ``programs``.
    ``NAME:LINE:COLUMN: motoin/2 is defined nowhere; did you mean motion/2?``, at its first use
    in each program.  Programs with a syntax error are left to :func:`check_syntax`."""
    parsed = [(name, found) for name, text in programs if (found := _parsed(text)) is not None]
    known = set(known_predicates()) | set(defined)
    for _, found in parsed:
        known |= found.defined
    return [
        undefined(name, sig, where, known)
        for name, found in parsed
        for sig, where in found.used.items()
        if sig not in known
    ]


def _changes_search(text: str) -> bool:
    """Does ``text`` hold a statement that changes what is optimal or how it is searched
    (``#minimize``, ``#heuristic``, ``#external``, ``#edge``, a weak constraint)?"""
    T = clingo.ast.ASTType
    kinds = (T.Minimize, T.Heuristic, T.External, T.Edge)
    found: list[bool] = []
    clingo.ast.parse_string(text, lambda stm: found.append(stm.ast_type in kinds), logger=lambda code, msg: None)
    return any(found)


def only_constraints(programs: Iterable[tuple[str, str]]) -> bool:
    """Do the user ``programs`` only remove trees: integrity constraints and rules whose heads
    are predicates of their own (none that foon2asp defines or writes), nothing that changes
    the objective or the search?  Then what preparation proves of a goal (it cannot be made,
    the relevant part, the landmarks, the lower bounds) still holds with them."""
    known = known_predicates()
    for _, text in programs:
        try:
            if predicates(text).defined & known or _changes_search(text):
                return False
        except RuntimeError:
            return False  # a syntax error: reported where the program is grounded
    return True
