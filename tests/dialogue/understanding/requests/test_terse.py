"""Terse and non-native requests: the phrase fronted before the verb, no determiners, no verb."""

import pytest

from dialogue import intents as I
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.requests.terse import terse
from kb import KB
from tests.dialogue.conftest import lexicon_of

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
