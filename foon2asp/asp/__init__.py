"""The clingo layer: facts, where the encodings are, groundings, the one control wrapper, sessions, objectives and decoding models into trees."""
