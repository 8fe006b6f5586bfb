"""What a program defines and uses: the predicates of user rules, the shipped encodings and the facts.

Read with clingo's parser; :func:`rule_warnings` names a predicate a user program uses that
nothing defines, :func:`only_constraints` says whether user programs only remove trees, and
:func:`refuse_host_code` refuses a program that would run code of the host (``#script``, ``@f(...)``).
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from functools import cache

import clingo
import clingo.ast

from foon2asp.asp import encoding_files
from foon2asp.errors import InputError, escape

#: a predicate: name and arity
Signature = tuple[str, int]

#: the facts :func:`foon2asp.asp.facts.facts` writes (docs/vocabulary.md, "Facts")
FACTS: frozenset[Signature] = frozenset(
    (s[:-2], int(s[-1]))
    for s in "object/1 label/2 state/2 ingredient/2 container/2 unit/1 motion/2 success/2 neglog/2 input/2"
    " required/2 output/2 product/2 kitchen/1 goal_node/2 goal/1".split()
)


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


@dataclass
class Predicates:
    """What one program defines and uses."""

    #: predicates in a rule head, ``#external`` or ``#defined``
    defined: set[Signature] = field(default_factory=set)
    #: predicates in a body, ``#show``, ``#heuristic`` or ``#project``, with their first use (line, column)
    used: dict[Signature, tuple[int, int]] = field(default_factory=dict)
    #: the program holds ``#minimize``, ``#heuristic``, ``#external``, ``#edge`` or a weak constraint
    changes_search: bool = False
    #: predicates only declared by ``#defined`` (optional inputs: they may have no facts)
    declared: set[Signature] = field(default_factory=set)

    def define(self, sigs: Iterable[Signature]) -> None:
        self.defined.update(sigs)

    def use(self, sigs: Iterable[Signature], location: clingo.ast.Location) -> None:
        for sig in sigs:
            self.used.setdefault(sig, (location.begin.line, location.begin.column))

    def statement(self, stm: clingo.ast.AST) -> None:
        """Collect the predicates of one statement."""
        kind = stm.ast_type
        T = clingo.ast.ASTType
        self.changes_search = self.changes_search or kind in (T.Minimize, T.Heuristic, T.External, T.Edge)
        if kind == T.Rule:
            self.visit(stm.head, head=True)
            self.visit(stm.body)
        elif kind == T.External:
            self.define(_signatures(stm.atom.symbol))
            self.visit(stm.body)
        elif kind == T.Defined:
            self.define([(stm.name, stm.arity)])
            self.declared.add((stm.name, stm.arity))
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


def outside_strings(name: str, text: str) -> None:
    """Raise an InputError, located in program ``name``, at a character that is not ASCII outside a
    closed string or a comment: clingo's parser would echo part of it in its message (a byte of a
    character in UTF-8), which it cannot report."""
    i, n, line, start = 0, len(text), 1, 0
    while i < n:
        c = text[i]
        if c == "\n":
            line, start = line + 1, i + 1
        elif c == "%":
            end = text.find("*%", i + 2) if text.startswith("%*", i) else text.find("\n", i)
            end = n if end < 0 else end + (2 if text.startswith("%*", i) else 0)
            line += text.count("\n", i, end)
            start = text.rfind("\n", 0, end) + 1 if "\n" in text[i:end] else start
            i = end
            continue
        elif c == '"':
            j = i + 1
            while j < n and text[j] not in '"\n':
                j += 2 if text[j] == "\\" else 1
            if j < n and text[j] == '"':
                i = j + 1
                continue
        elif ord(c) > 127:
            raise InputError(f"the character {c!r} is not ASCII and stands outside a string", name, line, i - start + 1)
        i += 1


def predicates(text: str, name: str = "program") -> Predicates:
    """The predicates program ``text`` (called ``name`` in errors) defines and uses (clingo's
    parser; RuntimeError on a syntax error)."""
    outside_strings(name, text)
    found = Predicates()
    clingo.ast.parse_string(text, found.statement, logger=lambda code, msg: None)
    return found


def _parsed(text: str, name: str = "program") -> Predicates | None:
    try:
        return predicates(text, name)
    except RuntimeError:
        return None  # a syntax error, reported as an error where the program is checked


def file_predicates(path: str) -> Predicates:
    """The predicates the encoding file at ``path`` (with the files it includes) defines and uses."""
    found = Predicates()
    clingo.ast.parse_files([path], found.statement, logger=lambda code, msg: None)
    return found


def _external_calls(node: object) -> Iterator[clingo.ast.AST]:
    """The ``@f(...)`` terms in ``node`` (an AST or a sequence of them), at any depth."""
    stack = [node]
    while stack:
        item = stack.pop()
        if isinstance(item, clingo.ast.AST):
            if item.ast_type == clingo.ast.ASTType.Function and item.external:
                yield item
            stack.extend(getattr(item, key) for key in item.child_keys)
        elif isinstance(item, (list, tuple, clingo.ast.ASTSequence)):
            stack.extend(item)


#: the (name, text) programs :func:`refuse_host_code` found free of host code
_NO_HOST_CODE: set[tuple[str, str]] = set()


def refuse_host_code(name: str, text: str) -> None:
    """Raise an InputError, located in program ``name`` (or the file it includes), when ``text``
    would run code of the host: a ``#script`` block of any language or an ``@``-function call
    (or holds a character clingo cannot report: :func:`outside_strings`).

    The program is read with clingo's parser, as clingo reads it: a comment or a string that
    mentions ``#script`` is no script, an included file is read too, and statements after a
    syntax error are still seen (clingo would run a script there before it reports the error)."""
    if (name, text) in _NO_HOST_CODE:
        return  # read before (each goal's control adds the programs again)
    outside_strings(name, text)
    found: list[tuple[clingo.ast.Location, str]] = []

    def statement(stm: clingo.ast.AST) -> None:
        if stm.ast_type == clingo.ast.ASTType.Script:
            found.append((stm.location, f"#script ({stm.name}) is refused: a program may not run host code"))
        else:
            for call in _external_calls(stm):
                text = f"@{call.name}(...) is refused: a program may not call host code (@-functions)"
                found.append((call.location, text))

    try:
        clingo.ast.parse_string(text, statement, logger=lambda code, msg: None)
    except RuntimeError:
        pass  # a syntax error: clingo's check names it, unless a script was seen first
    if found:
        where, what = min(found, key=lambda f: (f[0].begin.filename != "<string>", f[0].begin.line, f[0].begin.column))
        path = where.begin.filename
        if path != "<string>":
            what += f" (in a file {escape(name)} includes)"
        raise InputError(what, name if path == "<string>" else path, where.begin.line, where.begin.column)
    if "include" not in text:  # a program that may include a file is read again: the file may change
        _NO_HOST_CODE.add((name, text))


@cache
def shipped_predicates() -> dict[str, Predicates]:
    """Each shipped encoding part's :class:`Predicates` (with its includes), by name (``tree``, ``units``, ...)."""
    return {name: file_predicates(encoding_files.part(name)) for name in encoding_files.parts()}


