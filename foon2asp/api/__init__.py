"""The Python API: load a FOON with its kitchen, then ask it for task trees.

>>> import foon2asp
>>> kb = foon2asp.load("demo")
>>> t = kb.solve("tomato salad")
>>> t.status, t.cost["units"]
('optimal', 1)

Every command of ``foon2asp`` is a thin layer over these calls: :func:`load` reads the data,
:class:`KnowledgeBase` answers with the settings of one request (:class:`Options`), and the
answers render themselves in the formats of :mod:`foon2asp.report`.  The modules import each
other one way: options, catalog, matching, files, schedules, results, batches, kb, load, trees.
"""

from foon2asp.api.batches import BatchRun
from foon2asp.api.catalog import (
    COMPARE_METHODS,
    GROUNDINGS,
    MOTION_COST_PRECISION,
    OBJECT_FILTERS,
    OBJECTIVES,
    UTENSIL_RULES,
    method,
    methods,
)
from foon2asp.api.files import (
    FOON_FORMATS,
    match_foon,
    read_foons,
    read_program,
    writable_dir,
    write_file,
    write_foon,
)
from foon2asp.api.kb import GoalLike, KnowledgeBase
from foon2asp.api.load import load
from foon2asp.api.options import Constraints, Options, Settings
from foon2asp.api.results import CheckReport, Comparison, Missing, Reachability, Schedule, Tree, schedules_json
from foon2asp.api.schedules import (
    DEFAULT_SCHEDULE_ENCODING,
    SCHEDULE_ENCODINGS,
    SCHEDULE_STATUSES,
    ScheduleVerdict,
    is_schedule_file,
    verdicts_json,
)
from foon2asp.api.trees import (
    CandidateReport,
    ConsolidatedGoal,
    Consolidation,
    TreeVerdict,
    check_tree,
    consolidate,
    draw_file,
)
from foon2asp.batch.schedules import schedules_path
from foon2asp.schedule import ScheduleSpec, parse_agents

__all__ = [
    "load",
    "KnowledgeBase",
    "GoalLike",
    "Options",
    "Settings",
    "Constraints",
    "Tree",
    "CheckReport",
    "Comparison",
    "Missing",
    "Reachability",
    "BatchRun",
    "Schedule",
    "ScheduleSpec",
    "ScheduleVerdict",
    "SCHEDULE_STATUSES",
    "SCHEDULE_ENCODINGS",
    "DEFAULT_SCHEDULE_ENCODING",
    "parse_agents",
    "is_schedule_file",
    "schedules_path",
    "schedules_json",
    "verdicts_json",
    "check_tree",
    "TreeVerdict",
    "consolidate",
    "Consolidation",
    "ConsolidatedGoal",
    "CandidateReport",
    "read_foons",
    "match_foon",
    "write_foon",
    "FOON_FORMATS",
    "read_program",
    "draw_file",
    "writable_dir",
    "write_file",
    "methods",
    "method",
    "OBJECTIVES",
    "UTENSIL_RULES",
    "GROUNDINGS",
    "COMPARE_METHODS",
    "OBJECT_FILTERS",
    "MOTION_COST_PRECISION",
]
