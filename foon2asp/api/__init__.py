"""The Python API: load a FOON with its kitchen, then ask it for task trees.

>>> import foon2asp
>>> kb = foon2asp.load("demo")
>>> t = kb.solve("tomato salad")
>>> t.status, t.cost["units"]
('optimal', 1)

Every command of the ``foon2asp`` command line is a thin layer over these
calls: :func:`load` reads the data, :class:`KnowledgeBase` answers
(:meth:`~KnowledgeBase.solve`, :meth:`~KnowledgeBase.check`,
:meth:`~KnowledgeBase.compare`, :meth:`~KnowledgeBase.reachable`,
:meth:`~KnowledgeBase.missing`, :meth:`~KnowledgeBase.query`,
:meth:`~KnowledgeBase.batch`, :meth:`~KnowledgeBase.schedule`, :meth:`~KnowledgeBase.facts`) with the settings of
one request (:class:`Options`), and the answers render themselves in every
format of :mod:`foon2asp.report`.  Tree files without a FOON: :func:`check_tree`
judges one on its own, :func:`consolidate` merges candidate trees of one recipe
into one proven-best tree per goal.

The modules, each importing only those before it: :mod:`~foon2asp.api.options` (the request),
:mod:`~foon2asp.api.catalog` (methods, objectives and the other names a front end offers),
:mod:`~foon2asp.api.matching` (goals, tree files and substitutes as the comparison sees them),
:mod:`~foon2asp.api.files` (FOON files, programs, output files), :mod:`~foon2asp.api.schedules`
(the agents of a schedule, schedule files checked), :mod:`~foon2asp.api.results` (the answers),
:mod:`~foon2asp.api.batches` (batch runs), :mod:`~foon2asp.api.kb` (the knowledge base),
:mod:`~foon2asp.api.load` (reading data) and :mod:`~foon2asp.api.trees` (tree files judged on
their own or drawn, candidates consolidated).
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