#: the facts of the convenience flags (``encodings/parts/constraints.lp``): they only remove trees
FLAGS: frozenset[Signature] = frozenset(
    (name, 1) for name in ("forbid_motion", "forbid_object", "require_motion", "require_object", "max_units")
)


@cache
def known_predicates() -> frozenset[Signature]:
    """Every predicate foon2asp defines or writes: the facts and what the shipped encodings define or read."""
    known = set(FACTS)
    for found in shipped_predicates().values():
        known |= found.defined | set(found.used)
    return frozenset(known)


def signature_text(sig: Signature) -> str:
    return f"{sig[0]}/{sig[1]}"


def closest(sig: Signature, defined: Iterable[Signature]) -> str:
    """``; did you mean motion/2?``: the defined predicates whose names are closest to ``sig``'s, or ""."""
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
    """``NAME:LINE:COLUMN: motoin/2 is defined nowhere; did you mean motion/2?`` for each predicate a
    user program (name, text) uses that neither foon2asp, ``defined`` nor any of ``programs`` defines."""
    parsed = [(name, found) for name, text in programs if (found := _parsed(text, name)) is not None]
    known = set(known_predicates()) | set(defined)
    for _, found in parsed:
        known |= found.defined
    return [
        undefined(name, sig, where, known)
        for name, found in parsed
        for sig, where in found.used.items()
        if sig not in known
    ]


def only_constraints(programs: Iterable[tuple[str, str]]) -> bool:
    """Do the user ``programs`` only remove trees (constraints, rules with heads of their own, nothing
    that changes the objective or the search)?"""
    known = known_predicates() - FLAGS
    for _, text in programs:
        found = _parsed(text)
        if found is None or found.defined & known or found.changes_search:
            return False
    return True


def checkable(programs: Iterable[tuple[str, str]]) -> bool:
    """Do the ``programs`` read only the facts, ``use/1`` and what they define themselves?"""
    allowed = set(FACTS) | FLAGS | {("use", 1)}
    for _, text in programs:
        found = _parsed(text)
        if found is None or not set(found.used) <= allowed | found.defined:
            return False
    return True


def mentioned(programs: Iterable[tuple[str, str]]) -> set[str] | None:
    """The names of the predicates the ``programs`` define or use (None: one cannot be parsed)."""
    names: set[str] = set()
    for _, text in programs:
        found = _names(text)
        if found is None:
            return None
        names.update(found)
    return names


@cache
def _names(text: str) -> frozenset[str] | None:
    """The predicate names program ``text`` defines or uses, parsed once (a grounding per goal asks)."""
    found = _parsed(text)
    return None if found is None else frozenset(name for name, _ in (*found.defined, *found.used))
