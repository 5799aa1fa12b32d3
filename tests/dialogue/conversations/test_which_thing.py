"""Issue 30, class 2: a reply names a thing as a person tells it from others of its name."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.dialogue.conversations.talk import Talk, person, robot, talking, thing, zone

WORKSHOP = [
    *robot(), *zone("workshop", "workshop"), *zone("shed", "shed"),
    *person("person_tess", "Tess", zone="workshop", seen=True),
    *thing("bench_1", "dbr:Table_(furniture)", "bench", zone="workshop", seen=True),
    *thing("flask_green", "dbr:Bottle", "flask", color="green", on="bench_1", seen=True),
    *thing("flask_grey", "dbr:Bottle", "flask", color="grey", on="bench_1", seen=True),
    # Two spades told apart by whose they are, a lone saw by nothing.
    *thing("spade_1", "Artifact", "spade", owner="person_tess", zone="shed"),
    *thing("spade_2", "Artifact", "spade", zone="shed"),
    *thing("saw_1", "Artifact", "saw", on="bench_1", seen=True),
]


@pytest.fixture
def talk() -> Iterator[Talk]:
    with talking(WORKSHOP, "person_tess") as talk:
        yield talk


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
