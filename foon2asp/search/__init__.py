"""Search baselines: the classic task-tree searches: IDS and greedy best-first search (h1, h2).

They are faithful to the earlier FOON search programs, weaknesses included:
neither checks that the tree it returns is well-founded, so a greedy tree may
rest on a cycle (``foon2asp check`` and ``foon2asp compare`` report that).
All read the semantics from :class:`~foon2asp.foon.problem.Problem`:
``required`` (the utensil rule), ``producers`` (outputs with no state,
ingredient or container are not products) and ``kitchen``.

* ``ids`` -- iterative deepening: a depth-limited recursive search from the
  goal with bound 0, 1, 2, ...  An object in the kitchen succeeds; otherwise,
  with depth left, the producers are tried in FOON file order and a unit
  succeeds when all its required inputs succeed with one level less.  Results
  are memoised per (object, depth), so a bound costs at most
  objects x depth unit tries.  A goal not found within as many levels as the
  kitchen's derivation fixpoint has is not found (no deeper tree exists).
* ``gbfs-h1`` / ``gbfs-h2`` -- a FIFO queue of objects, starting with the
  goal; already searched objects are skipped, kitchen objects are done,
  otherwise one producer is chosen by the heuristic and its required inputs
  are queued.  h1: highest motion success rate; h2: fewest input nodes
  (all inputs of the unit).  Ties go to the unit first in FOON file order.
  An object with no producer makes the search fail.  The tree is the
  selected units in reverse selection order, as the earlier programs wrote
  it; that order is kept as it is, even when it is not executable.

Status is ``found`` or ``not-found``; the cost is :func:`~foon2asp.tree.measures`.
"""

from foon2asp.search.gbfs import gbfs
from foon2asp.search.heuristics import HEURISTICS, h1, h2
from foon2asp.search.ids import IDS

__all__ = ["IDS", "gbfs", "h1", "h2", "HEURISTICS"]
