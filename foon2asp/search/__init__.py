"""Search baselines: the classic task-tree searches: IDS and greedy best-first search (h1, h2).

They are faithful to the earlier FOON search programs, weaknesses included: neither checks
that its tree is well-founded, so a greedy tree may rest on a cycle.  ``ids`` deepens a
memoised depth-limited search from the goal, trying producers in FOON file order;
``gbfs-h1`` and ``gbfs-h2`` choose one producer per object of a FIFO queue by highest motion
success rate or fewest input nodes.  Status is ``found`` or ``not-found``.
"""

from foon2asp.search.gbfs import gbfs
from foon2asp.search.heuristics import h1, h2
from foon2asp.search.ids import IDS

__all__ = ["IDS", "gbfs", "h1", "h2"]
