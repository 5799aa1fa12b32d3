"""A role's phrase prepared for the grounding steps: what the words say before anything is named."""

from dialogue.history import Utterance
from dialogue.understanding.requests.phrase import prepared
from dialogue.understanding.requests.referents import Referents
from kb import KB
from tests.dialogue.conftest import lexicon_of
from tests.dialogue.understanding.test_interpret import say

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


def test_something_to_drink_with_several_drinks_in_sight_asks_which(office: KB) -> None:
    office.update(['cola_1 rdf:type cyc:Can', 'cola_1 rdfs:label "can of cola"', "myself sees cola_1",
                   'shake_1 rdf:type dbr:Cup', 'shake_1 rdfs:label "strawberry milkshake"', "myself sees shake_1"])
    for text in ("I'd love something to drink.", "bring me a drink"):
        out = say(office, text)
        assert out.intent is None and out.clarify
        assert "the can of cola" in out.reply and "the strawberry milkshake" in out.reply
