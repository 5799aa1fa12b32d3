"""Terse and non-native requests, said again in the order the grammar reads: the thing or place
fronted before the verb ("Orchid put on counter", "Back yard, go"), a subject "you" before the verb
("You pick watering can"), a verb with no preposition before a place ("Go workstand"), no verb at
all ("Sunflowers into tall vase", "Dining room, now please", "Binoculars, please", "Radio to the
skipper").

Only phrases that are exactly a name the KB knows are moved: a fronted person's name stays a
vocative ("John, go to the kitchen"), and a bare phrase is a place to go only when it names one
whole ("dining room"), never when it merely contains one.
"""

from __future__ import annotations

from collections.abc import Sequence

from dialogue.reference.english import Words
from dialogue.reference.grounding import Kind
from dialogue.reference.lexicon import Lexicon, singular
from dialogue.reference.resolution import PERSON, PLACE, ZONE, resolve
from dialogue.reference.snapshot import fixed
from dialogue.understanding.requests.compound import coordinated
from dialogue.understanding.requests.frames import verbs
from dialogue.understanding.said import Text
from dialogue.understanding.speech.plain import strip_politeness
from dialogue.understanding.speech.repair import asked_verb, normalise


def terse(text: Text, lexicon: Lexicon, robot_name: str = "", answering: bool = False) -> str | None:
    """The request said in the grammar's order, or None when the text is no terse request. A thing
    said alone is asked for only when politeness says it is a request, and never while `answering`
    the robot's question (then it is the answer)."""
    lang = lexicon.lang
    said = normalise(lang, text)
    words = strip_politeness(lang, said, robot_name)
    asked = len(words) < len(said) and not answering  # ("binoculars, please")
    subject = False
    # ("you go office": a subject said before an imperative by a speaker of another language)
    while words[:1] and words[0] in lang.requests.terse.subjects | {robot_name} and len(words) > 1:
        words, subject = words[1:], True
    if not words:
        return None
    at = next((i for i, w in enumerate(words) if asked_verb(lang, w) in verbs(lang)), None)
    if at is not None and ((asked and _all_named(words, lexicon)) or _one_thing(words, lexicon)
                           or _each_named(words, lexicon)):
        at = None  # ("sticks, please": the drumsticks, not "stick" said as a verb; "the still water")
    if at is None:
        return _verbless(words, lexicon) or (None if answering else _handed(words, lexicon, asked))
    verb, front, rest = asked_verb(lang, words[at]) or words[at], words[:at], words[at + 1 :]
    if front:
        named = _named(front, lexicon)
        if named is None:
            return None
        rest = [*named, *rest]
    motion = verb in lang.requests.terse_motion and rest and rest[0] not in lang.words.any_function_word
    if motion and _a_place(rest, lexicon):
        # "go workstand", "back yard, go"
        return lang.requests.terse.moving.format(verb=verb, place=" ".join(rest))
    return " ".join((verb, *rest)) if front or (subject and at == 0) else None


def unasked_thing(text: Text, lexicon: Lexicon, robot_name: str = "") -> str | None:
    """ "Water. Still.": words that read as a verb ("water") but all describe one thing the robot
    could bring, with no politeness to say they ask for it: the bringing a question may propose (never
    an activity of watering); None otherwise."""
    lang = lexicon.lang
    said = normalise(lang, text)
    words = strip_politeness(lang, said, robot_name)
    if len(words) < len(said) or not any(asked_verb(lang, w) in verbs(lang) for w in words):
        return None
    return _handed(words, lexicon, asked=True) if _one_thing(words, lexicon) else None


def _one_thing(words: Sequence[str], lexicon: Lexicon) -> bool:
    """Whether the words are one thing's names and words, a determiner before them allowed
    ("still water" of the "bottle of still water"), a thing that can be carried."""
    closed = lexicon.lang.words
    bare = list(words[1:]) if words[:1] and words[0] in closed.np_start else list(words)
    if not bare or any(w in closed.any_function_word or not lexicon.knows(w) for w in bare):
        return False  # (a clause or a request: "bring me the cup", "grab the cup", without a lookup)
    named = _named(words, lexicon)
    one = resolve(lexicon, named, PLACE).one if named is not None else None
    if one is None or not _movable(words, lexicon):
        return False
    spans = {i for m in lexicon.mentions(bare) if one.id in m.entities for i in range(m.start, m.end)}
    own = lexicon.attributes.get(one.id, frozenset())
    return all(i in spans or singular(w) in own for i, w in enumerate(bare))  # ("grab the mug": no)


