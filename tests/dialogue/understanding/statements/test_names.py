"""What words can be a person's name, and the name as it is kept."""

from __future__ import annotations

from dialogue.understanding.said import Said
from dialogue.understanding.statements import names
from tests.dialogue.conftest import english


def clean_name(told: str) -> str:
    return names.clean_name(Said(english(), told))


def name_like(words: tuple[str, ...], original: str) -> bool:
    return names.name_like(english(), words, Said(english(), original))


def given_name(words: tuple[str, ...]) -> bool:
    return names.given_name(english(), words)


def test_names_as_told() -> None:
    assert clean_name(" mary jane ") == "Mary Jane" and clean_name("McKenzie") == "McKenzie"
    assert clean_name("42") == "" and clean_name("x" * 61) == ""


def test_quotes_around_a_name_are_not_part_of_it() -> None:
    assert clean_name('"Bob" Smith') == "Bob Smith" and clean_name("'Bobby'") == "Bobby"
    assert clean_name("“Ana”") == "Ana" and clean_name("O'Brien") == "O'Brien"


def test_name_likeness_reads_casing_when_the_text_has_any() -> None:
    assert name_like(("frank",), "Frank") and not name_like(("frank",), "frank")
    assert name_like(("maria",), "maria") and not name_like(("very", "tired"), "very tired")


def test_lower_case_participles_numbers_and_adverbs_are_no_names() -> None:
    for word in ("lost", "bored", "scared", "thirty", "later", "maybe", "back"):
        assert not name_like((word,), word), word
    for word in ("bob", "sam", "maria", "rose", "mark"):  # "rose" is a past tense, no participle
        assert name_like((word,), word), word


def test_my_name_is_takes_any_words_but_a_negation_or_a_phrase() -> None:
    assert given_name(("frank",)) and given_name(("mary", "jane"))
    assert not given_name(("not", "important")) and not given_name(("a", "secret"))


def test_a_need_is_no_name() -> None:
    # "I'm peckish" asks for food, whatever a lemmatiser knows of the word; "I'm Pip" is a name
    assert not name_like(("peckish",), "im peckish") and name_like(("pip",), "im pip")
