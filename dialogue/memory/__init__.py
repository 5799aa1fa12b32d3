"""What people tell the robot: claims, their grounding, learning under a trust policy, provenance.

Modules: claims (the predicates table, claims grounded from a model's `facts`; the rules' grammar of
statements and of questions about them is dialogue.understanding's), kinds (classes a preference may
name), provenance (who told a fact, when: RDF reification), learn (beliefs per person, the trust
policy, perception wins), reconcile (perception wins afterwards too), replies (what the robot says
back), people and recollections (each person's memory across dialogues).
"""
