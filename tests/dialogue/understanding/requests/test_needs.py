"""Needs said before any verb: a need said with a question of what there is."""

import pytest

from dialogue import intents as I
from dialogue.understanding.requests.commands import parse
from tests.dialogue.conftest import english


@pytest.mark.parametrize(
    ("text", "thing"),
    [("I'm parched. Any tea going?", ("tea",)), ("im thirsty is there any juice", ("juice",)),
     ("I'm really thirsty, have you got any lemonade left", ("lemonade",)),
     # said with a sigh first, and "ever so" as much as "so"
     ("Oh dear, I'm ever so thirsty, is there any juice about?", ("juice",)),
     # anything at all: whatever meets the need
     ("im starving is there anything to eat", ("food",)),
     # what is said of it says which: "sugar free" of whatever meets the need
     ("I'm thirsty, anything sugar free to drink?", ("sugar", "free", "drink")),
     ("I'm thirsty, is there anything cold?", ("cold", "drink")),
     ("I'm parched, got anything low-sugar to drink?", ("low", "sugar", "drink")),
     # said by a symptom of it
     ("my throat's dry, any juice going?", ("juice",)),
     ("My mouth's gone awfully dry, is there any water about?", ("water",))],
)  # fmt: skip
def test_a_need_with_a_question_of_what_there_is_asks_for_that_thing(text: str, thing: tuple[str, ...]) -> None:
    p = parse(english(), text)
    assert (p.intent, p.slots) == (I.BRING_OBJECT, {"object": thing, "recipient": ("me",)})


@pytest.mark.parametrize(
    "text", ["I'm thirsty, is there any chance of that", "I'm thirsty, any of the red ones", "is there any tea"]
)
def test_a_question_of_what_there_is_without_a_need_or_a_thing_asks_for_none(text: str) -> None:
    assert parse(english(), text).intent is None


@pytest.mark.parametrize(
    ("text", "thing"),
    [("Ruby's thirsty, is there any lemonade for her?", ("lemonade",)),
     ("ruby is starving is there anything to eat", ("food",))],
)  # fmt: skip
def test_a_need_of_someone_named_with_a_question_of_what_there_is_is_for_them(text: str, thing: tuple[str, ...]) -> None:
    p = parse(english(), text)
    assert (p.intent, p.slots) == (I.BRING_OBJECT, {"object": thing, "recipient": ("ruby",)})
    # said alone, it is a remark
    assert parse(english(), "ruby is thirsty").intent is None


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [("The kickboard needs putting back on the kit shelf.", I.PLACE_OBJECT,
      {"object": ("the", "kickboard"), "recipient": ("the", "kit", "shelf")}),
     ("the small parcel needs taking to Lars", I.BRING_OBJECT,
      {"object": ("the", "small", "parcel"), "recipient": ("lars",)}),
     ("the road atlas wants putting on the table", I.PLACE_OBJECT,
      {"object": ("the", "road", "atlas"), "recipient": ("the", "table")})],
)  # fmt: skip
def test_a_thing_said_to_need_a_chore_asks_for_the_chore(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(english(), text)
    assert (p.intent, p.slots) == (intent, slots)


def test_a_need_of_someone_or_of_no_chore_read_is_no_chore() -> None:
    assert parse(english(), "the man with the hat needs taking to the exit").intent is None
    assert parse(english(), "the kettle needs descaling").intent is None


@pytest.mark.parametrize(
    ("text", "thing", "whom"),
    [("Freya's after her goggles, can you sort that out?", ("her", "goggles"), ("freya",)),
     ("Lucia's after a drink, the cola I reckon.", ("the", "cola"), ("lucia",))],
)  # fmt: skip
def test_someone_after_a_thing_is_brought_it(text: str, thing: tuple[str, ...], whom: tuple[str, ...]) -> None:
    p = parse(english(), text)
    assert (p.intent, p.slots) == (I.BRING_OBJECT, {"object": thing, "recipient": whom})
    assert parse(english(), "it's after six").intent is None  # no one's, a time


@pytest.mark.parametrize(("text", "thing"), [("is there anything to eat", ("food",)), ("is there anything to drink?", ("drink",))])
def test_a_question_of_anything_for_a_need_asks_for_what_meets_it(text: str, thing: tuple[str, ...]) -> None:
    p = parse(english(), text)
    assert (p.intent, p.slots) == (I.BRING_OBJECT, {"object": thing, "recipient": ("me",)})
    # where it is asked, or whether the robot sees it, it is a question
    assert parse(english(), f"{text.rstrip('?')} on the desk").act == "question"
    assert parse(english(), "do you see anything to eat").act == "question"
