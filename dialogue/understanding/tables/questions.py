"""The model of `questions.toml`: the words of questions about the situation and about what people told."""

from __future__ import annotations

from pydantic import Field

from dialogue.understanding.tables.base import (
    Phrase,
    Phrases,
    PhraseSet,
    Table,
    WordSet,
)


class SituationQuestionWords(Table):
    """`questions.toml` [situation]: the words of questions about the situation."""

    sees: Phrases = ()
    not_seen_before: WordSet = frozenset()
    where_leads: Phrases = ()
    on_glue: WordSet = frozenset()
    who_not_a_name: WordSet = frozenset()
    who_pointing: WordSet = frozenset()
    posture: WordSet = frozenset()
    count: Phrases = ()
    who_sees: WordSet = frozenset()
    see_words: WordSet = frozenset()
    colour_words: WordSet = frozenset()
    indirect: Phrases = ()
    describe: Phrases = ()
    described: dict[str, Phrase] = {}
    be: WordSet = frozenset()
    someone: WordSet = frozenset()
    else_: WordSet = Field(default=frozenset(), validation_alias="else")
    owners: WordSet = frozenset()
    nearby: WordSet = frozenset()
    others: WordSet = frozenset()
    there: WordSet = frozenset()
    there_after: WordSet = frozenset()
    asking_verbs: WordSet = frozenset()
    asked_subjects: WordSet = frozenset()
    count_tail: WordSet = frozenset()
    someone_said: WordSet = frozenset()
    seen_by_anyone: Phrases = ()
    placing: WordSet = frozenset()
    asker: WordSet = frozenset()
    gone: WordSet = frozenset()
    rooms: WordSet = frozenset()
    name_of: Phrases = ()
    whoever: WordSet = frozenset()
    show_me: Phrase = ()
    tell_me: Phrase = ()
    how_many: Phrase = ()
    belong_to: Phrase = ()
    in_front: Phrase = ()
    front_of: PhraseSet = frozenset()
    are_you: Phrase = ()
    what_heads: WordSet = frozenset()
    anything: WordSet = frozenset()
    is_are: WordSet = frozenset()
    social_how: Phrases = ()
    count_glue: WordSet = frozenset()
    count_after: WordSet = frozenset()
    seeing_aux: WordSet = frozenset()
    you_see: Phrase = ()
    not_which_see: WordSet = frozenset()
    where_me: str = ""
    where_you: str = ""
    name_words: WordSet = frozenset()
    not_what_is: WordSet = frozenset()
    does: WordSet = frozenset()
    got_to: PhraseSet = frozenset()
    did: WordSet = frozenset()
    went: WordSet = frozenset()
    where_am_i: PhraseSet = frozenset()
    where_tail: WordSet = frozenset()
    presence_asking: WordSet = frozenset()
    arrived: Phrases = ()
    departed: Phrases = ()
    asked_for: PhraseSet = frozenset()
    untracked: PhraseSet = frozenset()
    recall_tail: WordSet = frozenset()


class ToldQuestionWords(Table):
    """`questions.toml` [told]: the words of questions about what people told."""

    like: WordSet = frozenset()
    hate: WordSet = frozenset()
    who_am_i: PhraseSet = frozenset()
    tail: WordSet = frozenset()
    pronoun_of: dict[str, Phrase] = {}
    where: Phrases = ()
    where_end: WordSet = frozenset()
    name_of: Phrase = ()
    what_is: Phrase = ()
    what_do: WordSet = frozenset()
    speaker: PhraseSet = frozenset()
    spoken_of: PhraseSet = frozenset()


class QuestionWords(Table):
    """`questions.toml`: the words of questions."""

    situation: SituationQuestionWords = SituationQuestionWords()
    told: ToldQuestionWords = ToldQuestionWords()
