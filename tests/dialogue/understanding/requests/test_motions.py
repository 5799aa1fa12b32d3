"""An activity named by one of the robot's motions is that motion ("do a dance for me")."""

import pytest

from dialogue import intents as I
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.motions import as_motion, motions
from tests.dialogue.conftest import english


def test_the_motions_are_the_verbs_of_the_motion_frames() -> None:
    assert {"dance", "wave", "bow", "spin"} <= motions(english())
    assert "shake" not in motions(english())  # (its frame names its text: "shake_hands")


@pytest.mark.parametrize(
    ("text", "motion"),
    [("do a dance for me", "dance"), ("do a little dance", "dance"), ("do a quick spin", "spin"),
     ("perform a bow", "bow")],
)  # fmt: skip
def test_an_activity_named_by_a_motion_is_the_motion(text: str, motion: str) -> None:
    p = parse(english(), text)
    assert (p.intent, p.text, "activity" in p.slots) == (I.PERFORM_MOTION, motion, False)


@pytest.mark.parametrize("text", ["do the washing", "do a cartwheel", "do a dance class booking"])
def test_other_activities_stay_activities(text: str) -> None:
    assert parse(english(), text).intent == I.START_ACTIVITY


def test_a_parse_of_no_activity_is_left_as_it_was() -> None:
    p = parse(english(), "bring me the dance shoes")
    assert as_motion(english(), p) is p
