"""Answers to the robot's question: to its question about a request (a fragment that completes it,
a confirmation, an accepted offer, a correction), about a statement, and to the ask role's form."""
