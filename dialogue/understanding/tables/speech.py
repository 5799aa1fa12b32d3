"""The model of `speech.toml`: speech and chat forms."""

from __future__ import annotations

from functools import cached_property

from dialogue.understanding.tables.base import (
    Phrase,
    Phrases,
    PhraseSet,
    Table,
    WordList,
    Words,
    WordSet,
)


class ClauseWords(Table):
    """`speech.toml` [clauses]: where a run-on utterance is cut into clauses."""

    asks: Phrases = ()
    indefinite: WordSet = frozenset()
    subjects: WordSet = frozenset()
    auxiliaries: WordSet = frozenset()
    takes_clause: WordSet = frozenset()
    telling: WordSet = frozenset()
    reasons: WordSet = frozenset()
    hedges: WordSet = frozenset()
    describing: Phrases = ()
    thinking: Phrases = ()
    put: WordSet = frozenset()
    not_before_ask: WordSet = frozenset()
    not_after_you: WordSet = frozenset()
    third_person: WordSet = frozenset()
    agreeing: WordSet = frozenset()


class SpellingWords(Table):
    """`speech.toml` [spelling]: how a typo is found."""

    asked: WordSet = frozenset()
    keyboard: tuple[str, ...] = ()
    offsets: tuple[float, ...] = ()


class SpeechWords(Table):
    """`speech.toml`: speech and chat forms."""

    fillers: WordSet = frozenset()
    filler_pairs: PhraseSet = frozenset()
    filler_pairs_before_verb: PhraseSet = frozenset()
    searching: Phrases = ()
    asking: WordSet = frozenset()
    lead_fillers: WordSet = frozenset()
    repairs: Phrases = ()
    repairs_alone: Phrases = ()
    cancels: Phrases = ()
    polite_prefixes: Phrases = ()
    robot_suffixes: Phrases = ()
    polite_suffixes: Phrases = ()
    tags: Phrases = ()
    not_vocative: WordSet = frozenset()
    auxiliaries: WordSet = frozenset()
    homophones: Phrases = ()
    not_nouns: WordSet = frozenset()
    its: str = ""
    it_is: Phrase = ()
    participle_endings: WordList = ()
    numbering: WordSet = frozenset()
    my_after: WordSet = frozenset()
    wishing: WordSet = frozenset()
    preposition_slips: dict[str, str] = {}
    contractions: dict[str, Phrase] = {}
    chat: dict[str, Phrase] = {}
    clauses: ClauseWords = ClauseWords()
    spelling: SpellingWords = SpellingWords()

    @cached_property
    def written(self) -> dict[str, Words]:
        """Every written form read as other words: contractions, with or without the apostrophe,
        and chat."""
        return {**self.contractions, **self.chat}

    @cached_property
    def all_polite_suffixes(self) -> Phrases:
        """The politeness at the end of a request: the robot's, the others, and the tags ("the yellow
        one mate", "over here love")."""
        return (*self.robot_suffixes, *self.polite_suffixes, *self.tags)
