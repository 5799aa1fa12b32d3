"""Where a thing or person is among places: whether the KB puts it in or on a place (through what
holds it), and the answer to "is X in Y?" ("Is Marcus in the kitchen?", "Is the red kayak in the
shed?")."""

from __future__ import annotations

from collections.abc import Sequence

from dialogue.reference.english import Words
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import PERSON, resolve
from dialogue.understanding.replies import location, say, the
from dialogue.understanding.speech.plain import split_at

#: How many holders deep a thing is looked for in a place (a cup on a tray on a table in a room).
_DEPTH = 3


def held(snapshot: Snapshot, e: Entity, place: str, depth: int = _DEPTH) -> bool:
    """Whether the KB puts the thing on or in the place, or on or in what is there."""
    holders = {h for h in (e.support, e.zone, *(o for r, o in e.relations if r == "in")) if h}
    if place in holders:
        return True
    return depth > 0 and any(held(snapshot, h, place, depth - 1)
                             for h in (snapshot.get(x) for x in holders) if h is not None)  # fmt: skip


def is_there(lexicon: Lexicon, words: Sequence[str], speaker: str, locatives: Sequence[Words]) -> str | None:
    """ "Is Marcus in the kitchen?": where the KB puts a person, said first ("No, as far as I know
    Marcus is in the study."), or that the robot sees them but knows no place ("I can see Bo, but I
    don't know whether they are in the kitchen."); None when the words are not one person and one
    place."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    cut = split_at(words, locatives)
    if cut is None:
        return None
    who = resolve(lexicon, cut[0], PERSON).one
    place = resolve(lexicon, cut[2], frozenset({"zone", "thing"})).one
    if who is None and place is not None:
        return _elsewhere(lexicon, cut[0], place, speaker)
    if who is None or place is None or who.id == speaker:
        return None
    name, where = the(lang, snapshot, who, speaker), location(lang, snapshot, who)
    if not where and who.seen:  # seen, nowhere the KB says: that, and that the place is not known
        asked = f"{cut[1]} {the(lang, snapshot, place, speaker)}"
        return say(lang, "answers.seen_unplaced", name=name, where=asked)
    if not where:
        return say(lang, "answers.unknown_where_is", name=name)
    there = place.id in (who.zone, who.support) or ("in", place.id) in who.relations
    reply = say(lang, "answers.known_there" if there else "answers.known_elsewhere", name=name, where=where)
    return reply if who.seen else reply + say(lang, "answers.unseen_them")


def _elsewhere(lexicon: Lexicon, words: Sequence[str], place: Entity, speaker: str) -> str | None:
    """ "Is the red kayak in the shed?" of one thing the KB puts somewhere else: where it is ("No,
    as far as I know the red kayak is in the slipway."); None when the thing is not one, its place
    is not known, or it may be there (on something in that place, in something on it)."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    thing = resolve(lexicon, words, frozenset({"thing"}), sight=False).one
    if thing is None or thing.id == place.id:
        return None
    # (a zone: the one the KB puts it in; a thing: what it stands on, and in nothing else)
    known = thing.zone if place.kind == "zone" else (thing.support if not thing.relations else None)
    if known is None or held(snapshot, thing, place.id) or any(o == place.id for _, o in thing.relations):
        return None
    where = location(lang, snapshot, thing)
    if not where:
        return None
    return say(lang, "answers.known_elsewhere", name=the(lang, snapshot, thing, speaker), where=where)
