"""Tree files: judged on their own without a FOON (:func:`check_tree`), drawn (:func:`draw_file`),
and candidate trees of one recipe consolidated into one proven-best tree (:func:`consolidate`)."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, fields, replace
from pathlib import Path
from typing import Any

from foon2asp import report
from foon2asp.analysis import check as check_mod
from foon2asp.analysis import consolidate as consolidate_mod
from foon2asp.api.kb import GoalLike, KnowledgeBase
from foon2asp.api.load import Reading, knowledge_base
from foon2asp.api.request import KEYWORDS, Options, check_keywords, jobs
from foon2asp.api.results import Answer, Raw, Tree, as_list, object_of, objects_of, tree_of, units_of
from foon2asp.errors import InputError, strict_error
from foon2asp.foon.loaders import Dataset, read_goals, read_kitchen, read_motion, read_utensils
from foon2asp.foon.model import LEAVES, FoonObject, Unit, leaves
from foon2asp.foon.treefiles import TreeUnit, read_trees
from foon2asp.outcomes import Candidate
from foon2asp.report import draw


@dataclass(eq=False)
class TreeVerdict:
    """A tree of a file judged on its own: valid when every unit fires in the order written
    (from its leaves, or the kitchen given) and the goal is made."""

    raw: Any
    valid = Raw[bool]()
    kind = Raw[str | None](
        "``no-goal``, ``cycle``, ``missing-input``, ``order`` or ``goal-not-made`` (None when valid).", "verdict.kind"
    )
    valid_as_set = Raw[bool](
        "Do the units make the goal in some order (the independent validator's verdict)?", "verdict.valid"
    )
    goals = Raw[list[FoonObject]](path="verdict.goals", read=as_list)
    warnings = Raw[list[str]]("What reading the file skipped or merged (one line each).", "tree.warnings", as_list)

    @property
    def problem(self) -> str | None:
        """The first problem in words (None for a valid tree)."""
        return None if self.valid else self.raw.verdict.problem

    @property
    def cycle(self) -> list[tuple[FoonObject, Unit]]:
        """Circular support: (object, unit making it) pairs; each unit needs the next object."""
        return [(o, self.raw.tree.units[p - 1].unit) for o, p in self.raw.verdict.cycle]

    def to_dict(self) -> dict:
        """One element of ``check --format json`` (a tree judged on its own)."""
        return report.verdicts.alone_json(self.raw)

    def to_text(self) -> str:
        return report.verdicts.alone_text(self.raw)


@dataclass(eq=False)
class CandidateReport:
    """One candidate file for one goal: executable on its own or not, its measures, the units used."""

    raw: Any
    valid = Raw[bool]("Is it executable on its own (its units, in file order, from the consolidation's kitchen)?")
    cost = Raw[dict]("Its measures in the merged FOON, as ``solve`` reports a tree's.")
    file = Raw[str](path="candidate.path")
    used_units = Raw[list[int]](
        "The numbers (in its file, from 1) of its units the consolidated tree uses.", "used", as_list
    )

    @property
    def problem(self) -> str | None:
        return None if self.raw.valid else self.raw.verdict.problem


class ConsolidatedGoal(Answer):
    """One goal (or meal) of :func:`consolidate`: the proven-best tree, sources, verdicts, what to add."""

    json_of = report.candidates.consolidation_json
    goals = Raw[list[FoonObject]](read=objects_of)
    goal = Raw[FoonObject](path="goals", read=lambda a, ids: object_of(a, ids[0]))
    tree = Raw[Tree](read=tree_of)
    status = Raw[str](path="tree.status")
    cost = Raw[dict](path="tree.cost")
    units = Raw[list[Unit]](path="tree.units", read=units_of)
    candidates = Raw[list[CandidateReport]](read=lambda _, found: [CandidateReport(v) for v in found])

    @property
    def sources(self) -> list[list[str]]:
        """The files holding each unit of the tree, in the order of :attr:`units`."""
        return [list(self.raw.sources[u]) for u in self.raw.tree.units]

    @property
    def missing(self) -> list[FoonObject]:
        """The fewest objects to add to the kitchen (when the goal is unreachable; else empty)."""
        return objects_of(self, self.raw.missing.missing) if self.raw.missing is not None else []


@dataclass(eq=False)
class Consolidation(Answer):
    """What :func:`foon2asp.api.consolidate` found (``raw``: one record per goal) in the merged FOON
    (``kb``): iterable and indexable, one :class:`ConsolidatedGoal` per goal."""

    #: about the candidates, the files and the request
    warnings: tuple[str, ...] = ()
    kind = "consolidate"

    @property
    def results(self) -> list[ConsolidatedGoal]:
        return [ConsolidatedGoal(self.kb, r) for r in self.raw]

    def __iter__(self) -> Iterator[ConsolidatedGoal]:
        return iter(self.results)

    def __len__(self) -> int:
        return len(self.raw)

    def __getitem__(self, k: int) -> ConsolidatedGoal:
        return ConsolidatedGoal(self.kb, self.raw[k])

    def to_list(self) -> list[dict]:
        """``consolidate --format json`` as data: one object per goal."""
        return [r.to_dict() for r in self.results]


def check_tree(
    path: str | Path,
    goal: str | Sequence[str] | None = None,
    *,
    kitchen: str | Path | None = None,
    utensils: str | Path | None = None,
    utensil_rule: str = "starter",
    strict: bool = False,
) -> list[TreeVerdict]:
    """Judge every tree of a tree file on its own, without a FOON (docs/api.md)."""
    texts = () if goal is None else (goal,) if isinstance(goal, str) else tuple(goal)
    items = None if kitchen in (None, LEAVES) else read_kitchen(str(kitchen))
    source = "its leaves" if items is None else str(kitchen)
    tools = read_utensils(str(utensils)) if utensils is not None else frozenset()
    found = check_mod.check_alone(path, texts, items, tools, utensil_rule, strict, source)
    return [TreeVerdict(r) for r in found]


def draw_file(
    tree: str | Path,
    output: str | Path,
    *,
    fmt: str | None = None,
    kb: KnowledgeBase | None = None,
    goal: str | None = None,
    strict: bool = False,
    warnings: list[str] | None = None,
    options: Options | None = None,
) -> int:
    """Draw every tree of a tree file into ``output`` (the format by ``fmt`` or the extension) and
    return how many; with ``kb`` the goal is gold, kitchen items green and a blocking cycle red.
    What reading the file skipped or merged is added to ``warnings``."""
    fmt = fmt or draw.format_of(output)
    if fmt != "dot":
        draw.require_dot()
    if kb is None:
        trees, reports, problem = read_trees(tree, strict=strict), None, None
    else:  # the trees as the knowledge base sees them; with substitutes, what they stand in for is had
        trees = [kb.project_tree(t) for t in read_trees(tree, kb.problem, strict)]
        problem = kb.judging_problem(options)
        reports = check_mod.check_trees(kb.data, problem, trees, goal)
    if warnings is not None:
        warnings.extend(dict.fromkeys(w for t in trees for w in t.warnings))
    Path(output).write_bytes(draw.render(draw.file_graph(trees, reports, problem), fmt))
    return len(trees)


def consolidate(
    paths: Sequence[str | Path],
    goal: GoalLike | Sequence[GoalLike] | None = None,
    *,
    goals: str | Path | None = None,
    together: bool = False,
    **keywords: Any,
) -> Consolidation:
    """Merge candidate trees of one recipe into one FOON and find one proven-best tree per goal
    (docs/api.md); ``keywords``: the fields of :class:`foon2asp.api.load.Reading` and the request."""
    if not paths:
        raise InputError("no candidate tree given")
    check_keywords(keywords, {f.name for f in fields(Reading)} | KEYWORDS | {"options"}, "consolidate(): ")
    how = Reading.of(keywords)
    seen_as = how.projection()
    candidates = consolidate_mod.read_candidates(paths, how.strict)
    foon, sources = consolidate_mod.merge(candidates)
    given = None if how.kitchen in (None, LEAVES) else str(how.kitchen)
    warnings: list[str] = []
    data = Dataset(
        foon=foon,
        kitchen=leaves(foon) if given is None else read_kitchen(given),
        goals=read_goals(str(goals)) if goals not in (None, "all") else [],
        motion=read_motion(str(how.motion), warnings) if how.motion is not None else {},
        utensils=read_utensils(str(how.utensils), warnings) if how.utensils is not None else frozenset(),
        paths={"foon": ",".join(str(p) for p in paths), "kitchen": given or LEAVES},
        warnings=warnings,
    )
    kb = knowledge_base(data, how.utensil_rule, [w for c in candidates for w in c.warnings], seen_as)
    if not kb.projection.identity:
        candidates, sources = _projected(kb, candidates)
    solver, asked = kb.options_and_warnings(**keywords)
    if how.strict and asked:  # warnings about the request are errors too
        raise strict_error(asked)
    ids, source = _goals(kb, candidates, goal, goals)
    problem = kb.solving_problem(solver)
    raw = consolidate_mod.consolidate(
        problem, candidates, sources, jobs(ids, together), solver, source, given or LEAVES
    )
    return Consolidation(kb, raw, kb.warnings + tuple(asked))


def _projected(kb: KnowledgeBase, candidates: list[Candidate]) -> tuple[list[Candidate], list[list[str]]]:
    """The candidates with their units as the knowledge base's comparison sees them, and the
    files of each unit of its (projected) FOON."""
    out = []
    for cand in candidates:
        units: dict[tuple, TreeUnit] = {}
        for tu in cand.units:
            unit = kb.projection.unit(tu.unit)
            units.setdefault(unit.key(), TreeUnit(unit, tu.step, tu.line))
        out.append(replace(cand, units=list(units.values())))
    merged, found = consolidate_mod.merge(out)
    files = {unit.key(): paths for unit, paths in zip(merged.units, found, strict=True)}
    return out, [files[unit.key()] for unit in kb.problem.units]


def _goals(
    kb: KnowledgeBase, candidates: list[Candidate], goal: GoalLike | Sequence[GoalLike] | None, goals: str | Path | None
) -> tuple[list[int], str]:
    """The goal ids a consolidation answers and where they came from."""
    if goal is not None:
        return kb.goal_ids(goal), "given"
    if goals == "all":
        ranked = consolidate_mod.candidate_goals(candidates)
        if not ranked:
            raise InputError("no candidate's last unit makes an object: name the goal", hint="no-goal")
        return [kb.object_id(o) for o, _ in ranked], "a product of a candidate's last unit"
    if goals is not None:
        return kb.select_goals((), goals), "the goals file"
    obj, why = consolidate_mod.shared_goal(candidates)
    return [kb.object_id(obj)], why
