"""Speech asked for: a question put to someone ("ask Ollie if he wants a sausage") as "you"."""

import pytest

from dialogue import intents as I
from dialogue.understanding.requests.commands import parse
from tests.dialogue.conftest import english


@pytest.mark.parametrize(
    ("text", "question"),
    [("Ask Hamish whether he would like a booster cushion.", "would you like a booster cushion?"),
     ("ask Ollie if he wants a sausage", "do you want a sausage?"),
     ("ask Ana if she is ready", "are you ready?")],
)  # fmt: skip
def test_a_question_put_to_someone_is_said_to_them_as_you(text: str, question: str) -> None:
    p = parse(english(), text)
    assert (p.intent, p.text) == (I.SAY, question)
    assert p.slots["recipient"] in {("hamish",), ("ollie",), ("ana",)}


@pytest.mark.parametrize("text", ["ask Ana if the taxi is here", "ask Tom if he wants his coat", "ask Ana about it"])
def test_a_question_that_cannot_be_put_as_you_is_not_claimed(text: str) -> None:
    assert parse(english(), text).intent is None


@pytest.mark.parametrize(
    ("text", "message"),
    [("tell everyone lunch is ready", "lunch is ready"),
     ("would you mind telling everybody that lunch is ready", "lunch is ready"),
     ("let everyone know dinner is at seven", "dinner is at seven")],
)  # fmt: skip
def test_a_message_to_everyone_is_said_aloud_to_no_one_person(text: str, message: str) -> None:
    p = parse(english(), text)
    assert (p.intent, p.text) == (I.SAY, message)
    assert not p.slots.get("recipient")


def test_a_message_to_one_person_keeps_them(text: str = "could you let Tom know I'm outside") -> None:
    p = parse(english(), text)
    assert p.intent == I.SAY and p.slots["recipient"] == ("tom",)
