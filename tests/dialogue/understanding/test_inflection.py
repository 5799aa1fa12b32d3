"""Number from what a thing is: the lexicon of inflections, the language's nouns that are always
plural, and the head before "of"."""

from __future__ import annotations

from dialogue.understanding.inflection import plural_name
from tests.dialogue.conftest import english


def test_nouns_always_plural_are_plural_and_news_is_not() -> None:
    lang = english()
    assert all(plural_name(n, lang) for n in ("scissors", "kitchen scissors", "trousers", "pliers", "keys"))
    assert not any(plural_name(n, lang) for n in ("news", "series", "toy bus", "lens", "mug"))


def test_a_measure_or_container_before_of_is_the_head() -> None:
    lang = english()
    assert not any(plural_name(n, lang) for n in ("pair of glasses", "pair of scissors", "box of matches"))
    assert plural_name("boxes of matches", lang) and plural_name("glasses", lang)
