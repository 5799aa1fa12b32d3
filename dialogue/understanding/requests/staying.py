"""A thing to stay where it is: "great, leave it there" of a place just spoken of (after "the remote
is on the sofa", or after the robot put something there), "just leave it where it is". A placing
verb said so asks for nothing to be done; read as a placing, the robot would move a thing it was
asked to leave alone. Which verbs and places say it is the language's data (`requests.toml`:
`staying`, `stays`)."""

from __future__ import annotations

from dialogue import intents as I
from dialogue.reference.antecedent import antecedent
from dialogue.reference.resolution import PLACE
from dialogue.understanding.context import Reader
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse, Words
from dialogue.understanding.replies import say


def left_as_is(reader: Reader, p: Parse) -> Outcome | None:
    """The acknowledgement of a thing said to stay where it is, no intent; None when the request is
    not one ("leave the mug on the shelf" is a placing, "leave it there" with no place spoken of is
    a place pointed at, and a thing named to be left "there" may be put there)."""
    lang = reader.lexicon.lang
    r = lang.requests
    if p.intent != I.PLACE_OBJECT or not p.words or p.words[0] not in r.staying:
        return None
    thing, place = p.slots.get("object", ()), p.slots.get("recipient", ())
    if not place:  # ("leave it where it is": the grammar keeps the clause with the thing)
        thing, place = _split(thing, r.stays)
    if not thing or place not in r.stays:
        return None
    if place in r.said_there:  # "leave it there": the thing spoken of, at the place spoken of
        if len(thing) != 1 or thing[0] not in lang.words.pronouns:
            return None  # ("the shelf is free, leave the box there": put there)
        if antecedent(reader.lexicon, reader.history, PLACE, place=True, speaker=reader.speaker) is None:
            return None
    return Outcome(say(lang, "request.stays"))


def _split(words: Words, ends: frozenset[Words]) -> tuple[Words, Words]:
    """The words before a phrase of `ends` they end with, and that phrase."""
    for i in range(len(words)):
        if words[i:] in ends:
            return words[:i], words[i:]
    return words, ()
