"""Number in the replies, from what a thing is rather than how its name is spelt.

A person is one ("Ines is in the kitchen", though "Ines" ends in -s); a thing is as many as the
head noun of its name says by lemminflect's English lexicon ("the keys are", "the reading glasses
are", "the bus is"), or the language's nouns that are always plural, which that lexicon does not tell
from "news" ("the scissors are"); a measure or a container before "of" is the head ("the pair of
glasses is", "the box of matches is"). Counted nouns are said in the plural by the same lexicon ("two
mugs").
"""

from __future__ import annotations

from functools import cache

from lemminflect import getInflection, getLemma

from dialogue.reference.english import tokens
from dialogue.reference.grounding import Entity
from dialogue.understanding.language import Language


@cache
def plural_noun(word: str) -> bool:
    """Whether a noun is a plural form ("keys", "glasses"; not "bus", "lens", "Marcus")."""
    word = word.lower()
    lemmas = getLemma(word, "NOUN", lemmatize_oov=False)
    return any(lemma != word and word in getInflection(lemma, "NNS") for lemma in lemmas)


def plural_name(name: str, lang: Language) -> bool:
    """Whether a thing's name is plural, by its head noun: its last word, or the word before its
    "of" ("pair of glasses": one pair)."""
    words = tokens(name)
    at = words.index("of") if "of" in words[1:] else len(words)
    head = words[at - 1] if words else ""
    return bool(head) and (head in lang.words.plural_only or plural_noun(head))


def is_plural(entity: Entity, lang: Language) -> bool:
    """Whether a reply says the entity with a plural verb: never a person, a thing by its name."""
    return entity.kind == "thing" and plural_name(entity.name, lang)


def plural_of(noun: str) -> str:
    """A noun (its last word) in the plural: "mug" -> "mugs", "reading glass" -> "reading glasses";
    a plural already stays as it is."""
    head, _, last = noun.rpartition(" ")
    if plural_noun(last):
        return noun
    forms = getInflection(last.lower(), "NNS")
    said = forms[0] if forms else last + "s"
    return f"{head} {said}" if head else said
