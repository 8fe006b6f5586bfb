"""Turning what the user names (a label, a goals file, ``all``) into object ids."""

from __future__ import annotations

import difflib

from foon2asp.errors import MAX_ECHO, InputError, clip, shown
from foon2asp.foon.loaders import Dataset, read_goals
from foon2asp.foon.model import FoonObject, norm
from foon2asp.foon.problem import Problem


def _closest(problem: Problem, label: str) -> str:
    """``; closest labels: ...``: the FOON's labels closest to ``label`` (none for a label too long to be close)."""
    if len(label) > MAX_ECHO:
        return ""
    labels = sorted(problem.foon.labels())
    close = difflib.get_close_matches(label, labels, n=5, cutoff=0.5)
    if not close:  # a misspelt word of a longer label ("scrambld egg" -> "scrambled egg")
        words = sorted({w for lab in labels for w in lab.split()})
        hits = {w for part in label.split() for w in difflib.get_close_matches(part, words, n=2, cutoff=0.75)}
        close = [lab for lab in labels if hits & set(lab.split())][:5]
    return f"; closest labels: {', '.join(close)}" if close else ""


def goal_id(problem: Problem, obj, path: str | None = None, line: int | None = None) -> int:
    """Object id of a goal object, or an error suggesting close labels."""
    oid = problem.foon.object_ids.get(obj)
    if oid is None:
        same = problem.foon.by_label(obj.label)
        hint = (
            f"; objects labelled {shown(obj.label)} exist with other states" if same else _closest(problem, obj.label)
        )
        raise InputError(f"goal {clip(str(obj))} is not an object of the FOON{hint}", path, line)
    return oid


def parse_object_text(text: str) -> FoonObject | None:
    """The object an object's text names, as foon2asp prints it (``label, state, ...,
    contains {a,b}, in [c]``; states in any order), or None when ``text`` has no comma."""
    parts, depth, at = [], 0, 0
    for k, ch in enumerate(text):  # split at the commas outside {} and []
        if ch in "{[":
            depth += 1
        elif ch in "}]":
            depth = max(0, depth - 1)
        elif ch == "," and depth == 0:
            parts.append(text[at:k].strip())
            at = k + 1
    parts.append(text[at:].strip())
    if len(parts) < 2:
        return None
    states, ingredients, container = [], [], None
    for part in parts[1:]:
        if part.startswith("contains {") and part.endswith("}"):
            ingredients += part[len("contains {") : -1].split(",")
        elif part.startswith("in [") and part.endswith("]"):
            container = part[len("in [") : -1]
        elif part:
            states.append(part)
    return FoonObject.make(parts[0], states, ingredients, container)


def _exact(problem: Problem, text: str) -> int | None:
    """The id ``#ID`` or an object's text names (an error for ``#ID`` of no object); None for other text."""
    if text.startswith("#") and text[1:].isdigit():
        oid = int(text[1:])
        if oid >= len(problem.objects):
            raise InputError(f"no object #{oid}: ids run from #0 to #{len(problem.objects) - 1}")
        return oid
    obj = parse_object_text(text)
    return problem.foon.object_ids.get(obj) if obj is not None else None


def resolve_goal(data: Dataset, problem: Problem, text: str) -> int:
    """``--goal``: ``#ID`` (an object id as ``foon2asp objects`` lists it), an object's
    text as foon2asp prints it, or a label (see :func:`resolve_label`)."""
    oid = _exact(problem, text.strip())
    return oid if oid is not None else resolve_label(data, problem, text.strip())


def resolve_label(data: Dataset, problem: Problem, label: str) -> int:
    """``--goal LABEL``: the goals-file entry with that label, else the unique FOON object."""
    key = norm(label)
    path = data.paths.get("goals")
    entries = [(obj, line) for obj, line in data.goals if obj.label == key]
    if len(entries) == 1:
        return goal_id(problem, entries[0][0], path, entries[0][1])
    if len(entries) > 1:
        listing = " | ".join(str(o) for o, _ in entries)
        raise InputError(f"goal label {shown(label)} is ambiguous in the goals file: {listing}", path)
    candidates = [problem.foon.object_ids[o] for o in problem.foon.by_label(key)]
    produced = [o for o in candidates if o in problem.producers] or candidates
    if len(produced) == 1:
        return produced[0]
    if not produced:
        raise InputError(f"no goal or FOON object labelled {shown(label)}{_closest(problem, key)}")
    if len(produced) <= 20:
        listing = " | ".join(f"#{o} {problem.objects[o]}" for o in produced)
        raise InputError(
            f"label {shown(label)} names {len(produced)} FOON objects; give one as --goal with its text or #ID: {listing}"
        )
    raise InputError(
        f"label {shown(label)} names {len(produced)} FOON objects; list them with: foon2asp objects {shown(key)}"
        " (then give one as --goal with its text or #ID)"
    )


