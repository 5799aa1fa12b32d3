"""People's names heard or typed in another spelling: "jeff" for Geoff, "steven" for Stephen,
"reese" for Rhys, "aisha" for Ayesha, "kowalsky" for Kowalski.

A recogniser writes a name it hears in the spelling it knows best; a typist writes it as it sounds.
A word nothing else accounts for is read as the word of a person's name of the KB that sounds the
same: the same metaphone key (jellyfish), less the letters that barely sound between others (h, w,
y: "rhys" and "reese", "ayesha" and "aisha"), of at least two sounds. Only one such word may fit;
the reading is a guess about who is meant (the caller marks it so).
"""

from __future__ import annotations

from functools import lru_cache

from jellyfish import metaphone

from dialogue.reference.english import tokens
from dialogue.reference.lexicon import Lexicon

#: Sounds that barely sound after the first one: "RHS" (rhys) is "RS" (reese).
_FAINT = str.maketrans("", "", "HWY")
#: A key this short ("T") says too little of a name to match it by its sound.
_SHORTEST = 2


@lru_cache(maxsize=4096)
def sound_key(word: str) -> str:
    """The word's metaphone key without its faint sounds after the first ("ayesha", "aisha": "AX")."""
    key = metaphone(word)
    return key[:1] + key[1:].translate(_FAINT)


def heard_name(word: str, lexicon: Lexicon) -> str | None:
    """The one word of a person's name in the KB that `word` sounds like, if exactly one does."""
    key = sound_key(word)
    if len(key) < _SHORTEST:
        return None
    titles = frozenset(w for group in lexicon.lang.words.titles for w in group)
    found = {
        said
        for person in lexicon.snapshot.of_kind("person")
        for label in person.labels
        for said in tokens(label)
        if said != word and said not in titles and said.isalpha() and sound_key(said) == key
    }
    return found.pop() if len(found) == 1 else None
