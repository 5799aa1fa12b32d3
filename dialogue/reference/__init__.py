"""Reference resolution: from words to KB entities, shared by the rules and model answers."""
