"""Terse and non-native requests: the phrase fronted before the verb, no determiners, no verb."""

import pytest

from dialogue import intents as I
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.requests.terse import terse
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb
from tests.dialogue.understanding.test_interpret import say

BOB = "person_bob"


@pytest.mark.parametrize(
    ("text", "intent", "roles"),
    [
        ("Go desk.", I.MOVE_TO, {"goal": "desk_1"}),
        ("You go hallway.", I.MOVE_TO, {"goal": "hallway"}),
        ("Hallway, go.", I.MOVE_TO, {"goal": "hallway"}),
        ("Ari, hallway. Now please.", I.MOVE_TO, {"goal": "hallway"}),
        ("You pick stapler.", I.GRAB_OBJECT, {"object": "stapler_1"}),
        ("Pear put on shelf.", I.PLACE_OBJECT, {"object": "pear_1", "recipient": "shelf_9"}),
        ("Pear onto shelf, please.", I.PLACE_OBJECT, {"object": "pear_1", "recipient": "shelf_9"}),
        ("Stapler, take to Carol.", I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_carol"}),
        ("Ari, stapler, please.", I.BRING_OBJECT, {"object": "stapler_1", "recipient": BOB}),
        ("Stapler — to Carol — quick.", I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_carol"}),
        ("the stapler for Carol", I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_carol"}),
        # after a remark, the clauses to the end
        ("Carol asked: the stapler, give to Carol.", I.BRING_OBJECT,
         {"object": "stapler_1", "recipient": "person_carol"}),
        # after a need the words of which read as a request, no request of its own said before it
        ("I need ... how you say ... for the paper ... the stapler, please", I.BRING_OBJECT,
         {"object": "stapler_1", "recipient": BOB}),
    ],
)
def test_terse_requests_are_read_in_the_grammars_order(office: KB, text: str, intent: str, roles: dict) -> None:
    out = Interpreter(lexicon_of(office), BOB, robot_name="Ari").interpret(text)
    assert (out.intent, out.roles) == (intent, roles), out.reply


@pytest.mark.parametrize(
    "text",
    ["go to the desk", "Carol, go to the hallway", "the stapler", "I need the stapler", "it is on the shelf"],
)
def test_only_a_whole_known_phrase_is_moved(office: KB, text: str) -> None:
    assert terse(text, lexicon_of(office), "ari") is None


@pytest.mark.parametrize(
    "text",
    # a thing alone is no request without politeness, nor a place or furniture with it, nor a thing
    # given to what is no one
    ["stapler", "the hallway, please", "the desk, please", "stapler to the hallway"],
)
def test_a_thing_alone_is_asked_for_only_when_politeness_says_so(office: KB, text: str) -> None:
    out = Interpreter(lexicon_of(office), BOB, robot_name="Ari").interpret(text)
    assert out.intent != I.BRING_OBJECT, out.reply


def test_a_request_with_its_verb_and_politeness_is_not_read_as_a_thing_alone(office: KB) -> None:
    out = Interpreter(lexicon_of(office), BOB, robot_name="Ari").interpret("Could you grab the stapler, please?")
    assert (out.intent, out.roles) == (I.GRAB_OBJECT, {"object": "stapler_1"}), out.reply


def test_a_thing_said_to_the_robots_question_is_the_answer_not_a_request(office: KB) -> None:
    assert terse("stapler, please", lexicon_of(office), "ari") == "bring me stapler"
    assert terse("stapler, please", lexicon_of(office), "ari", answering=True) is None


def test_words_that_all_describe_one_thing_are_no_verb_of_an_activity() -> None:
    kb = scene_kb(None,
        "myself rdf:type Robot", "ann rdf:type Human", 'ann rdfs:label "Ann"', "myself sees ann",
        "w1 rdf:type dbr:Bottle", 'w1 rdfs:label "bottle of still water"', "w1 isMovable true", "myself sees w1",
        "w2 rdf:type dbr:Bottle", 'w2 rdfs:label "bottle of sparkling water"', "w2 isMovable true",
        "myself sees w2",
    )  # fmt: skip
    # asked for with politeness: brought
    out = say(kb, "still water, please", speaker="ann")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "w1", "recipient": "ann"})
    # said bare, the bringing is only proposed, never an activity of watering
    for text in ("Water. Still.", "the still water"):
        out = say(kb, text, speaker="ann")
        assert out.intent is None and out.reply == "Shall I bring the bottle of still water to you?"
    kb.close()
