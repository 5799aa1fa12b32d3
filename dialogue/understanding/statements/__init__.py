"""Statements: what a person tells the robot ("I'm Bob", "the keys are in the drawer", "I like
tea"), read as facts of the answer schema; which words can be a name."""
