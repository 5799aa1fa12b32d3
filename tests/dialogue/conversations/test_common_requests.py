"""Issue 30, class 5: common requests as people make them in a workshop — a farewell answered and
ending the conversation (and the next words opening it again), "follow me" and "wait here" mapped
to the intents that fit, and corrections by description ("no, the yellow one", "both")."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator

import pytest

from dialogue import intents as I
from tests.dialogue.conversations.talk import Said, Talk, talking

WORKSHOP = [
    "myself rdf:type Robot",
    'workshop rdf:type ZoneOfInterest', 'workshop rdfs:label "workshop"',
    'person_nia rdf:type Human', 'person_nia rdfs:label "Nia"', "person_nia isIn workshop", "myself sees person_nia",
    'person_oskar rdf:type Human', 'person_oskar rdfs:label "Oskar"', "person_oskar isIn workshop",
    "myself sees person_oskar",
    'bench_1 rdf:type Table', 'bench_1 rdfs:label "workbench"', "bench_1 isIn workshop", "myself sees bench_1",
    'torch_y rdf:type Artifact', 'torch_y rdfs:label "torch"', "torch_y hasColor yellow", "torch_y isOn bench_1",
    "myself sees torch_y",
    'torch_b rdf:type Artifact', 'torch_b rdfs:label "torch"', "torch_b hasColor black", "torch_b isOn bench_1",
    "myself sees torch_b",
]  # fmt: skip


@pytest.fixture
def talk() -> Iterator[Talk]:
    with talking(WORKSHOP, "person_nia") as talk:
        yield talk


def _over(talk: Talk) -> str:
    return talk.manager.progress(talk.manager.get(talk.dialogue)).status


def test_a_farewell_is_answered_and_ends_the_conversation(talk: Talk) -> None:
    for bye in ("bye", "see you later", "goodbye robot", "thanks, bye"):
        said = talk(bye)
        assert said.reply == "Goodbye Nia, it was nice talking to you!" and said.intents == ()
        assert _over(talk) == "done"
        # the turn said so to whoever waits for the end: the ROS goal, the chat
        result = asyncio.run(talk.manager.interact("person_nia", "hello", dialogue_id=talk.dialogue))
        assert result.dialogue_terminal is None and _over(talk) == "open"  # talking again opens it


def test_a_farewell_ends_the_turn_as_terminal(talk: Talk) -> None:
    result = asyncio.run(talk.manager.interact("person_nia", "good night", dialogue_id=talk.dialogue))
    assert result.dialogue_terminal is True and result.response.startswith("Goodbye Nia")
    hello = asyncio.run(talk.manager.interact("person_nia", "pick up the black torch", dialogue_id=talk.dialogue))
    assert hello.dialogue_terminal is None and hello.intents[0].intent == I.GRAB_OBJECT


def test_follow_me_starts_following_the_speaker(talk: Talk) -> None:
    for said in ("follow me", "please follow me", "can you follow us?"):
        following = ((I.START_ACTIVITY, {"object": "follow", "recipient": "person_nia"}),)
        assert talk(said) == Said("OK, I will follow you.", following)


def test_wait_here_stops_what_the_robot_is_about(talk: Talk) -> None:
    for said in ("wait here", "stay here a moment", "stay put", "please wait here"):
        assert talk(said) == Said("OK, I am stopping.", ((I.STOP_ACTIVITY, {}),))
    # "wait" alone says nothing of staying put; a place to wait at is a place to go
    assert talk("wait").intents[0][0] == I.RAW_USER_INPUT
    assert talk("wait by the workbench").intents == ((I.MOVE_TO, {"goal": "bench_1"}),)


def test_no_the_other_colour_corrects_the_thing_just_asked_for(talk: Talk) -> None:
    assert talk("bring me the black torch").intents == ((I.BRING_OBJECT, {"object": "torch_b", "recipient": "person_nia"}),)
    assert talk("no, the yellow one") == Said("OK, I will bring the yellow torch to you.",
                                              ((I.BRING_OBJECT, {"object": "torch_y", "recipient": "person_nia"}),))
    assert talk("pick up the yellow torch").intents == ((I.GRAB_OBJECT, {"object": "torch_y"}),)
    assert talk("nope, the black one!").intents == ((I.GRAB_OBJECT, {"object": "torch_b"}),)


def test_both_answers_which_one_with_each_of_them(talk: Talk) -> None:
    assert talk("pass me the torch").reply == "Which torch do you mean: the black one or the yellow one?"
    said = talk("both of them")
    assert said.reply == "OK, I will bring the black torch to you. Then I will bring the yellow torch to you."
    assert said.intents == ((I.BRING_OBJECT, {"object": "torch_b", "recipient": "person_nia"}),
                            (I.BRING_OBJECT, {"object": "torch_y", "recipient": "person_nia"}))
    assert talk("both").intents[0][0] == I.RAW_USER_INPUT  # nothing asked about any more


def test_the_left_one_is_said_to_be_unknown_and_the_question_still_answered(talk: Talk) -> None:
    asked = talk("pass me the torch").reply
    said = talk("the left one")
    assert said.intents == () and said.reply == f"Sorry, I can't tell which one is the left one. {asked}"
    assert talk("the yellow one").intents == ((I.BRING_OBJECT, {"object": "torch_y", "recipient": "person_nia"}),)