def _verbless(words: list[str], lexicon: Lexicon) -> str | None:
    """ "dining room": go there; "sunflowers into tall vase": put them there."""
    if _a_place(words, lexicon, ZONE):  # a place alone is a room or area, never a thing
        return lexicon.lang.requests.terse.going.format(place=" ".join(words))
    placing = lexicon.lang.prepositions.words("terse-place")
    at = next((i for i, w in enumerate(words) if w in placing), None)
    if at is None or at == 0 or _named(words[:at], lexicon) is None:
        return None
    return lexicon.lang.requests.terse.putting.format(words=" ".join(words))


def _handed(words: list[str], lexicon: Lexicon, asked: bool) -> str | None:
    """ "binoculars, please": bring them to the speaker; "radio to the skipper", "the headphones for
    Maud": to the one person said after the thing."""
    to = lexicon.lang.prepositions.words("terse-to")
    at = next((i for i, w in enumerate(words) if w in to), None)
    parts = coordinated(lexicon.lang, tuple(words)) if at is None else []
    if parts:  # "painkillers please and then the glass of water": each brought, politeness between
        asked = asked or sum(map(len, parts)) + len(parts) - 1 < len(words)
        each = _each_named(words, lexicon) and all(_movable(p, lexicon) for p in parts)
        return lexicon.lang.requests.terse.handed_me.format(thing=" ".join(words)) if asked and each else None
    if at is None:
        said = asked and (_all_named(words, lexicon) or _one_thing(words, lexicon))
        thing = _named(words, lexicon) if said else None
        handed_me = lexicon.lang.requests.terse.handed_me
        return handed_me.format(thing=" ".join(thing)) if thing and _movable(thing, lexicon) else None
    thing = _named(words[:at], lexicon) if at and _all_named(words[:at], lexicon) else None
    if thing is None or resolve(lexicon, words[at + 1 :], PERSON).one is None:
        return None
    return lexicon.lang.requests.terse.handed.format(thing=" ".join(thing), person=" ".join(words[at + 1 :]))


def _all_named(words: Sequence[str], lexicon: Lexicon) -> bool:
    """Whether every word but a determiner before them is of a name the KB knows ("the island
    map"), no word of a request besides ("grab Ines's phone")."""
    bare = list(words[1:]) if words[:1] and words[0] in lexicon.lang.words.np_start else list(words)
    return sum(m.end - m.start for m in lexicon.mentions(bare)) == len(bare) > 0


def _each_named(words: Sequence[str], lexicon: Lexicon) -> bool:
    """Whether the words are things the KB names joined by "and" ("the juice and the glass of water"),
    politeness between them allowed."""
    parts = coordinated(lexicon.lang, tuple(words))
    return bool(parts) and all(_all_named(p, lexicon) for p in parts)


def _movable(words: Sequence[str], lexicon: Lexicon) -> bool:
    """Whether the words name things only, of which none is fixed where it is (never a place)."""
    things = resolve(lexicon, words, PLACE).matches
    return bool(things) and all(t.kind == "thing" and not fixed(t) for t in things)


def _named(words: Sequence[str], lexicon: Lexicon) -> Words | None:
    """The phrase as the grammar reads it when it is exactly names the KB knows (a determiner
    before it allowed): one thing or place ("birthday card"), or a person's then a thing ("edna
    cardigan": Edna's cardigan); else None."""
    closed = lexicon.lang.words
    bare = list(words[1:]) if words[:1] and words[0] in closed.np_start else list(words)
    found = lexicon.mentions(bare)
    named = {i for m in found for i in range(m.start, m.end)}
    if not bare or any(w in closed.any_function_word for i, w in enumerate(bare) if i not in named):
        return None  # ("you go", "I need", "it is"): a clause, no phrase
    people = [m for m in found if all(lexicon.is_person(e) for e in m.entities)]
    if people and people[0].start == 0 and len(people) == 1 and people[0].end < len(bare):
        # "edna cardigan": Edna's cardigan, when that is a thing
        owner, thing = bare[: people[0].end], bare[people[0].end :]
        return (*owner[:-1], f"{owner[-1]}'s", *thing) if _a_thing(thing, lexicon) else None
    return tuple(words) if not people and _a_thing(bare, lexicon) else None


def _a_thing(words: Sequence[str], lexicon: Lexicon) -> bool:
    """Whether the words name a thing or place the KB has (one or more: "sunflowers")."""
    return bool(resolve(lexicon, words, PLACE).matches)


def _a_place(words: Sequence[str], lexicon: Lexicon, kinds: frozenset[Kind] = PLACE) -> bool:
    """Whether the words are exactly the name of one place (a zone, or a thing to go to after a
    verb of motion)."""
    found = lexicon.mentions(words)
    if len(found) != 1 or (found[0].start, found[0].end) != (0, len(words)):
        return False
    if any(lexicon.is_person(e) for e in found[0].entities):
        return False
    return resolve(lexicon, words, kinds).one is not None
