"""Requests: the verb frames and the constructions a frame cannot say, an utterance's act and its
roles' phrases, compound and terse requests, and each role's phrase grounded in the KB."""
