"""Issue 30, class 1: a thing the KB names but nobody has seen or put anywhere is known."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.dialogue.conversations.talk import Talk, talking

STUDY = [
    "myself rdf:type Robot",
    'study rdf:type ZoneOfInterest', 'study rdfs:label "study"',
    'person_hugo rdf:type Human', 'person_hugo rdfs:label "Hugo"', "person_hugo isIn study",
    "myself sees person_hugo",
    'desk_drawer rdf:type Container', 'desk_drawer rdfs:label "desk drawer"', "desk_drawer isIn study",
    # Known by its kind and name only: never seen, no place.
    'diary_1 rdf:type Artifact', 'diary_1 rdfs:label "diary"',
    'atlas_1 rdf:type dbr:Book', 'atlas_1 rdfs:label "atlas"',
]  # fmt: skip


@pytest.fixture
def talk() -> Iterator[Talk]:
    with talking(STUDY, "person_hugo") as talk:
        yield talk


def test_where_a_known_thing_is_nobody_knows_yet_then_it_is_told(talk: Talk) -> None:
    first = talk("where is the diary?")
    assert first.reply == "I don't know where the diary is right now." and first.intents == ()
    told = talk("the diary is in the desk drawer")
    assert "diary is in the desk drawer" in told.reply and "know any" not in told.reply
    assert talk.kb.exist(["diary_1 isIn desk_drawer"], models=["person_hugo"])


def test_a_thing_known_only_by_name_can_be_asked_for(talk: Talk) -> None:
    fetched = talk("bring me the atlas")
    assert fetched.intents == (("__intent_bring_object__", {"object": "atlas_1", "recipient": "person_hugo"}),)


def test_what_someone_told_of_where_it_is_is_said_as_their_word() -> None:
    """Issue 30, item 4 of round 2: under the default trust policy the place stays the teller's
    belief; asked where it is, the robot says whose word it has."""
    talk = Talk([*STUDY, 'person_rosa rdf:type Human', 'person_rosa rdfs:label "Rosa"'], "person_rosa")
    try:
        assert talk("the atlas is on the desk drawer").reply.startswith("OK")
        assert not talk.kb.exist(["atlas_1 isOn desk_drawer"])  # the robot did not adopt it
        assert talk("where is the atlas?").reply == "You told me the atlas is on the desk drawer."
        talk.speaker = "person_hugo"
        assert talk("do you know where the atlas is?").reply == "Rosa told me the atlas is on the desk drawer."
        assert talk("where is the diary?").reply == "I don't know where the diary is right now."
    finally:
        talk.close()
