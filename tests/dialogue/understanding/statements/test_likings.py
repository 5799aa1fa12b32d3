"""The statements' likings: a person likes or dislikes a kind, a thing, a person or the robot."""

from __future__ import annotations

import pytest

from kb import KB
from tests.dialogue.understanding.statements.test_grammar import BOB, facts


@pytest.mark.parametrize(("text", "expected"), [
    ("I like tea", [(BOB, "likes", "tea")]),
    ("I really love tea", [(BOB, "likes", "tea")]),
    ("Alice hates coffee", [("person_alice", "dislikes", "coffee")]),
    ("Alice doesn't like coffee", [("person_alice", "dislikes", "coffee")]),
    ("I do not like the cookbook", [(BOB, "dislikes", "book_1")]),
    ("I can't stand coffee", [(BOB, "dislikes", "coffee")]),
    ("Alice likes Ines", [("person_alice", "likes", "person_ines")]),
    ("I prefer tea", [(BOB, "likes", "tea")]),
    ("I prefer tea to coffee", [(BOB, "likes", "tea")]),
    ("I'm a big fan of yours", [(BOB, "likes", "myself")]),
    ("I'm fond of tea", [(BOB, "likes", "tea")]),
    ("I'm a big fan of coffee", [(BOB, "likes", "coffee")]),
    ("I'm not a fan of coffee", [(BOB, "dislikes", "coffee")]),
    ("tea is my favourite", [(BOB, "likes", "tea")]),
    ("my favorite drink is coffee", [(BOB, "likes", "coffee")]),
])
def test_preferences(home: KB, text: str, expected: list[tuple[str, ...]]) -> None:
    assert facts(home, text) == expected



@pytest.mark.parametrize("text", [
    # likings of what happens, of doing something, of "it": no thing or kind of the KB
    "I like it when you dance", "I love it here", "I like to dance", "I hate when that happens",
    "I like the way you talk", "I don't like it when you do that", "I like it", "I like that",
    "i hate marking lab reports", "this is my favourite",
])
def test_what_is_no_liking_of_a_thing_is_left_to_the_other_rules(home: KB, text: str) -> None:
    assert facts(home, text) is None
