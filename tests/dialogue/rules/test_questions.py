"""Questions about the situation, on whole words."""

import pytest

from dialogue.rules.questions import question
from kb import KB
from tests.dialogue.rules.test_interpret import say


@pytest.mark.parametrize(
    ("text", "thing"),
    [
        ("how many mugs have we got", ("mugs",)),
        ("how many mugs do we have", ("mugs",)),
        ("how many green mugs have you got left", ("green", "mugs")),
        ("how many chairs are there in the hall", ("chairs", "in", "the", "hall")),
        ("how many mugs can you see", ("mugs",)),
        ("how many mugs are there", ("mugs",)),
        ("how many mugs", ("mugs",)),
    ],
)
def test_how_many_counts_the_words_before_the_questions_own_clause(text: str, thing: tuple[str, ...]) -> None:
    asked = question(text.split())
    assert asked is not None and asked.question == "how_many" and asked.slots == {"thing": thing}


def test_how_many_have_we_got_is_answered(office: KB) -> None:
    assert say(office, "how many mugs have we got").reply == (
        "I see two: the green mug and the yellow mug.")  # fmt: skip
