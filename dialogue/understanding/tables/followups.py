"""The model of `followups.toml`: the words of answers to the robot's question."""

from __future__ import annotations

from dialogue.understanding.tables.base import (
    Phrase,
    Phrases,
    PhraseSet,
    Table,
    WordSet,
)


class FollowupWords(Table):
    """`followups.toml`: the words of answers to the robot's question."""

    interjections: WordSet = frozenset()
    approving: WordSet = frozenset()
    one: WordSet = frozenset()
    offers: Phrases = ()
    offers_a_thing: Phrases = ()
    choosing: Phrases = ()
    swapped: dict[str, str] = {}
    confirms: Phrases = ()
    accepting: WordSet = frozenset()
    yes: WordSet = frozenset()
    yes_phrases: Phrases = ()
    no: dict[str, str] = {}
    other: WordSet = frozenset()
    correcting: Phrases = ()
    again: Phrases = ()
    additive: Phrases = ()
    instead: Phrases = ()
    additive_leads: Phrases = ()
    additive_alone: Phrases = ()
    softening: WordSet = frozenset()
    emphasis: WordSet = frozenset()
    both: PhraseSet = frozenset()
    joining: WordSet = frozenset()
    articles: WordSet = frozenset()
    the_other: Phrase = ()
    offered_request: Phrase = ()
    continued_to: str = ""
