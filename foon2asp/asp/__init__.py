"""The clingo layer: facts, encodings, the one control wrapper, sessions, objectives and the model reader."""
