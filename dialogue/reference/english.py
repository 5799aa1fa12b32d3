"""The one tokeniser, and the helpers that read word lists.

The words themselves are data: closed-class words, prepositions and the grammar's words are in the
language folder (dialogue.understanding.language, `lang/en/`); nouns always come from the KB
(dialogue.reference.lexicon).
"""

from __future__ import annotations

import re

Words = tuple[str, ...]

_TOKEN = re.compile(r"[a-z0-9]+(?:'[a-z]+)?")
#: The same words, and the commas and semicolons that may end a part of a compound request.
_TOKEN_OR_MARK = re.compile(r"[a-z0-9]+(?:'[a-z]+)?|,|;")
#: The marks `spans` gives with `marks`: a scan with them, less them, is the scan without them.
MARKS = frozenset({",", ";"})


def lowered(text: str) -> str:
    """Lower case with typographic apostrophes made plain (the form every tokeniser reads)."""
    return text.lower().replace("\u2019", "'")


def tokens(text: str) -> list[str]:
    """Lower-case whole words; `cup_1` gives `cup 1`, "don't" stays one word."""
    return _TOKEN.findall(lowered(text))


def spans(text: str, marks: bool = False) -> list[tuple[str, int, int]]:
    """Each word (and, with `marks`, each comma or semicolon) with its start and end in `text`.

    The offsets are those of the lowered text, which are the original's whenever lowering kept its
    length (callers that slice the original check that)."""
    pattern = _TOKEN_OR_MARK if marks else _TOKEN
    return [(m.group(), m.start(), m.end()) for m in pattern.finditer(lowered(text))]


def word_set(text: str) -> frozenset[str]:
    return frozenset(text.split())


def phrases(text: str) -> tuple[Words, ...]:
    """ "a b|c" -> (("a", "b"), ("c",)): compact phrase lists."""
    return tuple(tuple(p.split()) for p in text.split("|"))
