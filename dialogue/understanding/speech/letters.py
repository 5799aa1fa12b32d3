"""Words spelled out letter by letter ("the s u v brochure", "the b b q tongs", "3 d glasses"), joined
into the word the KB knows.

A recogniser writes an initialism it hears letter by letter as single letters; a person typing may
too. A run of two or more single letters or digits is joined when the joined word is a word of the
KB's names (the lexicon's vocabulary); otherwise the letters stay as they are (chat's "u" and "n"
are read later as "you" and "and": the language's chat forms). Nothing here is a guess: the letters
say the word.
"""

from __future__ import annotations

from dialogue.reference.english import lowered
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.said import Said, Text

#: At least this many letters make a word spelled out ("a b" in "plan a b" would be two).
_LEAST = 2


def joined(said: Text, lexicon: Lexicon) -> str:
    """The text with each run of single letters that spells a word of the KB joined into it."""
    heard = Said.read(lexicon.lang, said)
    text, words = heard.text, heard.spans
    if len(lowered(text)) != len(text) or not any(len(w) == 1 for w, _, _ in words):
        return text
    out: list[str] = []
    last = 0
    i = 0
    while i < len(words):
        j = i
        while j < len(words) and len(words[j][0]) == 1 and (j == i or words[j][1] == words[j - 1][2] + 1):
            j += 1
        word = "".join(w for w, _, _ in words[i:j])
        if j - i >= _LEAST and lexicon.knows(word) and not word.isdigit():
            start, end = words[i][1], words[j - 1][2]
            spelled = text[start:end].replace(" ", "")
            out += [text[last:start], spelled]
            last = end
            i = j
        else:
            i += 1
    return "".join([*out, text[last:]]) if out else text
