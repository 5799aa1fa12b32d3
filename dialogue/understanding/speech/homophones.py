"""Words of the grammar a speech recogniser writes as their homophones: "the pear of goggles" (a
pair of), "go to the prep room write now" (right now), "wait their for the van" (there).

A homophone is read as the grammar's word only where the grammar's word makes a phrase of the
grammar and the word as written does not: a measure before "of" (MEASURES: "pair of", "piece of"),
an adjunct or a politeness said at the end ("right now", "right away"), a pointing word where no
noun follows a possessive ("wait their for the van", "leave it their"). A word the KB has a name
with is never read otherwise ("the pear" in a greengrocer's).
"""

from __future__ import annotations

from collections.abc import Sequence

from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.language import Language


class _Homophones:
    """A language's homophones and the phrases one may be read into (made once per language)."""

    def __init__(self, lang: Language) -> None:
        closed = lang.words
        self.homophones = lang.speech.homophones
        #: Phrases a homophone may be read into, by their first word: adjuncts and politeness at the end.
        said = lang.requests
        self.phrases = tuple(p for p in (*said.all_adjuncts, *lang.speech.all_polite_suffixes) if len(p) > 1)
        self.pointing = frozenset(p[0] for p in (*said.here, *said.there) if len(p) == 1)
        self.measures = closed.measures
        self.possessives = closed.possessives
        self.np_start = closed.np_start
        self.function_words = closed.any_function_word
        self.numbers = closed.numbers


def misheard(words: Sequence[str], n: int, lexicon: Lexicon) -> str | None:
    """The grammar's word the n-th word is a homophone of, where only that word makes sense."""
    said = lexicon.lang.derived(_Homophones)
    word = words[n]
    others = [w for group in said.homophones if word in group for w in group if w != word]
    if not others or lexicon.knows(word):
        return None
    after = words[n + 1] if n + 1 < len(words) else ""
    for other in others:
        if other in said.measures and after == "of" and n > 0 and words[n - 1] in said.np_start:
            return other  # "the pear of goggles"
        if n > 0 and any(_said(said, words, n, p, other) for p in said.phrases if p[0] == other):
            return other  # "write now"
        if other in said.pointing and word in said.possessives and n > 0 and _no_noun(said, after):
            return other  # "wait their for the van"
    return None


def _said(said: _Homophones, words: Sequence[str], n: int, phrase: tuple[str, ...], first: str) -> bool:
    """Whether the phrase, its first word read as `first`, is said at n ("write now" as "right now")."""
    return tuple((first, *words[n + 1 : n + len(phrase)])) == phrase and not any(
        p == tuple(words[n : n + len(p)]) for p in said.phrases)


def _no_noun(said: _Homophones, after: str) -> bool:
    """Whether what follows a possessive is no noun phrase (a preposition, a conjunction, nothing)."""
    closed = after in said.function_words and after not in said.numbers
    return not after or (closed and after not in said.np_start)
