"""Schedules: a task tree's units on robot arms and people, with a proven-minimal makespan.

* :mod:`foon2asp.schedule.spec` -- agents, durations, capabilities, resources (parsing)
* :mod:`foon2asp.schedule.model` -- the instance of a tree, agents dealt, schedules compacted
* :mod:`foon2asp.schedule.bounds` -- lower bounds and the list-scheduling baseline
* :mod:`foon2asp.schedule.encode` -- the time-step and clingo-dl encodings
* :mod:`foon2asp.schedule.fixed` -- a fixed tree's optimal schedule
* :mod:`foon2asp.schedule.solve` -- :func:`schedule`, the entry point (fixed tree or joint)
* :mod:`foon2asp.schedule.joint` -- joint scheduling tree by tree (designated trees listed by clingo)
* :mod:`foon2asp.schedule.result` -- :class:`ScheduleResult`: JSON shape and text timeline
* :mod:`foon2asp.schedule.check` -- an independent checker of schedule JSON
"""

from foon2asp.schedule.result import ScheduleResult
from foon2asp.schedule.solve import DEFAULT_ENCODING, schedule
from foon2asp.schedule.spec import ScheduleSpec, parse_agents

__all__ = ["DEFAULT_ENCODING", "ScheduleResult", "ScheduleSpec", "parse_agents", "schedule"]
