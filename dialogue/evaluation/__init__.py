"""Evaluation and comparison of backends on dialogue case sets (a tool, not run-time code)."""
