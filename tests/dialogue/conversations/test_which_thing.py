"""Issue 30, class 2: a reply names a thing as a person tells it from others of its name."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.dialogue.conversations.talk import Talk

WORKSHOP = [
    "myself rdf:type Robot",
    'workshop rdf:type ZoneOfInterest', 'workshop rdfs:label "workshop"',
    'shed rdf:type ZoneOfInterest', 'shed rdfs:label "shed"',
    'person_tess rdf:type Human', 'person_tess rdfs:label "Tess"', "person_tess isIn workshop",
    "myself sees person_tess",
    "bench_1 rdf:type dbr:Table_(furniture)", 'bench_1 rdfs:label "bench"', "bench_1 isIn workshop",
    "myself sees bench_1",
    'flask_green rdf:type dbr:Bottle', 'flask_green rdfs:label "flask"', "flask_green hasColor green",
    "flask_green isOn bench_1", "myself sees flask_green",
    'flask_grey rdf:type dbr:Bottle', 'flask_grey rdfs:label "flask"', "flask_grey hasColor grey",
    "flask_grey isOn bench_1", "myself sees flask_grey",
    # Two spades told apart by whose they are, a lone saw by nothing.
    'spade_1 rdf:type Artifact', 'spade_1 rdfs:label "spade"', "spade_1 belongsTo person_tess", "spade_1 isIn shed",
    'spade_2 rdf:type Artifact', 'spade_2 rdfs:label "spade"', "spade_2 isIn shed",
    'saw_1 rdf:type Artifact', 'saw_1 rdfs:label "saw"', "saw_1 isOn bench_1", "myself sees saw_1",
]  # fmt: skip


@pytest.fixture
def talk() -> Iterator[Talk]:
    talk = Talk(WORKSHOP, "person_tess")
    yield talk
    talk.close()


def test_an_intent_taken_on_names_the_thing_told_apart_with_its_id_unchanged(talk: Talk) -> None:
    said = talk("hand me the grey flask")
    assert said.reply == "OK, I will bring the grey flask to you."
    assert said.intents == (("__intent_bring_object__", {"object": "flask_grey", "recipient": "person_tess"}),)
    asked = talk("pick up the flask")
    assert asked.intents == () and asked.reply.endswith("?")
    answered = talk("the green one")
    assert answered.reply == "OK, I will pick up the green flask."
    assert answered.intents == (("__intent_grab_object__", {"object": "flask_green"}),)
    # A thing no other shares its name with is named plainly.
    assert talk("pick up the saw").reply == "OK, I will pick up the saw."


def test_several_of_a_kind_are_counted_and_told_apart(talk: Talk) -> None:
    assert talk("how many flasks do you see?").reply == "I see two flasks: the green one and the grey one."
    seen = talk("what do you see?").reply
    assert "the green flask" in seen and "the grey flask" in seen


def test_whose_it_is_tells_namesakes_apart(talk: Talk) -> None:
    assert talk("where is my spade?").reply == "Your spade is in the shed. I don't see it right now."
