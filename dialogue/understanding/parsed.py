"""What the grammar makes of an utterance's words, before any of them is grounded in the KB."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from dialogue.reference.english import Words

Act = Literal["command", "question", "greeting", "negated", "conditional", "thanks", "farewell",
              "abilities", "joke", "unknown"]

__all__ = ["Act", "Parse", "Words"]


@dataclass(frozen=True)
class Parse:
    act: Act
    intent: str | None = None
    #: Each role's phrase (still words: which entity it names is decided against the KB).
    slots: dict[str, Words] = field(default_factory=dict)
    text: str | None = None
    question: str | None = None
    words: Words = ()
    #: BRING/give without "to": the recipient and the object are both in `slots["rest"]`.
    double_object: bool = False
    #: Phrases that say how, when or by which way ("through the main door", "on my behalf"):
    #: understood, and part of no referent.
    adjuncts: tuple[Words, ...] = ()
    #: Roles the utterance did not say, filled by the frame's default ("lead the way to the lobby":
    #: the speaker); the interpreter may take them from the conversation instead.
    implicit: frozenset[str] = frozenset()
    #: The preposition that introduced each role's phrase ("beside" for "next to the laptop").
    marks: dict[str, Words] = field(default_factory=dict)
    #: A question said after a greeting ("hello robot, what's your name"): greet, then answer.
    greeted: bool = False
