"""Names misheard or mistyped as other words: what a phrase that names nothing may have meant.

A speech recogniser writes a word it heard for the word that was said: a homophone ("bay for" for
"bay four"), a word that sounds alike ("the blew kettle", "the bath matt", "the kit chin" for the
kitchen: the same consonants in the same order, by the metaphone key of jellyfish), two words for
one ("the pen sill", "the kit chin"); a typist hits a neighbouring key ("bay mine" for "bay nine").
A word the KB does not know is replaced by such a slip of a word of the KB's names (or two words by
one) only when that makes the phrase name exactly one thing, and only when the slip is part of a name
said with other words ("bay nine", "blue water bottle") or two said words make it (a single word heard
for a single other word, "cup" for "cap", is too weak a clue). A word said short ("the mic" for
the "microphone", "the amp"), the start of one word of the names of the things in sight whose rest
is no word of its own ("cup" is not said for the "cupboard"), is that word when that makes the
phrase name exactly one thing. The thing found is a guess (dialogue.llm.hybrid leaves such turns
to its model).
"""

from __future__ import annotations

from collections.abc import Collection
from functools import lru_cache

from jellyfish import metaphone
from rapidfuzz import process
from rapidfuzz.distance import OSA

from dialogue.reference.english import Words
from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import resolve
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.speech.spelling import SHORTEST_KEY, typing_cost

#: At most this many letters apart (optimal string alignment) for a word heard for another.
_HEARD = 2


def slips(word: str, lexicon: Lexicon) -> list[str]:
    """Words of the KB's names that `word` may have been heard or typed for: a homophone ("for":
    "four"), a word that sounds alike ("blew": "blue") or one slip of a neighbouring key ("mine":
    "nine")."""
    sounds = [w for group in lexicon.lang.speech.homophones if word in group for w in group if w != word]
    vocabulary = list(lexicon.vocabulary)
    near = process.extract(word, vocabulary, scorer=OSA.distance, score_cutoff=_HEARD, limit=None)
    typed = [c for c, d, _ in near if c != word and d <= 1 and typing_cost(lexicon.lang, word, c) <= 1]
    heard = [c for c, _, _ in near if c != word and sounds_alike(word, c)]
    return list(dict.fromkeys(w for w in (*sounds, *typed, *heard) if lexicon.knows(w)))


@lru_cache(maxsize=4096)
def sounds_alike(said: str, meant: str) -> bool:
    """Whether two words have the same metaphone key, of at least two sounds."""
    key = metaphone(said)
    return len(key) >= SHORTEST_KEY and key == metaphone(meant)


def slipped(lexicon: Lexicon, words: Words, kinds: Collection[Kind], owner: str | None) -> Entity | None:
    """The one thing the phrase names when a word of it (or two words said for one) is read as a
    slip of a word of the KB's names (see the module docstring), or None."""
    determiners, modifier_start = lexicon.lang.words.determiners, lexicon.lang.modifier_start
    found: set[str] = set()
    for i, word in enumerate(words):
        last = i == len(words) - 1
        if word in determiners or (word in modifier_start and not last):
            continue
        if not lexicon.knows(word):
            for other in slips(word, lexicon):
                trial = (*words[:i], other, *words[i + 1 :])
                one = resolve(lexicon, trial, kinds, owner=owner).one
                if one is not None and _named_with(lexicon, one, trial, i):
                    found.add(one.id)
        pair = words[i : i + 2]
        if len(pair) == 2 and pair[1] not in determiners and not all(lexicon.knows(w) for w in pair):
            # "the pen sill", "the kit chin": two words heard for one
            for other in slips("".join(pair), lexicon):
                one = resolve(lexicon, (*words[:i], other, *words[i + 2 :]), kinds, owner=owner).one
                if one is not None:
                    found.add(one.id)
    return lexicon.snapshot.get(next(iter(found))) if len(found) == 1 else None


def _named_with(lexicon: Lexicon, entity: Entity, words: Words, i: int) -> bool:
    """Whether a name of the entity spans word i and another word ("table *nine*", "*blue* water
    bottle")."""
    for start in range(i + 1):
        for name in lexicon.names_at(words, start):
            if name.entity == entity.id and len(name.words) > 1 and start + len(name.words) > i:
                return True
    return False


#: A word said short has at least this many letters ("mic", "amp"), and leaves at least as many.
_CLIPPED = 3


def clipped(lexicon: Lexicon, words: Words, kinds: Collection[Kind], owner: str | None) -> Entity | None:
    """The one thing the phrase names when a word of it is read as the start of a longer word of
    the KB's names ("the mic": the microphone), or None (see the module docstring)."""
    determiners = lexicon.lang.words.determiners
    found: set[str] = set()
    for i, word in enumerate(words):
        if word in determiners or len(word) < _CLIPPED or not word.isalpha():
            continue
        for other in _longer(word, lexicon):
            one = resolve(lexicon, (*words[:i], other, *words[i + 1 :]), kinds, owner=owner).one
            if one is not None:
                found.add(one.id)
    return lexicon.snapshot.get(next(iter(found))) if len(found) == 1 else None


def _longer(word: str, lexicon: Lexicon) -> list[str]:
    """Words of the names of the things in sight that start with the word and go on with no word
    of their own (only those: a KB's whole vocabulary is too many to try every turn)."""
    attributes = lexicon.attributes
    said = {w for e in lexicon.snapshot.visible() for w in attributes.get(e.id, ())}
    return [w for w in said if w.startswith(word) and len(w) >= len(word) + _CLIPPED
            and not lemmas_of(w[len(word) :])]  # fmt: skip
