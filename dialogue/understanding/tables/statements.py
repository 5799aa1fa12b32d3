"""The model of `statements.toml`: the words of statements."""

from __future__ import annotations

import re

from dialogue.understanding.tables.base import (
    Pattern,
    Phrase,
    Phrases,
    PhraseSet,
    Table,
    WordSet,
)


class LikingWords(Table):
    """`statements.toml` [likings]: "I like tea", "I'm fond of tea", "tea is my favourite"."""

    intensifiers: WordSet = frozenset()
    like: WordSet = frozenset()
    hate: WordSet = frozenset()
    favourite: WordSet = frozenset()
    over: WordSet = frozenset()
    happenings: WordSet = frozenset()
    appraised: PhraseSet = frozenset()
    clause: WordSet = frozenset()
    leads: dict[Phrase, str] = {}
    negation: Phrases = ()
    negated: WordSet = frozenset()
    is_my: Phrase = ()
    degree: WordSet = frozenset()
    determined: WordSet = frozenset()
    robot: WordSet = frozenset()


class NameWords(Table):
    """`statements.toml` [names]: which words can be a person's name."""

    not_names: WordSet = frozenset()


class StatementWords(Table):
    """`statements.toml`: the words of statements."""

    clauses: Pattern = re.compile(r"(?!)")
    leads: WordSet = frozenset()
    by_the_way: Phrase = ()
    asking: WordSet = frozenset()
    relatives: WordSet = frozenset()
    friends: WordSet = frozenset()
    put: WordSet = frozenset()
    be: WordSet = frozenset()
    polite: PhraseSet = frozenset()
    no: PhraseSet = frozenset()
    name_asked: tuple[str, ...] = ()
    name_leads_surely: Phrases = ()
    name_leads: Phrases = ()
    pointed: PhraseSet = frozenset()
    greeting_topics: Phrases = ()
    trailing: WordSet = frozenset()
    name_last: Phrase = ()
    i_am: Phrase = ()
    it_is: Phrase = ()
    their_name: PhraseSet = frozenset()
    name_is: WordSet = frozenset()
    introducing: Phrases = ()
    belongs_to: Phrases = ()
    to_me: WordSet = frozenset()
    speaker_subject: PhraseSet = frozenset()
    spoken_of: PhraseSet = frozenset()
    speaker_person: PhraseSet = frozenset()
    i_own: Phrase = ()
    when: WordSet = frozenset()
    remark_subjects: WordSet = frozenset()
    remark_verbs: WordSet = frozenset()
    apposed: WordSet = frozenset()
    remark_denials: WordSet = frozenset()
    remark_of: WordSet = frozenset()
    owner_ending: str = ""
    likings: LikingWords = LikingWords()
    names: NameWords = NameWords()
