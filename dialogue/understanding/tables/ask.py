"""The model of `ask.toml`: the ask role's words."""

from __future__ import annotations

import re

from pydantic import Field

from dialogue.understanding.tables.base import (
    Pattern,
    Table,
    WordSet,
)


class AskAnswerWords(Table):
    """`ask.toml` [answers]: how an answer to the ask role's form is read."""

    cancel: Pattern = re.compile(r"(?!)")
    skip: Pattern = re.compile(r"(?!)")
    correction: WordSet = frozenset()
    split: Pattern = re.compile(r"(?!)")


class AskWords(Table):
    """`ask.toml`: the ask role's words."""

    yes: WordSet = frozenset()
    no: WordSet = frozenset()
    not_negators: WordSet = frozenset()
    lead_ins: WordSet = frozenset()
    self_: WordSet = Field(default=frozenset(), validation_alias="self")
    kept_lead_ins: WordSet = frozenset()
    owned: WordSet = frozenset()
    unqualifying: WordSet = frozenset()
    ordinals: dict[str, int] = {}
    lead_in_text: Pattern = re.compile("")
    question_back: Pattern = re.compile(r"(?!)")
    number: Pattern = re.compile(r"(?<![\w.])(-)?(\d+(?:\.\d+)?)(?![\w]|\.\d)")
    pronoun_one: Pattern = re.compile(r"(?!)")
    thousands: Pattern = re.compile(r"(?!)")
    half: Pattern = re.compile(r"(?!)")
    field_value: Pattern = re.compile(r":")
    boolean_phrases: dict[str, bool] = {}
    answers: AskAnswerWords = AskAnswerWords()
