"""What the tables of a language folder are made of: words, phrases and patterns as they are written
in a file ("a b c", "a b|c"), and the base of every table."""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict

Words = tuple[str, ...]


def _words(value: Any) -> Any:
    """ "a b c" (or ["a", "b"]) -> the words."""
    if isinstance(value, str):
        return value.split()
    return value


def _phrases(value: Any) -> Any:
    """ "a b|c" (or ["a b", "c"]) -> (("a", "b"), ("c",)), in order."""
    if isinstance(value, str):
        value = value.split("|")
    if isinstance(value, list):
        return [tuple(p.split()) if isinstance(p, str) else p for p in value]
    return value


def _phrase(value: Any) -> Any:
    """ "what is" -> ("what", "is")."""
    return tuple(value.split()) if isinstance(value, str) else value


def words_in(value: object) -> Iterator[str]:
    """Every word of a table's values, however nested ("a b|c", a dict's keys and values, phrases)."""
    if isinstance(value, str):
        yield from value.replace("|", " ").split()
    elif isinstance(value, dict):
        yield from words_in(tuple(value))
        yield from words_in(tuple(value.values()))
    elif isinstance(value, Iterable) and isinstance(value, (frozenset, set, tuple, list)):
        for item in value:
            yield from words_in(item)


WordSet = Annotated[frozenset[str], BeforeValidator(_words)]
WordList = Annotated[tuple[str, ...], BeforeValidator(_words)]
Phrases = Annotated[tuple[Words, ...], BeforeValidator(_phrases)]
PhraseSet = Annotated[frozenset[Words], BeforeValidator(_phrases)]
Phrase = Annotated[Words, BeforeValidator(_phrase)]
#: A regular expression (flags inline: "(?i)").
Pattern = Annotated[re.Pattern[str], BeforeValidator(lambda v: re.compile(v) if isinstance(v, str) else v)]


class Table(BaseModel):
    """The tables of one file; a table the file leaves out is empty."""

    model_config = ConfigDict(frozen=True, extra="forbid")
