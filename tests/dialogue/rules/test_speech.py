"""Speech-recogniser and chat style: what normalisation and the grammar make of it."""

import pytest

from dialogue import intents as I
from dialogue.rules.commands import parse
from dialogue.rules.utterance import cleaned, normalise


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("wheres my phone", "where is my phone"),
        ("im thirsty shes here", "i am thirsty she is here"),
        ("put the uh cup erm on the table", "put the cup on the table"),
        ("put the put the knife on table four", "put the knife on table four"),
        ("pick up the the red jumper", "pick up the red jumper"),
        ("bring me the uh no wait put the candle on the table", "put the candle on the table"),
        ("take the beaker to uh sorry i mean put the beaker on the bench", "put the beaker on the bench"),
        ("pick up the cup you know the blue one", "pick up the cup the blue one"),
        ("do you know where the keys are", "do you know where the keys are"),  # not a filler here
        ("table 4 4", "table 4 4"),  # numbers are not stutters
    ],
)
def test_normalise(text: str, words: str) -> None:
    assert " ".join(normalise(text)) == words


def test_cleaned_keeps_text_without_repairs() -> None:
    assert cleaned('Say "Hello, Tom!" to Tom') == 'Say "Hello, Tom!" to Tom'
    assert cleaned("put the put the cup down") == "put the cup down"


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        ("john can you go to the bathroom", I.MOVE_TO, {"goal": ("the", "bathroom")}),
        ("michael go to the kitchen", I.MOVE_TO, {"goal": ("the", "kitchen")}),
        ("hey tiago pick up the red jumper", I.GRAB_OBJECT, {"object": ("the", "red", "jumper")}),
        ("listen go to the kitchen", I.MOVE_TO, {"goal": ("the", "kitchen")}),
        ("be a dear and fetch me the tape", I.BRING_OBJECT, {"object": ("the", "tape"), "recipient": ("me",)}),
        ("I was wondering if you could get me the map", I.BRING_OBJECT,
         {"object": ("the", "map"), "recipient": ("me",)}),
        ("off you go to the shed", I.MOVE_TO, {"goal": ("the", "shed")}),
        ("go close to the window", I.MOVE_TO, {"goal": ("the", "window")}),
        ("go quickly to the corner", I.MOVE_TO, {"goal": ("the", "corner")}),
        ("please enter the bathroom", I.MOVE_TO, {"goal": ("the", "bathroom")}),
        ("I'm absolutely parched", I.BRING_OBJECT, {"object": ("drink",), "recipient": ("me",)}),
        ("im starving", I.BRING_OBJECT, {"object": ("food",), "recipient": ("me",)}),
        ("take the cup next to the pear", I.GRAB_OBJECT, {"object": ("the", "cup", "beside", "the", "pear")}),
        ("help me get to the bathroom, would you?", I.GUIDE, {"recipient": ("me",), "goal": ("the", "bathroom")}),
        ("put it over there", I.PLACE_OBJECT, {"object": ("it",), "recipient": ("there",)}),
        ("i really need you to bring me the cup", I.BRING_OBJECT, {"object": ("the", "cup"), "recipient": ("me",)}),
    ],
)  # fmt: skip
def test_requests(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.act, p.intent) == ("command", intent)
    assert {k: v for k, v in p.slots.items() if k in slots} == slots


@pytest.mark.parametrize(
    "text", ["do you like music?", "do robots ever get tired", "do you think this colour suits me"]
)
def test_yes_no_questions_are_never_activities(text: str) -> None:
    assert parse(text).intent is None
