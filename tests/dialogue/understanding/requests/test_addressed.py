"""Whom a request is said to: someone present, by their name set apart or by their things."""

import pytest

from dialogue import intents as I
from dialogue.understanding.requests.addressed import to_someone_else
from dialogue.understanding.said import Said
from kb import KB
from tests.dialogue.conftest import english, lexicon_of
from tests.dialogue.understanding.test_interpret import BOB, say


@pytest.mark.parametrize(
    ("text", "whom"),
    [("Carol, can you pass me the green mug?", "Carol"), ("carol put your mug on the desk", "Carol"),
     # called from elsewhere: Dan is not in sight
     ("Dan, can you pass me the green mug?", "Dan"),
     # the robot's own name, the speaker's, more than a name before the comma, or no request after it
     ("Ari, can you pass me the green mug?", None), ("Bob, can you pass me the green mug?", None),
     ("Carol's green mug, can you pass me that?", None), ("Carol, the mug is green", None),
     # without the comma or "your", the name may be the robot's
     ("carol put the green mug on the desk", None)],
)  # fmt: skip
def test_a_request_is_said_to_someone_present(office: KB, text: str, whom: str | None) -> None:
    assert to_someone_else(lexicon_of(office), Said.read(english(), text), BOB, "Ari") == whom


def test_a_request_said_to_someone_else_is_not_the_robots(office: KB) -> None:
    out = say(office, "Carol, can you pass me the green mug?")
    assert (out.intent, out.understood) == (None, True) and "Carol" in out.reply
    assert say(office, "Ari, can you pass me the green mug?").intent == I.BRING_OBJECT
