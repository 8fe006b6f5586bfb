"""Bounds on the optimum without the solver: a valid tree (upper bound), landmarks and lower bounds.

:mod:`foon2asp.bounds.upper` finds a cheap valid tree for any derivable goal,
:mod:`foon2asp.bounds.lower` the landmarks and a lower bound of each goal and the units an
optimal tree may use.  Why these are bounds: docs/proofs/preparation.md.
"""
