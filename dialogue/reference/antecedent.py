"""What a pronoun refers to: "it", "her", "there" to the entity an earlier turn mentioned.

The latest turn with an unambiguous mention of the kinds the pronoun allows settles it ("take it to
her": a thing, then a person); a mention after a locative preposition ("on the shelf") is where,
never a thing's pronoun, and comes first for "there". A mention of several things is narrowed by
whose the turn says it is ("your ticket" in the robot's words, "my ticket" in a person's, "Chloe's
book"), by where it puts it ("the ticket is on the low table") and by the words describing it ("the
red ball").
"""

from __future__ import annotations

from collections.abc import Collection, Sequence

from dialogue.history import Utterance
from dialogue.reference.english import tokens
from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.lexicon import Lexicon, Mention, norm
from dialogue.reference.resolution import PERSON
from dialogue.understanding.language import Language


def pronoun_kinds(lang: Language, words: Sequence[str], kinds: Collection[Kind]) -> frozenset[Kind]:
    """The kinds a pronoun may refer to among `kinds`: "her" and "him" only ever a person, "it"
    never one ("take it to her": the thing to the person)."""
    said = {w for w in words if w not in lang.words.not_said}
    if said and said <= lang.words.personal:
        return frozenset(kinds) & PERSON
    if said and said <= lang.words.neuter:
        return frozenset(kinds) - PERSON
    return frozenset(kinds)


def antecedent(
    lexicon: Lexicon,
    history: Sequence[str | Utterance],
    kinds: Collection[Kind],
    *,
    place: bool = False,
    speaker: str | None = None,
) -> Entity | None:
    """The entity a pronoun refers to: the latest turn's first non-locative unambiguous mention.

    For "there" (`place=True`) mentions after a locative preposition ("on the shelf") come first;
    for a thing's pronoun they are never it.
    A mention of several things is narrowed by whose it is said to be ("your ticket" in the robot's
    words is the ticket of `speaker`, the person now speaking; "my ticket" in a person's is theirs;
    "Chloe's book") and by where the same turn puts it ("the ticket is on the low table").
    """
    for turn in reversed(history):
        text, owners = _owners(lexicon.lang, turn, speaker)
        words = [w[:-2] if w.endswith("'s") and len(w) > 2 else w for w in tokens(text)]
        mentions = lexicon.mentions(words)
        places = {e for m in mentions if _after_locative(lexicon.lang, words, m.start) for e in m.entities}
        found: list[tuple[bool, int, Entity]] = []
        before: Mention | None = None
        for mention in mentions:
            ents = [lexicon.snapshot.get(e) for e in mention.entities]
            typed = [e for e in ents if e is not None and e.kind in kinds]
            if len(typed) > 1:
                owner = _owner_before(lexicon, words, mention.start, owners, before)
                typed = _described(lexicon, _narrowed(typed, owner, places), words, mention.start)
            before = mention
            locative = _after_locative(lexicon.lang, words, mention.start)
            # "my keys are on the counter, get them": "them" is not where the keys are
            if len(typed) != 1 or (locative and not place and typed[0].kind != "person"):
                continue
            found.append((locative, mention.start, typed[0]))
        if found:
            found.sort(key=lambda f: (f[0] != place, f[1]))
            return found[0][2]
    return None


def _owners(lang: Language, turn: str | Utterance, speaker: str | None) -> tuple[str, dict[str, str]]:
    """The turn's text and whom its possessives name: "my" is the speaker's in a person's words,
    "your" the person spoken to in the robot's."""
    if isinstance(turn, str):
        return turn, {}
    if turn.role == "user":
        return turn.text, dict.fromkeys(lang.words.speaker_possessives, turn.speaker)
    if turn.role == "assistant" and speaker is not None:
        return turn.text, dict.fromkeys(lang.words.addressee_possessives, speaker)
    return turn.text, {}


def _after_locative(lang: Language, words: Sequence[str], start: int) -> bool:
    return any(w in lang.locative for w in words[max(0, start - 2) : start])


def _owner_before(
    lexicon: Lexicon, words: Sequence[str], start: int, owners: dict[str, str], before: Mention | None
) -> str | None:
    """Whose thing the words just before a mention say it is: a possessive ("your") or a person
    named right before it ("Chloe's book", "chloes book" as a recogniser writes it)."""
    if before is not None and before.end == start and len(before.entities) == 1:
        person = lexicon.snapshot.get(next(iter(before.entities)))
        if person is not None and person.kind == "person":
            return person.id
    return next((owners[w] for w in reversed(words[max(0, start - 2) : start]) if w in owners), None)


def _described(lexicon: Lexicon, typed: list[Entity], words: Sequence[str], start: int) -> list[Entity]:
    """Those the words right before the mention describe ("the *red* ball": its colour or label
    words), when any are."""
    said: list[str] = []
    at = start - 1
    glue, pronouns = lexicon.lang.glue, lexicon.lang.words.pronouns
    while at >= 0 and len(said) < 3 and words[at] not in glue and words[at] not in pronouns:
        said.append(words[at])
        at -= 1
    if not said:
        return typed
    qualifiers = norm(said)
    fit = [e for e in typed if all(w in lexicon.attributes.get(e.id, frozenset()) for w in qualifiers)]
    return fit or typed


def _narrowed(typed: list[Entity], owner: str | None, places: set[str]) -> list[Entity]:
    if owner is not None:
        typed = [e for e in typed if e.owner == owner] or typed
    if len(typed) > 1 and places:
        typed = [e for e in typed if e.support in places or e.zone in places] or typed
    return typed
