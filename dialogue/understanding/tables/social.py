"""The model of `social.toml`: greetings and what is said with them."""

from __future__ import annotations

from functools import cached_property

from dialogue.understanding.tables.base import (
    Phrase,
    Phrases,
    PhraseSet,
    Table,
    WordSet,
)


class SocialWords(Table):
    """`social.toml`: greetings and what is said with them."""

    greetings: Phrases = ()
    attention: PhraseSet = frozenset()
    social: PhraseSet = frozenset()
    farewells: PhraseSet = frozenset()
    abilities: PhraseSet = frozenset()
    jokes: PhraseSet = frozenset()
    thanks: WordSet = frozenset()
    thank_you: Phrase = ()
    after_no: WordSet = frozenset()
    welcome_back: WordSet = frozenset()

    @cached_property
    def greetings_longest_first(self) -> Phrases:
        """The greetings, longest first: "hello there" before "hello"."""
        return tuple(sorted(self.greetings, key=len, reverse=True))
