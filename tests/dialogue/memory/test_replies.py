"""What the robot says back: one sentence per claim, perception's word when it wins."""

from __future__ import annotations

from dialogue.memory.claims import Claim
from dialogue.memory.learn import Outcome, Settled
from dialogue.memory.replies import confirmation
from kb import KB
from tests.dialogue.conftest import english
from tests.dialogue.memory.conftest import snapshot_of

BOB = "person_bob"


def say(kb: KB, *outcomes: Outcome, names: dict[str, str] | None = None) -> str:
    return confirmation(english(), Settled(outcomes, names or {}), snapshot_of(kb), BOB)


def test_confirmations(home: KB) -> None:
    assert say(home, Outcome(Claim(BOB, "name", "Bob", "text"), "adopted", "Bob")) == "Nice to meet you, Bob."
    assert say(home, Outcome(Claim(BOB, "name", "Rob", "text"), "adopted", "Rob", replaced=("Bob",))) == (
        "Got it: Rob, not Bob.")
    assert say(home, Outcome(Claim("mug_red", "belongsTo", BOB), "adopted", BOB),
               Outcome(Claim("keys_1", "isIn", "drawer_1"), "adopted", "drawer_1")) == (
        "OK, the mug is yours and the keys are in the drawer.")
    tea = Outcome(Claim("person_alice", "dislikes", "dbr:Tea"), "adopted", "dbr:Tea")
    assert say(home, tea, names={"dbr:Tea": "tea"}) == "OK, Alice doesn't like tea."
    ines = Outcome(Claim("phone_1", "belongsTo", "person_ines"), "believed", "person_ines")
    assert say(home, ines) == "OK, I'll remember that you said the phone is Ines's."


def test_perception_is_said_when_it_wins(home: KB) -> None:
    remote = Outcome(Claim("remote_1", "isIn", "drawer_1"), "perceived", "drawer_1", held=(("isOn", "sofa_1"),))
    assert say(home, remote) == "I can see the remote on the couch, though."
    keys = Outcome(Claim("keys_1", "isOn", "table_1"), "perceived", "table_1", held=(("isIn", "kitchen"),))
    assert say(home, keys) == "As far as I know, the keys are in the kitchen."
    book = Outcome(Claim("book_1", "belongsTo", BOB), "perceived", BOB, held=(("belongsTo", "person_alice"),))
    assert say(home, book) == "As far as I know, the cookbook is Alice's."
    name = Outcome(Claim("person_alice", "name", "Ally", "text"), "perceived", "Ally", held=(("rdfs:label", "Alice"),))
    assert say(home, name) == "I know them as Alice, though."


def test_another_persons_word_is_said_when_it_holds(home: KB) -> None:
    def mug(by: str, owner: str) -> Outcome:
        return Outcome(Claim("mug_red", "belongsTo", BOB), "disputed", BOB, held=(("belongsTo", owner),),
                       hearsay=((by, owner),))

    assert say(home, mug("person_alice", "person_alice")) == "Alice told me the mug is theirs."
    assert say(home, mug("person_ines", "person_alice")) == "Ines told me the mug is Alice's."
    assert say(home, mug("person_x", "person_alice")) == "Someone told me the mug is Alice's."  # no name known
    alice = Outcome(Claim(BOB, "name", "Alice", "text"), "disputed", "Alice", held=(("rdfs:label", "Alice"),),
                    hearsay=(("person_alice", "Alice"),))
    assert say(home, alice) == "I know someone else called Alice."


def test_answers(home: KB) -> None:
    likes = Outcome(Claim("person_alice", "likes", None), "answered",
                    held=(("likes", "dbr:Tea"), ("likes", "dbr:Coffee")))
    assert say(home, likes, names={"dbr:Tea": "tea", "dbr:Coffee": "coffee"}) == "Alice likes tea and coffee."
    hearsay = Outcome(Claim("person_alice", "dislikes", None), "answered", hearsay=(("person_ines", "dbr:Tea"),))
    assert say(home, hearsay, names={"dbr:Tea": "tea"}) == "Ines told me Alice doesn't like tea."
    assert say(home, Outcome(Claim(BOB, "name", None), "answered")) == "I don't know your name yet. What is it?"
    assert say(home, Outcome(Claim("person_alice", "likes", None), "answered")) == "I don't know what Alice likes."
    assert say(home, Outcome(Claim(BOB, "likes", "jazz", "kind"), "unknown", "jazz")) == (
        "Sorry, I don't know what jazz is.")


def test_the_robot_is_me(home: KB) -> None:
    assert say(home, Outcome(Claim(BOB, "likes", "myself"), "adopted", "myself")) == "OK, you like me."
