"""Issue 30, class 3: the number of a reply's verb from what the thing is, people never "it"."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from dialogue.understanding.inflection import plural_name, plural_noun, plural_of
from tests.dialogue.conftest import english
from tests.dialogue.conversations.talk import Talk, talking

FLAT = [
    "myself rdf:type Robot",
    'lounge rdf:type ZoneOfInterest', 'lounge rdfs:label "lounge"',
    'hallway rdf:type ZoneOfInterest', 'hallway rdfs:label "hallway"',
    'person_ines rdf:type Human', 'person_ines rdfs:label "Ines"', "person_ines isIn hallway",
    'person_tomas rdf:type Human', 'person_tomas rdfs:label "Tomas"', "person_tomas isIn lounge",
    "myself sees person_tomas",
    "shelf_1 rdf:type dbr:Shelf_(storage)", 'shelf_1 rdfs:label "shelf"', "shelf_1 isIn lounge",
    "myself sees shelf_1",
    'keys_1 rdf:type Artifact', 'keys_1 rdfs:label "keys"', "keys_1 isIn hallway",
    'glasses_1 rdf:type Artifact', 'glasses_1 rdfs:label "reading glasses"', "glasses_1 isOn shelf_1",
    "myself sees glasses_1",
    "bottle_1 rdf:type dbr:Bottle", "bottle_1 isOn shelf_1", "myself sees bottle_1",
    'remote_1 rdf:type Artifact', 'remote_1 rdfs:label "remote"', "remote_1 isOn shelf_1", "myself sees remote_1",
    'bus_1 rdf:type Artifact', 'bus_1 rdfs:label "toy bus"', "bus_1 isIn hallway",
]  # fmt: skip


@pytest.fixture
def talk() -> Iterator[Talk]:
    with talking(FLAT, "person_tomas") as talk:
        yield talk


def test_a_persons_name_ending_in_s_is_one_person_never_it(talk: Talk) -> None:
    assert talk("where is Ines?").reply == "Ines is in the hallway. I don't see them right now."


def test_things_are_as_many_as_their_names_say(talk: Talk) -> None:
    assert talk("where are the keys?").reply == "The keys are in the hallway. I don't see them right now."
    assert talk("where are my reading glasses?").reply == "The reading glasses are on the shelf."
    assert talk("where is the toy bus?").reply == "The toy bus is in the hallway. I don't see it right now."
    on = talk("what is on the shelf?").reply
    assert on == "On the shelf, there are a bottle, the reading glasses and the remote."
    told = talk("the keys are on the shelf").reply
    assert "the keys are on the shelf" in told


def test_number_by_the_english_lexicon() -> None:
    assert plural_noun("keys") and plural_noun("glasses")
    assert not any(plural_noun(w) for w in ("bus", "lens", "ines", "marcus", "mug"))
    assert plural_name("reading glasses", english()) and not plural_name("toy bus", english())
    assert (plural_of("mug"), plural_of("box"), plural_of("reading glasses")) == ("mugs", "boxes", "reading glasses")


SEWING = [
    "myself rdf:type Robot",
    'sewing_room rdf:type ZoneOfInterest', 'sewing_room rdfs:label "sewing room"',
    'person_ada rdf:type Human', 'person_ada rdfs:label "Ada"', "person_ada isIn sewing_room",
    "myself sees person_ada",
    'scissors_1 rdf:type Artifact', 'scissors_1 rdfs:label "scissors"', "scissors_1 isIn sewing_room",
    "myself sees scissors_1",
    'trousers_1 rdf:type Artifact', 'trousers_1 rdfs:label "trousers"', "trousers_1 isIn sewing_room",
    'goggles_1 rdf:type Artifact', 'goggles_1 rdfs:label "pair of goggles"', "goggles_1 isIn sewing_room",
    "myself sees goggles_1",
]  # fmt: skip


def test_nouns_always_plural_are_and_a_pair_of_them_is() -> None:
    talk = Talk(SEWING, "person_ada")
    try:
        assert talk("where are the scissors?").reply == "The scissors are in the sewing room."
        assert talk("where are the trousers?").reply.startswith("The trousers are in the sewing room.")
        assert talk("where is the pair of goggles?").reply == "The pair of goggles is in the sewing room."
        assert talk("the trousers are mine").reply == "OK, the trousers are yours."
        assert talk("the pair of goggles is mine").reply == "OK, the pair of goggles is yours."
    finally:
        talk.close()
