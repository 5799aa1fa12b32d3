"""Closed-class English: numbers written the other way."""

import pytest

from dialogue.reference.english import other_numbers


@pytest.mark.parametrize(
    ("words", "other"),
    [
        ("bay 4", ("bay", "four")),
        ("bay four", ("bay", "4")),
        ("gate 21", ("gate", "twenty", "one")),
        ("gate twenty one", ("gate", "21")),
        ("room 40 b", ("room", "forty", "b")),
        ("row zero", ("row", "0")),
    ],
)
def test_a_number_in_digits_is_said_in_words_and_back(words: str, other: tuple[str, ...]) -> None:
    assert other_numbers(words.split()) == other


def test_words_without_a_number_have_no_other_form() -> None:
    assert other_numbers(["the", "red", "mug"]) is None
    assert other_numbers(["room", "101"]) is None  # only numbers below a hundred are said
