"""The Python API: load a FOON with its kitchen, then ask it for task trees.

Every command of ``foon2asp`` is a thin layer over these calls: :func:`load` reads the data,
:class:`KnowledgeBase` answers with the settings of one request (:class:`Options`), and the
answers render themselves in the formats of :mod:`foon2asp.report`.  The modules import each
other one way: options, results, schedules, kb, load, trees.  Below: what the library knows by
name, for front ends that offer it as choices.
"""

from foon2asp import methods as methods_mod
from foon2asp.analysis.compare import DEFAULT_METHODS as COMPARE_METHODS
from foon2asp.api.kb import KnowledgeBase
from foon2asp.api.load import FOON_FORMATS, load, match_foon, read_foons, read_program, write_foon
from foon2asp.api.request import Constraints, Options
from foon2asp.api.results import (
    BatchRun,
    CheckReport,
    Comparison,
    Missing,
    Reachability,
    Schedule,
    Tree,
    schedules_json,
    writable_dir,
    write_file,
)
from foon2asp.api.schedules import ScheduleVerdict, is_schedule_file, verdicts_json
from foon2asp.api.trees import (
    CandidateReport,
    ConsolidatedGoal,
    Consolidation,
    TreeVerdict,
    check_tree,
    consolidate,
    draw_file,
)
from foon2asp.asp.control import option_names as clingo_option_names
from foon2asp.asp.interrupts import keep_interrupts_until_exit, kept_interrupts
from foon2asp.asp.options import OBJECTIVES as _OBJECTIVES
from foon2asp.batch.results_file import schedules_path
from foon2asp.foon.goals import OBJECT_FILTERS
from foon2asp.foon.motioncost import PRECISION_TEXT as MOTION_COST_PRECISION
from foon2asp.foon.problem import UTENSIL_RULES
from foon2asp.methods.parts import GROUNDING_CHOICES as GROUNDINGS
from foon2asp.methods.registry import Method
from foon2asp.schedule import DEFAULT_ENCODING as DEFAULT_SCHEDULE_ENCODING
from foon2asp.schedule import ScheduleSpec, parse_agents
from foon2asp.schedule.encode import ENCODINGS as SCHEDULE_ENCODINGS
from foon2asp.schedule.result import seconds_text
from foon2asp.schedule.solve import DEFAULT_TIME_LIMIT as SCHEDULE_TIME_LIMIT
from foon2asp.tree.tasktree import WITH_TREE

#: objective names, for ``objective=`` (lexicographic lists of them)
OBJECTIVES: tuple[str, ...] = tuple(_OBJECTIVES)


def methods() -> list[Method]:
    """Every registered method (``.name``, ``.kind``: ``asp`` or ``search``, ``.description``), in order."""
    return [methods_mod.get(name) for name in methods_mod.names()]


def method(name: str) -> Method:
    """The registered method ``name`` (an unknown name is an InputError listing the known ones)."""
    return methods_mod.get(name)


__all__ = ["load", "KnowledgeBase", "Options", "Constraints", "Tree", "CheckReport", "Comparison", "Missing"]
__all__ += ["Reachability", "BatchRun", "Schedule", "ScheduleSpec", "ScheduleVerdict", "SCHEDULE_ENCODINGS"]
__all__ += ["DEFAULT_SCHEDULE_ENCODING", "parse_agents", "is_schedule_file", "schedules_path", "schedules_json"]
__all__ += ["verdicts_json", "check_tree", "TreeVerdict", "consolidate", "Consolidation", "ConsolidatedGoal"]
__all__ += ["CandidateReport", "read_foons", "match_foon", "write_foon", "FOON_FORMATS", "read_program", "draw_file"]
__all__ += ["writable_dir", "write_file", "methods", "method", "OBJECTIVES", "UTENSIL_RULES", "GROUNDINGS"]
__all__ += ["COMPARE_METHODS", "OBJECT_FILTERS", "MOTION_COST_PRECISION", "WITH_TREE", "clingo_option_names"]
__all__ += ["SCHEDULE_TIME_LIMIT", "seconds_text"]
__all__ += ["kept_interrupts", "keep_interrupts_until_exit"]
