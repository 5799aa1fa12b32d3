"""A role's phrase prepared for the grounding steps: what the words say before anything is named."""

from dialogue.history import Utterance
from dialogue.understanding.requests.phrase import prepared
from dialogue.understanding.requests.referents import Referents
from kb import KB
from tests.dialogue.conftest import lexicon_of

BOB = "person_bob"


def _refs(office: KB) -> Referents:
    return Referents(lexicon_of(office), BOB, (Utterance(BOB, "hello"),))


def test_a_pronoun_said_with_where_it_is_is_the_pronoun(office: KB) -> None:
    assert prepared(_refs(office), ("it", "off", "the", "shelf")) == ("it",)


def test_the_thing_not_meant_is_dropped(office: KB) -> None:
    words = ("the", "box", "of", "gloves", "not", "the", "plasters")
    assert prepared(_refs(office), words) == ("the", "box", "of", "gloves")


def test_words_said_plainly_are_kept(office: KB) -> None:
    assert prepared(_refs(office), ("the", "green", "mug")) == ("the", "green", "mug")
