"""Claims on what the robot holds as someone else's: a thing another's word made theirs, a known name."""

from __future__ import annotations

from datetime import UTC, datetime

from rdflib import URIRef

from dialogue.memory.claims import Claim
from dialogue.memory.disputes import Dispute, dispute
from dialogue.memory.provenance import Fact, record
from kb import KB
from kb.terms import ORO

WHEN = datetime(2025, 6, 1, tzinfo=UTC)


def told(kb: KB, thing: str, owner: str, by: str) -> Fact:
    fact: Fact = (URIRef(ORO + thing), URIRef(ORO + "belongsTo"), URIRef(ORO + owner))
    kb.update([f"{thing} belongsTo {owner}", *record(fact, URIRef(ORO + by), WHEN, "words")])
    return fact


def test_a_thing_told_to_be_someone_elses_is_theirs_against_a_third_persons_word(home: KB) -> None:
    by_alice = told(home, "mug_red", "person_alice", "person_alice")
    claim = Claim("mug_red", "belongsTo", "person_bob")
    assert dispute(home, claim, "person_bob", [by_alice]) == Dispute("belongsTo", "person_alice", "person_alice")
    assert dispute(home, claim, "person_ines", [by_alice]) is not None
    assert dispute(home, claim, "person_alice", [by_alice]) is None  # the owner gives it away
    by_ines = told(home, "keys_1", "person_alice", "person_ines")
    keys = Claim("keys_1", "belongsTo", "person_bob")
    assert dispute(home, keys, "person_ines", [by_ines]) is None  # whoever told it corrects it
    assert dispute(home, keys, "person_bob", [by_ines]) == Dispute("belongsTo", "person_alice", "person_ines")
    assert dispute(home, Claim("mug_red", "belongsTo", "person_alice"), "person_bob", [by_alice]) is None


def test_a_name_another_known_person_has_is_theirs_whatever_its_case(home: KB) -> None:
    for name in ("Alice", "alice", "ALICE"):
        assert dispute(home, Claim("person_bob", "name", name, "text"), "person_bob", []) == Dispute(
            "rdfs:label", "Alice", "person_alice")
    assert dispute(home, Claim("person_alice", "name", "Alice", "text"), "person_alice", []) is None
    assert dispute(home, Claim("person_bob", "name", "Alicia", "text"), "person_bob", []) is None
    assert dispute(home, Claim("person_bob", "name", "kitchen", "text"), "person_bob", []) is None  # no person's
