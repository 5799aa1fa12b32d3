"""What people tell the robot: claims, their grounding, learning under a trust policy, provenance.

Modules: claims (the predicates table, claims grounded from a model's `facts`), statements, asking
and followup (the rules' grammar of statements, of questions about what was told, and of the answer
to a question about a statement; likings the statements' preferences, clause the reader they share),
names (which words are a name), reading (them tied into the rules model), kinds (classes a
preference may name), provenance (who told a fact, when: RDF reification), learn (beliefs per
person, the trust policy, perception wins), reconcile (perception wins afterwards too), replies
(what the robot says back), people and recollections (each person's memory across dialogues).
"""
