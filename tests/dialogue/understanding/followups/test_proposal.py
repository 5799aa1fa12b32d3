"""A reading the rules lack evidence for is proposed, never acted on; "yes" acts on it, "no" drops it."""

import pytest

from dialogue import intents as I
from dialogue.understanding.outcome import Outcome
from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.dialogue.understanding.test_interpret import say

JO = "person_jo"


@pytest.fixture
def studio() -> KB:
    return scene_kb(
        None,
        "myself rdf:type Robot",
        "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"',
        f"{JO} rdf:type Human", f'{JO} rdfs:label "Jo"', f"myself sees {JO}",
        "person_tam rdf:type Human", 'person_tam rdfs:label "Tam"', "myself sees person_tam",
        "drum_1 rdf:type Artifact", 'drum_1 rdfs:label "drum"', "myself sees drum_1",
    )  # fmt: skip


def _asked(studio: KB, text: str) -> Outcome:
    out = say(studio, text, speaker=JO)
    assert out.intent is None and out.clarify and out.proposal is not None
    return out


def test_a_question_of_what_the_robot_can_do_is_proposed_not_acted_on(studio: KB) -> None:
    out = _asked(studio, "can you dance?")
    assert out.reply == "Shall I dance?"
    assert out.proposal is not None and out.proposal.intent == I.PERFORM_MOTION
    # the same verb asked for is done at once
    assert say(studio, "dance", speaker=JO).intent == I.PERFORM_MOTION


@pytest.mark.parametrize("text", ["can you do some exercises with us", "can you make the bed"])
def test_a_performance_asked_of_the_robots_skills_is_proposed_not_acted_on(studio: KB, text: str) -> None:
    assert _asked(studio, text).reply.startswith("Shall I")
    # asked for, or an activity asked whether the robot can start it, it is started
    assert say(studio, text.removeprefix("can you "), speaker=JO).intent == I.START_ACTIVITY
    assert say(studio, "can you start the quiz", speaker=JO).intent == I.START_ACTIVITY
    # said after the robot's name, still a question
    assert _asked(studio, f"ari {text}").reply.startswith("Shall I")


@pytest.mark.parametrize(
    "text", ["can you cook dinner?", "can you do the washing up", "can you do my homework lol",
             "can you play the drum for us", "can you do a cartwheel"],
)  # fmt: skip
def test_a_chore_beyond_the_robots_skills_is_said_to_be_neither_proposed_nor_started(studio: KB, text: str) -> None:
    for said in (text, text.removeprefix("can you "), f"ari {text}"):
        out = say(studio, said, speaker=JO)
        assert out.intent is None and not out.clarify and out.reply.startswith("I can't")


def test_a_person_named_where_the_reading_has_no_role_for_them_is_proposed(studio: KB) -> None:
    out = _asked(studio, "salute Tam in the hall")
    assert out.reply == "Shall I salute?"
    assert say(studio, "salute", speaker=JO).intent == I.PERFORM_MOTION
    # whom it is for is accounted for
    assert say(studio, "start the drum practice for Tam", speaker=JO).intent == I.START_ACTIVITY


@pytest.mark.parametrize("answer", ["yes", "yes please", "sure, go ahead", "please do"])
def test_yes_acts_on_the_reading_proposed(studio: KB, answer: str) -> None:
    history = [("user", "can you dance?"), ("robot", "Shall I dance?")]
    out = say(studio, answer, speaker=JO, history=history)
    assert (out.intent, out.roles) == (I.PERFORM_MOTION, {"object": "dance"})
    assert out.confidence < 0.9  # confirmed, not said whole


@pytest.mark.parametrize("answer", ["no", "nope", "no thanks"])
def test_no_drops_it(studio: KB, answer: str) -> None:
    out = say(studio, answer, speaker=JO, history=[("user", "can you dance?"), ("robot", "Shall I dance?")])
    assert out.intent is None and out.understood and not out.clarify


def test_anything_else_is_a_new_turn(studio: KB) -> None:
    history = [("user", "can you dance?"), ("robot", "Shall I dance?")]
    out = say(studio, "go to the hall", speaker=JO, history=history)
    assert (out.intent, out.roles) == (I.MOVE_TO, {"goal": "hall"})


def test_yes_acts_on_what_the_request_before_the_question_proposed(studio: KB) -> None:
    history = [("user", "salute Tam in the hall"), ("robot", "Shall I salute?")]
    out = say(studio, "yeah", speaker=JO, history=history)
    assert (out.intent, out.roles) == (I.PERFORM_MOTION, {"object": "salute"})
