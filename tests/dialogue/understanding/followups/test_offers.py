"""Answers to the robot's offer: a yes, or a choice among the things it offered."""

import pytest

from dialogue import intents as I
from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.dialogue.understanding.test_interpret import say

NELL = "person_nell"


@pytest.fixture
def kitchen() -> KB:
    return scene_kb(
        None, "myself rdf:type Robot",
        f"{NELL} rdf:type Human", f'{NELL} rdfs:label "Nell"', f"myself sees {NELL}",
        "tea_1 rdf:type dbr:Cup", 'tea_1 rdfs:label "tea"', "myself sees tea_1",
        "juice_1 rdf:type Bottle", 'juice_1 rdfs:label "orange juice"', "myself sees juice_1",
        "scarf_1 rdf:type Artifact", 'scarf_1 rdfs:label "scarf"', "myself sees scarf_1",
    )  # fmt: skip


@pytest.mark.parametrize(
    ("offer", "answer", "thing"),
    [("Would you like tea or orange juice?", "I'll have the tea", "tea_1"),
     ("Would you like tea or orange juice?", "the orange juice please", "juice_1"),
     ("Shall I bring you the tea or the orange juice?", "I'll take the orange juice, ta", "juice_1"),
     ("Can I get you some tea or juice?", "I would like the juice", "juice_1")],
)  # fmt: skip
def test_a_choice_among_the_things_offered_is_the_offer_of_that_thing(
    kitchen: KB, offer: str, answer: str, thing: str
) -> None:
    out = say(kitchen, answer, speaker=NELL, history=[("robot", offer)])
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": thing, "recipient": NELL})


def test_a_choice_of_something_not_offered_answers_nothing(kitchen: KB) -> None:
    out = say(kitchen, "I'll have the scarf", speaker=NELL, history=[("robot", "Would you like tea or orange juice?")])
    assert out.intent is None


@pytest.mark.parametrize("answer", ["I'll take the orange juice, ta", "I'll have the tea"])
def test_with_no_offer_a_choice_is_what_the_speaker_does(kitchen: KB, answer: str) -> None:
    assert say(kitchen, answer, speaker=NELL).intent is None


def test_yes_to_an_offer_is_still_the_request_offered(kitchen: KB) -> None:
    out = say(kitchen, "yes please", speaker=NELL, history=[("robot", "Would you like me to bring you the tea?")])
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "tea_1", "recipient": NELL})
