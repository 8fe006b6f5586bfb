"""Optimal trees by maximum satisfiability: the second exact back end beside clingo.

:mod:`foon2asp.maxsat.oracle` is the one wrapper of the MaxSAT solver (RC2 of PySAT,
interruptible, with a valid lower bound at every moment); :mod:`foon2asp.maxsat.trees`
writes a goal's minimum-weight tree problem for it and reads the answer back.  Two more
solvers take the same formula on the goals RC2 finds hard: UWrMaxSat in a child process
(:mod:`foon2asp.maxsat.uwr`) and HiGHS as a 0/1 program (:mod:`foon2asp.maxsat.mip`).
"""
