"""A request that may only ask what the robot can do: a verb alone, a performance or a chore."""

import pytest

from dialogue.understanding.requests.abilities import asks_ability
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.said import Said
from tests.dialogue.conftest import english


@pytest.mark.parametrize(
    ("text", "asked"),
    [("can you dance", True), ("can you cook dinner", True), ("can you do the washing up", True),
     ("pip can you do my homework", True), ("pip, can you cook paella", True),
     ("could you make me a nice cup of tea", True), ("can you prepare the salad", True), ("make a cup of tea", False),
     ("can you start the quiz", False), ("cook dinner", False), ("can you hoover the foyer", False)],
)  # fmt: skip
def test_a_question_of_a_verb_alone_a_performance_or_a_chore_asks_an_ability(text: str, asked: bool) -> None:
    lang = english()
    heard = Said(lang, text)
    assert asks_ability(lang, heard, parse(lang, heard, "pip"), "pip") is asked
