"""Issue 30, round 2, item 3: "my X" when none of them is the speaker's says so before asking which;
"is Bo in the kitchen?" of someone seen whom the KB puts nowhere answers what is known."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from dialogue import intents as I
from tests.dialogue.conversations.talk import Talk, talking

BAKERY = [
    "myself rdf:type Robot",
    'bakehouse rdf:type ZoneOfInterest', 'bakehouse rdfs:label "bakehouse"',
    'shopfront rdf:type ZoneOfInterest', 'shopfront rdfs:label "shopfront"',
    'person_leni rdf:type Human', 'person_leni rdfs:label "Leni"', "person_leni isIn bakehouse",
    "myself sees person_leni",
    'person_joss rdf:type Human', 'person_joss rdfs:label "Joss"', "myself sees person_joss",  # seen, nowhere
    'person_uma rdf:type Human', 'person_uma rdfs:label "Uma"',
    'apron_1 rdf:type Artifact', 'apron_1 rdfs:label "apron"', "apron_1 hasColor white", "apron_1 isIn bakehouse",
    "apron_1 belongsTo person_uma", "myself sees apron_1",
    'apron_2 rdf:type Artifact', 'apron_2 rdfs:label "apron"', "apron_2 hasColor blue", "apron_2 isIn shopfront",
    'tray_1 rdf:type Artifact', 'tray_1 rdfs:label "tray"', "tray_1 isIn bakehouse", "tray_1 belongsTo person_leni",
    "myself sees tray_1",
    'tray_2 rdf:type Artifact', 'tray_2 rdfs:label "tray"', "tray_2 isIn shopfront",
]  # fmt: skip


@pytest.fixture
def talk() -> Iterator[Talk]:
    with talking(BAKERY, "person_leni") as talk:
        yield talk


def test_my_x_when_neither_is_mine_says_so_before_asking_which(talk: Talk) -> None:
    said = talk("give me my apron")
    assert said.reply == ("As far as I know, neither apron is yours. "
                          "Which apron do you mean: the white one or the blue one?")
    assert said.intents == ()
    assert talk("the blue one").intents == ((I.BRING_OBJECT, {"object": "apron_2", "recipient": "person_leni"}),)
    # one of them is mine: that one, nothing said of the others
    assert talk("bring me my tray").intents == ((I.BRING_OBJECT, {"object": "tray_1", "recipient": "person_leni"}),)
    # "the apron" claims no one's: only which is asked
    assert talk("bring me the apron").reply == "Which apron do you mean: the white one or the blue one?"


def test_someone_seen_whom_the_kb_puts_nowhere_is_answered_with_what_is_known(talk: Talk) -> None:
    assert talk("is Joss in the shopfront?").reply == (
        "I can see Joss, but I don't know whether they are in the shopfront.")
    assert talk("is Uma in the shopfront?").reply == "I don't know where Uma is right now."
