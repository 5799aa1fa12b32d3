"""People's names as they are told: what words can be a name, and the name as it is kept.

"I'm Bob", "call me Bob", "this is Maria" and an answer to "what is your name?" say a name only
when the words look like one: one to three words, no function word, and — in lower-case text, as
speech recognisers write it — no adjective, adverb, participle or number ("I'm tired", "call me
later", "I'm lost", "I'm thirty"). "My name is ..." says a name more surely (an adjective may then
be one: "my name is frank"), but never a negation or a phrase ("my name is not important", "my name
is a secret"). The name kept is the words without quotes or surrounding punctuation, title-cased
when they had no casing ("bob" -> "Bob"), and never longer than `MAX_NAME`.
"""

from __future__ import annotations

from lemminflect import getInflection

from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.said import Said

Words = tuple[str, ...]
#: Longest name a person may give (characters).
MAX_NAME = 60
#: Parts of speech a lower-case word of a name is not.
_NOT_NAME_POS = frozenset({"ADJ", "ADV", "AUX"})
#: Single quotes quote a name only at its words' edges ("'Bobby'"; "O'Brien" keeps its own).
_SINGLE_QUOTES = "'‘’`"


def clean_name(told: Said) -> str:
    """A name as told ("bob" -> "Bob", "mary jane" -> "Mary Jane", '"Bob" Smith' -> "Bob Smith";
    casing kept when it has any), or "" when it is no name (no letters, or too long)."""
    words = (w.strip(_SINGLE_QUOTES) for w in told.unquoted)
    name = " ".join(w for w in words if w).strip(" .,!?;:")
    if not name or len(name) > MAX_NAME or not any(c.isalpha() for c in name):
        return ""
    return name if name != name.lower() else name.title()


def name_like(lang: Language, words: Words, original: Said) -> bool:
    """Whether the words of "I'm X" are a name: one to three words, none a function word, and
    (for lower-case speech-recogniser text) none an adjective, adverb, participle or number."""
    # ("I'm peckish": a need the rules' grammar reads, whatever a lemmatiser knows of the word)
    needs, not_names = lang.requests.needs, lang.statements.names.not_names
    if not 1 <= len(words) <= 3 or any(w in not_names or w in needs or not w.isalpha() for w in words):
        return False
    if original.text != original.text.lower():  # written casing tells names apart: "I'm Frank", "I'm frank"
        return all(part[:1].isupper() for part in original.written)
    closed = lang.words.any_function_word
    return not any(w in closed or _descriptive(w) for w in words) and not words[0].endswith("ing")


def given_name(lang: Language, words: Words) -> bool:
    """Whether the words after "my name is" are a name: "not ...", "a ..." are not."""
    return 1 <= len(words) <= 4 and not any(w in lang.statements.names.not_names for w in words)


def _descriptive(word: str) -> bool:
    """An adjective, an adverb, or a verb's past participle ("lost", "bored"): how someone is."""
    lemmas = lemmas_of(word)
    if _NOT_NAME_POS & set(lemmas):
        return True
    return any(word in getInflection(verb, tag="VBN") for verb in lemmas.get("VERB", ()))
