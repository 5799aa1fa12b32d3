"""Whether a request is for now: negated, or under a condition yet to happen, not a polite one."""

import pytest

from dialogue.understanding.requests.timing import conditional, later, negation, when
from dialogue.understanding.requests.vocabulary import Grammar
from tests.dialogue.conftest import english


def test_a_negated_request_is_not_for_now() -> None:
    g = english().derived(Grammar)
    assert negation(g, ["don't", "go", "to", "the", "kitchen"]) and negation(g, ["do", "not", "move"])
    assert not negation(g, ["go", "to", "the", "kitchen"])


@pytest.mark.parametrize(
    ("text", "held"),
    [("if i nod off could you close the door", True), ("if you could close the door", False),
     ("if i could have the bill", False)],
)  # fmt: skip
def test_a_condition_is_held_a_polite_if_is_not(text: str, held: bool) -> None:
    assert conditional(english().derived(Grammar), text.split()) is held


@pytest.mark.parametrize(
    ("text", "held"),
    [("when the bell goes could you open the door", True), ("when you get a chance open the door", False),
     ("after lunch take me to the day room", True)],
)  # fmt: skip
def test_a_request_after_a_condition_yet_to_happen_is_held(text: str, held: bool) -> None:
    assert later(english(), text.split()) is held


def test_a_clause_of_time_after_the_request_holds_it() -> None:
    g = english().derived(Grammar)
    assert when(g, (("when", "she", "comes", "in"),))
    assert not when(g, (("carefully",),))


def test_the_speakers_absence_yet_to_come_holds_the_request() -> None:
    g = english().derived(Grammar)
    assert when(g, (("while", "i", "am", "out"),)) and when(g, (("whilst", "we", "are", "both", "away"),))
    # while someone waits, or the robot is out, is now
    assert not when(g, (("while", "i", "wait"),)) and not when(g, (("while", "you", "are", "out"),))


def test_a_thing_had_when_it_is_ready_is_not_asked_for_now() -> None:
    from tests.dialogue.conftest import scene_kb
    from tests.dialogue.understanding.test_interpret import say

    kb = scene_kb("office")
    assert say(kb, "I'll have my stapler when it's ready").intent is None
    assert say(kb, "I'll have a look").intent is None
    # not the speaker's own thing: what they will do, or a choice among things offered, not this
    assert say(kb, "I'll have the stapler").intent is None
    kb.close()
