"""Perception wins afterwards too: a perceived value retracts the told values it contradicts."""

from __future__ import annotations

from dialogue.memory.claims import Claim
from dialogue.memory.learn import Memory, Trust
from dialogue.memory.provenance import told
from dialogue.memory.reconcile import Reconciler
from kb import KB
from tests.dialogue.memory.conftest import snapshot_of

BOB = "person_bob"


def tell(memory: Memory, kb: KB, *claims: Claim) -> None:
    memory.settle(claims, speaker=BOB, text="words", snapshot=snapshot_of(kb))


def test_a_perceived_place_retracts_the_told_one_but_not_a_zone_that_holds_it(home: KB) -> None:
    memory = Memory(home, Trust.ALL)
    reconciler = Reconciler(memory)
    assert reconciler.start()
    try:
        tell(memory, home, Claim("keys_1", "isIn", "drawer_1"), Claim("glasses_1", "belongsTo", BOB))
        home.update(["keys_1 isIn kitchen"])  # perceived again in the kitchen, where the drawer is
        reconciler.join()
        assert home.is_asserted("keys_1 isIn drawer_1")
        home.update(["keys_1 isOn table_1", "myself sees keys_1"])  # now the robot sees them on the table
        home.update(["glasses_1 belongsTo person_alice"])  # and a producer says whose the glasses are
        reconciler.join()
        assert not home.is_asserted("keys_1 isIn drawer_1") and home.is_asserted("keys_1 isOn table_1")
        assert not home.is_asserted(f"glasses_1 belongsTo {BOB}")
        assert told(home) == []  # their records went with them
        assert home.is_asserted("keys_1 isIn drawer_1", BOB)  # Bob still believes it
    finally:
        reconciler.stop()


def test_told_values_are_left_alone_by_their_own_commit_and_by_unrelated_facts(home: KB) -> None:
    memory = Memory(home, Trust.ALL)
    reconciler = Reconciler(memory)
    reconciler.start()
    try:
        tell(memory, home, Claim(BOB, "name", "Bob", "text"), Claim(BOB, "likes", "dbr:Tea"))
        home.update([f"{BOB} likes dbr:Coffee", "cup_9 isOn table_1"])
        reconciler.join()
        assert {t.predicate for t in told(home)} == {"rdfs:label", "likes"}
        home.update([f"{BOB} dislikes dbr:Tea"])  # perceived (no record): the opposite told liking goes
        reconciler.join()
        assert [t.predicate for t in told(home)] == ["rdfs:label"]
    finally:
        reconciler.stop()


def test_a_told_fact_retracted_by_anyone_takes_its_record_with_it(home: KB) -> None:
    memory = Memory(home, Trust.ALL)
    reconciler = Reconciler(memory)
    reconciler.start()
    try:
        tell(memory, home, Claim("glasses_1", "isOn", "sofa_1"))
        home.remove(["glasses_1 isOn sofa_1"])  # a producer retracts it (the scene moved them)
        reconciler.join()
        assert told(home) == []  # no record of a fact the robot no longer holds
        # Perceived there again later, the fact is perception's: a statement does not replace it.
        home.update(["glasses_1 isOn sofa_1"])
        reconciler.join()
        tell(memory, home, Claim("glasses_1", "isIn", "drawer_1"))
        assert home.is_asserted("glasses_1 isOn sofa_1") and not home.is_asserted("glasses_1 isIn drawer_1")
    finally:
        reconciler.stop()
