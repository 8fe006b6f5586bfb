"""bench/calls.py: the clingo calls of answering goals, counted and timed by kind."""

from __future__ import annotations

import calls
from synth import preset


def test_calls_counts_every_clingo_call_of_the_goals_it_answers():
    syn = preset("small")
    problem = syn.problem()
    goals = [problem.foon.object_ids[g] for g in syn.goals]
    spent, count, routes, wall, together = calls.measure(problem, goals, ("units",))
    assert sum(routes.values()) == len(goals)
    searched = routes.get("prepared", 0) + routes.get("clingo", 0)
    assert searched > together > 0
    # each goal clingo searches alone has its own control, parsed, grounded and solved at least
    # once; the goals decided together share one
    controls = searched - together + 1
    assert count["create"] >= controls and count["solve"] >= controls
    assert count["ground"] >= count["create"] and count["parse"] >= count["create"]
    assert 0 < sum(spent.values()) < wall
    # the clingo API is itself again afterwards
    assert (
        not hasattr(calls.clingo.Control.solve, "__wrapped__") and "wrapper" not in calls.clingo.Control.solve.__name__
    )
