"""What a stage reads a parse against: the language, the KB's names, who speaks, what was said
before, and the referents' grounding. The interpreter (dialogue.understanding.interpret) is one; the
stages it calls are given it as this, so that none imports it back."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

from dialogue.history import Utterance
from dialogue.reference.english import Words
from dialogue.reference.grounding import Snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests.referents import Referents
from dialogue.understanding.said import Said, Text


class Context(Protocol):
    """The turn a parse is read in."""

    lang: Language
    lexicon: Lexicon
    snapshot: Snapshot
    speaker: str
    history: tuple[Utterance, ...]
    robot_name: str
    refs: Referents


class Reader(Context, Protocol):
    """What reads a parse in its turn, and again with another conversation before it."""

    def within(self, history: Sequence[Utterance]) -> Reader: ...

    def act(self, p: Parse, overrides: dict[str, Words] | None = None) -> Outcome: ...

    def interpret(self, text: Text) -> Outcome: ...

    def part(self, heard: Said) -> Outcome: ...
