"""Issue 30, classes 4 and 5 (in part): answers that agree with each other and say what the robot
can do; leave-taking and a joke answered in words."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from dialogue import intents as I
from dialogue.understanding.replies import abilities
from tests.dialogue.conftest import english
from tests.dialogue.conversations.talk import Talk, talking

PORCH = [
    "myself rdf:type Robot",
    'porch rdf:type ZoneOfInterest', 'porch rdfs:label "porch"',
    'person_lou rdf:type Human', 'person_lou rdfs:label "Lou"', "person_lou isIn porch", "myself sees person_lou",
    'person_bo rdf:type Human', 'person_bo rdfs:label "Bo"', "person_bo isIn porch", "myself sees person_bo",
    'person_kim rdf:type Human', 'person_kim rdfs:label "Kim"', "person_kim isIn garage",
    'garage rdf:type ZoneOfInterest', 'garage rdfs:label "garage"',
    'lamp_1 rdf:type Artifact', 'lamp_1 rdfs:label "lamp"', "lamp_1 isIn porch", "myself sees lamp_1",
]  # fmt: skip


@pytest.fixture
def talk() -> Iterator[Talk]:
    with talking(PORCH, "person_lou") as talk:
        yield talk


def test_counting_people_agrees_with_naming_them(talk: Talk) -> None:
    assert talk("who do you see?").reply == "I see Bo and you."
    assert talk("how many people can you see?").reply == "I see two people: Bo and you."


def test_whether_someone_is_somewhere_starts_with_what_the_kb_says(talk: Talk) -> None:
    assert talk("is Kim in the garage?").reply == "Yes, as far as I know Kim is in the garage. I don't see them right now."
    assert talk("is Kim on the porch?").reply == "No, as far as I know Kim is in the garage. I don't see them right now."


def test_what_the_robot_can_do_is_said_from_its_intents(talk: Talk) -> None:
    said = talk("what can you do?")
    assert said.intents == () and said.reply.startswith("I can ")
    assert "pick things up" in said.reply and "bring things to people" in said.reply
    assert talk("help").reply == said.reply


def test_leave_taking_and_jokes_are_answered_in_words(talk: Talk) -> None:
    for bye in ("bye", "see you later", "goodbye"):
        said = talk(bye)
        assert said.reply == "Goodbye Lou, it was nice talking to you!" and said.intents == ()
    joke = talk("tell me a joke")
    assert joke.intents == () and "joke" in joke.reply


def test_abilities_follow_the_intent_catalogues_order() -> None:
    said = abilities(english())
    at = [said.index(p) for p in ("go places", "pick things up", "bring things to people")]
    assert at == sorted(at) and list(I.CATALOGUE).index(I.MOVE_TO) < list(I.CATALOGUE).index(I.GRAB_OBJECT)
