"""Kinds of thing a person may like or dislike ("tea", "coffee"): classes of the KB, by their labels.

A preference is often about a kind rather than one thing of the situation, so its object may be a
class. The words must be a label of that class (singular or plural, "teas" for "tea"): nothing is
invented, an unknown kind is said to be unknown.
"""

from __future__ import annotations

from dataclasses import dataclass

from dialogue.reference.lexicon import phrase
from kb.protocol import KnowledgeBase
from kb.terms import format_term, parse_name


@dataclass(frozen=True)
class Kind:
    id: str
    name: str


def find_kind(kb: KnowledgeBase, words: str) -> Kind | None:
    """The class whose label is `words` (the first by id when several are), or None (blocking)."""
    wanted = phrase(words)
    if not wanted:
        return None
    found: list[Kind] = []
    for term, kind in kb.lookup(" ".join(wanted)):
        if kind != "class":
            continue
        labels = [str(r["l"]) for r in kb.find([f"{format_term(parse_name(term, 'class'))} rdfs:label ?l"])]
        for label in labels:
            if phrase(label) == wanted:
                found.append(Kind(term, label))
                break
    return min(found, key=lambda k: k.id) if found else None
