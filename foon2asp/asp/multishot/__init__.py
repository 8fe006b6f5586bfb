"""Multi-shot solving on one grounding: the depth and meal drivers beyond a single optimisation."""
