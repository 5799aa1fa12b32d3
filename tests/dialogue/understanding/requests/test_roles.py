"""One request read against the KB: the intent its roles say, the roles implied, each grounded,
and what is asked when one is missing."""

from dialogue import intents as I
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.roles import one_command
from kb import KB
from tests.dialogue.conftest import english, lexicon_of

BOB = "person_bob"


def _read(kb: KB, text: str, **overrides: tuple[str, ...]) -> Outcome:
    return one_command(Interpreter(lexicon_of(kb), BOB), parse(english(), text), overrides)


def test_a_person_taken_somewhere_is_guided_there(office: KB) -> None:
    out = _read(office, "take Carol to the bathroom")
    assert (out.intent, out.roles) == (I.GUIDE, {"recipient": "person_carol", "goal": "bathroom"})


def test_each_role_is_grounded_to_one_entity(office: KB) -> None:
    out = _read(office, "leave the pear on the shelf")
    assert (out.intent, out.clarify) == (I.PLACE_OBJECT, False)
    assert out.roles == {"object": "pear_1", "recipient": "shelf_9"}


def test_a_role_given_in_place_of_the_words_is_grounded_instead(office: KB) -> None:
    out = _read(office, "grab the gray laptop", object=("stapler",))
    assert out.roles == {"object": "stapler_1"}


def test_a_required_role_not_said_is_asked_for(office: KB) -> None:
    out = _read(office, "put the pear")
    assert (out.intent, out.clarify, out.open_role) == (None, True, "recipient")
