"""The speaker's family said by kin words ("bring my wife her phone", "tell Dad dinner is ready",
"give this to my youngest"): whom the KB relates to the speaker so (`reference.facts.KIN`: isParentOf,
isSpouseOf, hasSibling and their other spellings), by the chain of relations the language gives each
word (`words.toml`: `kin`, `kin_bare`). Where the KB names no one, or several, the robot asks; so it
does where the word says a gender (`kin_gender`) the KB cannot bear out."""

from __future__ import annotations

from dialogue.reference.english import Words
from dialogue.reference.snapshot import Entity, Snapshot
from dialogue.understanding.language import Language


def kin_word(lang: Language, words: Words) -> str | None:
    """The kin word a phrase says the speaker's relative by ("my wife", "our youngest", "Dad"), or
    None when it is not such a phrase ("the dad" is someone's, not the speaker's)."""
    closed = lang.words
    lowered = [w.lower() for w in words]
    if lowered[:1] and lowered[0] in closed.determiners and lowered[0] not in closed.possessives:
        return None
    mine = bool(lowered[:1]) and lowered[0] in closed.speaker_possessives
    rest = lowered[1:] if mine else lowered
    if len(rest) != 1 or rest[0] not in closed.kin:
        return None
    return rest[0] if mine or rest[0] in closed.kin_bare else None


def relatives(lang: Language, snapshot: Snapshot, speaker: str, word: str) -> list[str]:
    """Whom the KB relates to the speaker as the kin word says, in id order (none, one or several)."""
    found = {speaker}
    for relation in lang.words.kin[word]:
        found = {other for who in found if (e := snapshot.get(who)) is not None
                 for rel, other in e.kin if rel == relation and other != speaker}  # fmt: skip
    return sorted(found)


def said_so(lang: Language, relative: Entity, word: str) -> bool:
    """Whether the KB bears out the gender the kin word says of the one relative it found: a word
    with none ("my spouse"), or a relative called by it ("Mum"). ORO gives people no gender, so
    "my mum" of a lone parent is otherwise a guess, asked rather than acted on."""
    if word not in lang.words.kin_gender:
        return True
    return word in {label.lower() for label in relative.labels}
