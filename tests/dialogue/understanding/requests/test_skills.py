"""Which activities are the robot's: its chores, its games and shows, anything asked to start; the
rest it says it cannot do and starts nothing."""

import pytest

from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.skills import no_intent, skilled, unskilled
from tests.dialogue.conftest import english


@pytest.mark.parametrize(
    "text",
    ["tidy up the kids room", "can you hoover the foyer", "play hide and seek with me", "let's do some chair exercises",
     "kick off story time for the little ones", "start counting my reps", "start watering the plants",
     "Please make the bed", "follow me", "vacuuming the floor please", "cleaning the office please",
     "exercise with me"],
)  # fmt: skip
def test_the_robots_activities_are_started(text: str) -> None:
    assert skilled(english(), parse(english(), text))


@pytest.mark.parametrize(
    ("text", "said"),
    [("Fold all the towels for me.", "I can't fold all the towels for you myself."),
     ("Water the tomatoes in the raised beds.", "I can't water the tomatoes in the raised beds myself."),
     ("Play us something on the piano, would you?", "I can't play you something on the piano myself."),
     ("can you do my exercises for me", "I can't do your exercises for you myself."),
     ("do our exercises for us", "I can't do your exercises for you myself.")],
)  # fmt: skip
def test_an_activity_the_robot_has_no_skill_for_is_said_to_be_beyond_it(text: str, said: str) -> None:
    outcome = unskilled(english(), parse(english(), text))
    assert outcome is not None and outcome.intent is None and outcome.reply == said


@pytest.mark.parametrize(
    ("text", "said"),
    [("hang the calendar on the wall", "I can't hang the calendar on the wall myself."),
     ("stick the poster to the ceiling", "I can't stick the poster to the ceiling myself.")],
)  # fmt: skip
def test_a_thing_fixed_to_a_wall_is_no_placing(text: str, said: str) -> None:
    p = parse(english(), text)
    outcome = unskilled(english(), p)
    assert not skilled(english(), p) and outcome is not None and outcome.reply == said and not outcome.understood


def test_a_thing_hung_on_furniture_is_placed() -> None:
    assert skilled(english(), parse(english(), "hang the coat on the coat rack"))


@pytest.mark.parametrize(
    "text",
    ["put the cushion on the shelf by the wall", "put the fruit bowl on the dining table next to the wall",
     "put the watering can by the wall", "put the vase against the wall"],
)  # fmt: skip
def test_a_thing_put_by_a_wall_or_on_furniture_near_one_is_placed(text: str) -> None:
    assert skilled(english(), parse(english(), text))


@pytest.mark.parametrize(
    "text", ["hang the picture on the wall by the door", "put the clock onto the wall", "hang the calendar by the wall"]
)
def test_a_thing_attached_to_a_wall_by_the_preposition_or_the_verb_is_no_placing(text: str) -> None:
    assert not skilled(english(), parse(english(), text))


@pytest.mark.parametrize(
    ("text", "said"),
    [("plug the lamp in", "I can't plug the lamp in myself."), ("pin the calendar up", "I can't pin the calendar up myself."),
     ("turn off the lamp", "I can't turn off the lamp myself.")],
)  # fmt: skip
def test_an_action_with_no_intent_said_alone_is_said_to_be_beyond_the_robot(text: str, said: str) -> None:
    outcome = no_intent(english(), parse(english(), text))
    assert outcome is not None and outcome.reply == said and outcome.intent is None and not outcome.understood


@pytest.mark.parametrize("text", ["bring me the lamp", "I plug the lamp in every night", "lamp"])
def test_other_words_are_no_action_without_an_intent(text: str) -> None:
    assert no_intent(english(), parse(english(), text)) is None
