"""Task trees: the result value, measures, weights, the independent validator and diagnosis."""
