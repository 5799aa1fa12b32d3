"""What a phrase names when no name of the KB settles it (the later sieves of
dialogue.reference.resolution): a part of a label ("the teddy"), qualifiers alone ("the orange
one"), what a measure of it names ("a pair of glasses") or a container holds ("a can of beer"); and
the adjective a comparative compares by ("the bigger one": big)."""

from __future__ import annotations

from collections.abc import Collection, Sequence
from functools import lru_cache

from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of


@lru_cache(maxsize=4096)
def compared(lang: Language, word: str) -> str:
    """The adjective a comparative or superlative compares by ("the bigger one": big), else the word."""
    if word.endswith(lang.words.compared):
        bases: tuple[str, ...] = lemmas_of(word).get("ADJ", ())
        if bases and bases[0] != word:
            return bases[0]
    return word


def thing_measured(lang: Language, words: Sequence[str]) -> tuple[str, ...]:
    """ "a pair of glasses" -> "glasses": what a measure of it names; () when no measure is said."""
    measures = lang.words.measures
    at = next((i for i in range(len(words) - 2) if words[i] in measures and words[i + 1] == "of"), None)
    return () if at is None else tuple(words[at + 2 :])


def thing_held(lang: Language, words: Sequence[str], normed: Sequence[str]) -> tuple[str, ...]:
    """ "the beer cans" -> "the beer", "a can of beer" -> "beer": what a container named by a word
    the KB has no thing for holds (the caller tried the container first); () when there is none."""
    for i, word in enumerate(normed):
        if word not in lang.words.containers:
            continue
        if words[i + 1 : i + 2] == ["of"] and words[i + 2 :]:
            return tuple(words[i + 2 :])
        if i > 0 and words[i - 1] not in lang.glue:
            return (*words[:i], *words[i + 1 :])
    return ()


def by_qualifiers(lexicon: Lexicon, qualifiers: Sequence[str], kinds: Collection[Kind]) -> list[Entity]:
    """ "the orange one": with no noun, the things every qualifier holds for (colour, label words)."""
    said = [(w, compared(lexicon.lang, w)) for w in qualifiers]
    out = []
    for entity in lexicon.snapshot.entities.values():
        attrs = lexicon.attributes.get(entity.id, frozenset())
        if entity.kind in kinds and all(w in attrs or base in attrs for w, base in said):
            out.append(entity)
    return out


def by_label_words(lexicon: Lexicon, content: Sequence[str], kinds: Collection[Kind]) -> list[Entity]:
    """ "the teddy" for the "teddy bear", "the flathead" for the "flathead screwdriver": when no name
    occurs, a part of a label still names the thing if every other word qualifies it."""
    candidates = dict.fromkeys(e for w in content for e in lexicon.by_label_word.get(w, ()))
    out = []
    for entity_id in candidates:
        entity = lexicon.snapshot.get(entity_id)
        attrs = lexicon.attributes.get(entity_id, frozenset())
        if entity is not None and entity.kind in kinds and all(w in attrs for w in content):
            out.append(entity)
    return lexicon.snapshot.in_order(out)