def all_objects(problem: Problem) -> list[int]:
    """Every object some unit produces that is not in the kitchen."""
    return sorted(o for o in problem.producers if o not in problem.kitchen)


def resolve(data: Dataset, problem: Problem, goal: tuple[str, ...] | None, goals: str | None) -> list[int]:
    """Goal ids for ``--goal TEXT`` (repeatable) and ``--goals FILE|all|all-objects``;
    neither: :func:`default_goals`."""
    if not goal and not goals:
        return default_goals(data, problem)
    out = [resolve_goal(data, problem, label) for label in goal or ()]
    if goals == "all":
        need = "'all' needs a goals file (goal_nodes.json in the data folder, or one given)"
        out += _file_goals(data, problem, need, "goals-all")
    elif goals == "all-objects":
        out += all_objects(problem)
    elif goals:
        out += [goal_id(problem, obj, goals, line) for obj, line in read_goals(goals)]
    if not out and goals == "all-objects":
        raise InputError("no unit makes an object that is not in the kitchen: no goal")
    if not out:
        raise InputError("the goals file lists no goal", data.paths.get("goals") if goals == "all" else goals)
    return out


def default_goals(data: Dataset, problem: Problem) -> list[int]:
    """The goals when none are named, the same for every command: the goals file's entries."""
    need = "no goal given and no goals file (name goals, a goals file or 'all-objects')"
    return _file_goals(data, problem, need, "no-goals-file")


def _file_goals(data: Dataset, problem: Problem, need: str, hint: str) -> list[int]:
    """The ids of the goals file's entries; the error ``need`` (with ``hint``, and the path looked for
    as ``hint=PATH``) without a goals file."""
    path = data.paths.get("goals")
    if path is None:
        looked = data.looked_for.get("goals")
        raise InputError(need + (f" (there is no {looked})" if looked else ""), hint=f"{hint}={looked or ''}")
    return [goal_id(problem, obj, path, line) for obj, line in data.goals]


# ---------------------------------------------------------------- listing objects

#: what ``objects`` can restrict the listing to
OBJECT_FILTERS = ("produced", "kitchen", "derivable")


def object_info(problem: Problem, oid: int) -> dict:
    """One object as ``foon2asp objects --format json`` lists it (also a goals-file entry)."""
    obj = problem.objects[oid]
    return {
        "id": oid,
        "text": obj.text,
        **obj.to_json(),
        "in_kitchen": oid in problem.kitchen,
        "producers": len(problem.producers.get(oid, ())),
    }


def find_objects(problem: Problem, query: str | None = None, only: str | None = None) -> list[int]:
    """Ids of the objects ``query`` names, in id order: every object (None), ``#ID``, an
    object's text, a label, else the labels containing ``query`` as words; ``only`` keeps
    the ``produced``, ``kitchen`` or ``derivable`` ones.  Nothing matching is an
    :class:`InputError` with the closest labels."""
    if only is not None and only not in OBJECT_FILTERS:
        raise InputError(f"unknown object filter {shown(only)} (have {', '.join(OBJECT_FILTERS)})")
    ids = _matching(problem, query.strip()) if query and query.strip() else list(range(len(problem.objects)))
    if only is None:
        return ids
    pool = problem.producers if only == "produced" else problem.kitchen if only == "kitchen" else problem.derivable
    return [o for o in ids if o in pool]


def _matching(problem: Problem, query: str) -> list[int]:
    oid = _exact(problem, query)
    if oid is not None:
        return [oid]
    key = norm(query)
    ids = [problem.foon.object_ids[o] for o in problem.foon.by_label(key)]
    # else the labels that contain the query as whole words ("egg" -> "scrambled egg")
    ids = ids or [i for i, o in enumerate(problem.objects) if f" {key} " in f" {o.label} "]
    if ids:
        return ids
    raise InputError(f"no object matches {shown(query)}{_closest(problem, key)}")
