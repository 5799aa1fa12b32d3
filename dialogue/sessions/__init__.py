"""Dialogue sessions: where dialogues live and how their turns are run one at a time.

`manager` (the dialogue manager: start, end, run a turn through the dialogue's role), `store` (the
`SessionStore` protocol, the session state, `MemorySessions`), `sparql` (`SparqlSessions`: the
sessions in a SPARQL store several service processes share), `turnqueue` (the turns of one dialogue
in arrival order, each by its own deadline).
"""
