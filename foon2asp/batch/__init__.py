"""Batches of goals: the grounding policy, the worker pool and the results file."""
