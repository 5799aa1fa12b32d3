"""Whether an answer only says yes ("yes please", "go on then", "that'd be lovely"): to an offer, a
guess, or a reading the robot proposed."""

from __future__ import annotations

from dialogue.reference.english import Words
from dialogue.understanding.language import Language

__all__ = ["accepts"]


def accepts(lang: Language, words: list[str]) -> bool:
    """Whether the words only say yes ("yes please", "go on then", "that'd be lovely")."""
    if not words or not set(words) <= lang.followups.accepting:
        return False
    said = tuple(words)
    yes = lang.followups
    return bool(set(words) & yes.yes) or any(p in _spans(said, len(p)) for p in yes.yes_phrases)


def _spans(words: Words, n: int) -> set[Words]:
    return {words[i : i + n] for i in range(len(words) - n + 1)}
