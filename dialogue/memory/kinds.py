"""Kinds of thing a person may like or dislike ("tea", "coffee"): classes of the KB, by their labels.

A preference is often about a kind rather than one thing of the situation, so its object may be a
class. The words must be a label of that class (singular or plural, "teas" for "tea"): nothing is
invented, an unknown kind is said to be unknown.
"""

from __future__ import annotations

from dataclasses import dataclass

from dialogue.reference.lexicon import phrase
from kb.protocol import KnowledgeBase

#: The labels of the classes, by the types that make a term a class (as `lookup` tells classes).
CLASS_LABELS = (("?c rdfs:label ?l", "?c rdf:type owl:Class"), ("?c rdfs:label ?l", "?c rdf:type rdfs:Class"))


@dataclass(frozen=True)
class Kind:
    id: str
    name: str


def find_kind(kb: KnowledgeBase, words: str) -> Kind | None:
    """The class whose label is `words` (the first by id when several are), or None (blocking).

    Reads the labels of the classes only (a few hundred), not a text search of the whole KB
    (`lookup` scans every label: O(KB size) per turn)."""
    wanted = phrase(words)
    if not wanted:
        return None
    labels = {(str(r["c"]), str(r["l"])) for patterns in CLASS_LABELS for r in kb.find(list(patterns))}
    found = [Kind(term, label) for term, label in labels if phrase(label) == wanted]
    return min(found, key=lambda k: (k.id, k.name)) if found else None
