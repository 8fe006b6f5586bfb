"""Schedules: a task tree's units on robot arms and people, with a proven-minimal makespan.

The modules follow the data: spec -> instances -> lower_bounds/baseline -> shaving -> encode ->
joint/solve -> result; checker reads schedule JSON on its own.
"""

from foon2asp.schedule.result import ScheduleResult
from foon2asp.schedule.solve import DEFAULT_ENCODING, schedule
from foon2asp.schedule.spec import ScheduleSpec, parse_agents

__all__ = ["DEFAULT_ENCODING", "ScheduleResult", "ScheduleSpec", "parse_agents", "schedule"]
