"""What the client makes of the patterns and keys it is given, before any ROS call.

knowledge_core's client turns every ``*`` into an anonymous variable (``?__<random>``), which its
server names ``var1``, ``var2``... in results; here they are numbered (``?__1``, ``?__2``...) across
one call's patterns, so the same call sends the same text. Statements are split as the KB splits
them (quoted literals whole, with their quotes): ``kb['johnny rdfs:label "A que Johnny"']`` is one
pattern of three terms, where knowledge_core's client strips the quotes (kb-compat K2).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from kb.errors import KbError
from kb.terms import tokenize

STAR = "*"
ANONYMOUS = "?__"


def tokens(statement: str) -> list[str] | None:
    """The terms of a statement as written, or None when it cannot be split (an open quote)."""
    try:
        return [token.text for token in tokenize(statement)]
    except KbError:
        return None


def anonymous(patterns: Sequence[str]) -> list[str]:
    """The patterns with each ``*`` written as an anonymous variable of its own."""
    count = 0
    written: list[str] = []
    for pattern in patterns:
        terms = tokens(pattern)
        if terms is None or STAR not in terms:
            written.append(pattern)
            continue
        named: list[str] = []
        for term in terms:
            if term == STAR:
                count += 1
                term = f"{ANONYMOUS}{count}"
            named.append(term)
        written.append(" ".join(named))
    return written


def named_variables(patterns: Sequence[str]) -> list[str]:
    """The variables of the patterns a caller named (not ``*`` nor ``?__x``), in order, once each."""
    found: list[str] = []
    for pattern in patterns:
        for term in tokens(pattern) or ():
            if term.startswith("?") and not term.startswith(ANONYMOUS) and term not in found:
                found.append(term)
    return found


@dataclass(frozen=True)
class Find:
    patterns: list[str]
    models: list[str]


@dataclass(frozen=True)
class Lookup:
    text: str
    models: list[str]


def item(key: Any) -> Find | Lookup:
    """What ``kb[key]`` asks, as knowledge_core's client reads it: a string of three terms (or a
    one-item tuple of one) is a pattern, any other string a lookup; several strings are a
    conjunction; a list after them names the models."""
    models: list[str] = []
    if isinstance(key, tuple) and len(key) > 1 and isinstance(key[-1], list):
        models, key = list(key[-1]), key[:-1]
    if isinstance(key, tuple) and len(key) == 1:
        key = key[0]
    if isinstance(key, str):
        terms = tokens(key)
        if terms is not None and len(terms) == 3:
            return Find([key], models)
        return Lookup(key, models)
    if isinstance(key, tuple | list) and key and all(isinstance(p, str) for p in key):
        return Find(list(key), models)
    raise KbError(f"kb[...] takes a pattern, a lookup text or several patterns (then a list of models), "
                  f"got {key!r}")
