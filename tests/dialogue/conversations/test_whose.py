"""Issue 30, class 7: "my X" that the KB says is someone else's, or nobody's, is said so before
the robot acts."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.dialogue.conversations.talk import Talk

OFFICE = [
    "myself rdf:type Robot",
    'office rdf:type ZoneOfInterest', 'office rdfs:label "office"',
    'person_noor rdf:type Human', 'person_noor rdfs:label "Noor"', "person_noor isIn office",
    "myself sees person_noor",
    'person_abel rdf:type Human', 'person_abel rdfs:label "Abel"',
    'stapler_1 rdf:type Artifact', 'stapler_1 rdfs:label "stapler"', "stapler_1 belongsTo person_abel",
    "stapler_1 isIn office", "myself sees stapler_1",
    'scarf_1 rdf:type Artifact', 'scarf_1 rdfs:label "scarf"', "scarf_1 isIn office", "myself sees scarf_1",
    'badge_1 rdf:type Artifact', 'badge_1 rdfs:label "badge"', "badge_1 belongsTo person_noor",
    "badge_1 isIn office", "myself sees badge_1",
]  # fmt: skip


@pytest.fixture
def talk() -> Iterator[Talk]:
    talk = Talk(OFFICE, "person_noor")
    yield talk
    talk.close()


def test_my_thing_that_is_someone_elses_is_said_whose_first(talk: Talk) -> None:
    said = talk("bring me my stapler")
    assert said.reply == "The stapler is Abel's, not yours. OK, I will bring the stapler to you."
    assert said.intents == (("__intent_bring_object__", {"object": "stapler_1", "recipient": "person_noor"}),)


def test_my_thing_that_is_nobodys_is_said_so_and_ones_own_plainly(talk: Talk) -> None:
    assert talk("pick up my scarf").reply == "As far as I know, the scarf belongs to nobody. OK, I will pick up the scarf."
    assert talk("pick up my badge").reply == "OK, I will pick up the badge."
