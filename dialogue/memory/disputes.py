"""Claims on what the robot holds as someone else's: a thing another person's word made theirs, or
the name of another known person. Such a claim stays the speaker's belief, whatever the trust policy.

    Ana: "the red mug is mine"  -> adopted: mug_red belongsTo person_ana, told by Ana
    Bob: "that mug is mine"     -> disputed: Bob's belief only ("Ana told me the mug is theirs.")
    Bob: "I'm Ana"              -> disputed: Bob's belief only ("I know someone else called Ana.")

Otherwise one person's word would take another's things and name, and what that other person asks
for ("bring me my mug", "bring the mug to Ana") would go to the wrong one. A value the robot
perceived is perception's, which dialogue never overwrites anyway (dialogue.memory.learn); these are
the values people told. A told owner may still be replaced by the owner, or by whoever told it
(their correction). A person's own name stays theirs to give or correct, unless another known
person has it (compared without case: "alice" is Alice).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from dialogue.memory.claims import Claim
from dialogue.memory.provenance import Fact, teller
from kb.protocol import KnowledgeBase
from kb.terms import format_term


@dataclass(frozen=True)
class Dispute:
    """Whose word holds instead: `value` (an owner's id, or the name as another person has it),
    told by `by` (an owner's teller; for a name, the person who has it)."""

    property: str
    value: str
    by: str


def dispute(kb: KnowledgeBase, claim: Claim, speaker: str, told: Sequence[Fact]) -> Dispute | None:
    """Why the claim may not replace what the robot holds, if it may not. `told` are the robot's
    told values of the claim's place (dialogue.memory.learn). Blocking: KB reads."""
    if claim.predicate == "belongsTo":
        return _owned(kb, claim, speaker, told)
    if claim.predicate == "name" and claim.object is not None:
        return _named(kb, claim.subject, claim.object)
    return None


def _owned(kb: KnowledgeBase, claim: Claim, speaker: str, told: Sequence[Fact]) -> Dispute | None:
    for fact in told:
        owner = format_term(fact[2])
        if owner == claim.object:
            continue
        who = teller(kb, fact)
        if who is not None and speaker not in (owner, who):
            return Dispute("belongsTo", owner, who)
    return None


def _named(kb: KnowledgeBase, person: str, name: str) -> Dispute | None:
    wanted = name.casefold()
    for row in kb.find(["?p rdf:type Human", "?p rdfs:label ?n"]):
        other, label = str(row["p"]), str(row["n"])
        if other != person and label.casefold() == wanted:
            return Dispute("rdfs:label", label, other)
    return None
