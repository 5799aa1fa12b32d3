"""Questions of comings and goings ("has Frances arrived?", "did Tom leave?"), answered from what the
KB knows of the person: seen, placed, or neither."""

import pytest

from dialogue.understanding.questions.presence import ARRIVED, DEPARTED, presence
from kb import KB
from tests.dialogue.conftest import english, scene_kb
from tests.dialogue.understanding.test_interpret import say

ANA = "person_ana"


@pytest.fixture
def hall() -> KB:
    return scene_kb(
        None,
        "myself rdf:type Robot",
        "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"',
        "den rdf:type ZoneOfInterest", 'den rdfs:label "den"',
        f"{ANA} rdf:type Human", f'{ANA} rdfs:label "Ana"', f"myself sees {ANA}",
        "person_frances rdf:type Human", 'person_frances rdfs:label "Frances"', "myself sees person_frances",
        "person_frances isIn hall",
        "person_bo rdf:type Human", 'person_bo rdfs:label "Bo"', "person_bo isIn den",
        "person_tom rdf:type Human", 'person_tom rdfs:label "Tom"',
        "parcel_1 rdf:type Artifact", 'parcel_1 rdfs:label "parcel"',
    )  # fmt: skip


@pytest.mark.parametrize(
    ("text", "who", "way"),
    [("has frances arrived", ("frances",), ARRIVED), ("is marta back yet", ("marta",), ARRIVED),
     ("did tom leave", ("tom",), DEPARTED), ("has tom already left", ("tom",), DEPARTED),
     ("has ade gone home", ("ade",), DEPARTED), ("has she turned up yet", ("she",), ARRIVED),
     ("is tom home", ("tom",), ARRIVED)],
)  # fmt: skip
def test_the_question_says_who_and_which_way(text: str, who: tuple[str, ...], way: str) -> None:
    asked = presence(english(), tuple(text.split()))
    assert asked is not None and (asked.question, asked.slots) == (way, {"thing": who})


@pytest.mark.parametrize("text", ["has arrived", "did you leave it", "is the cup on the table", "has left"])
def test_other_words_are_no_such_question(text: str) -> None:
    assert presence(english(), tuple(text.split())) is None


def test_someone_seen_has_come_and_not_gone(hall: KB) -> None:
    assert say(hall, "Has Frances arrived?", speaker=ANA).reply == "Yes, Frances is here: I can see them in the hall."
    assert say(hall, "did Frances leave?", speaker=ANA).reply == "No, Frances is still here: I can see them in the hall."


def test_someone_placed_but_not_seen_is_said_so(hall: KB) -> None:
    out = say(hall, "is Bo back yet?", speaker=ANA)
    assert out.intent is None and out.reply == "I can't see Bo right now; the last I know, they were in the den."


def test_someone_neither_seen_nor_placed_is_not_known(hall: KB) -> None:
    out = say(hall, "has Tom left?", speaker=ANA)
    assert out.understood and out.reply == "I don't know: I can't see Tom, and I don't know where they are."


def test_a_pronoun_is_the_person_just_spoken_of(hall: KB) -> None:
    history = [("user", "is Bo in the den?"), ("robot", "Yes, as far as I know Bo is in the den.")]
    assert "Bo" in say(hall, "has she gone home?", speaker=ANA, history=history).reply


@pytest.mark.parametrize("text", ["has the parcel arrived?", "has Zed arrived?"])
def test_what_is_no_person_known_is_not_answered(hall: KB, text: str) -> None:
    assert not say(hall, text, speaker=ANA).understood


def test_still_here_is_asked_as_here(hall: KB) -> None:
    assert say(hall, "is Frances still here?", speaker=ANA).reply == "Yes, I see Frances in the hall."
