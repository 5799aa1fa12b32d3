"""Verbal answers to questions about the situation, computed from the snapshot (no intent, D19),
said with the language's templates (dialogue.understanding.replies)."""

from __future__ import annotations

from collections.abc import Callable, Collection, Sequence

from dialogue.reference.clarify import describe_options
from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.grounding import Entity, Kind, Snapshot
from dialogue.reference.lexicon import Lexicon, singular
from dialogue.reference.resolution import ALL_KINDS, content_words, resolve, said_phrase
from dialogue.understanding.inflection import is_plural, plural_of
from dialogue.understanding.language import Language
from dialogue.understanding.questions.placed import held
from dialogue.understanding.replies import (
    MAX_LISTED,
    article,
    capitalised,
    indefinite,
    listing,
    location,
    number,
    say,
    template,
    the,
    told_apart,
)
from dialogue.understanding.speech.plain import split_at

#: What a thing may be on or in.
PLACES: frozenset[Kind] = frozenset({"thing", "zone"})

#: Places described at most in one answer about several ("what is on the shelves").
MAX_PLACES = 3


def what_do_you_see(lang: Language, snapshot: Snapshot, speaker: str = "") -> str:
    you = say(lang, "naming.you")
    seen = [e for e in snapshot.visible() if e.kind == "thing"]
    if len(seen) > MAX_LISTED:
        # A list cut short names what the others are on first: the sofa, not the cardigan on it.
        seen.sort(key=lambda e: not snapshot.placed_at(e.id))
    things = told_apart(lang, seen, snapshot)
    people = [you if e.id == speaker else indefinite(lang, e)
              for e in snapshot.visible() if e.kind == "person"]  # fmt: skip
    if not things and not people:
        return say(lang, "answers.nothing_seen")
    return say(lang, "answers.see", things=listing(lang, [*things, *people]))


def _people(lang: Language, people: Sequence[Entity], speaker: str) -> list[str]:
    you, unknown = say(lang, "naming.you"), say(lang, "naming.someone_unknown")
    return [you if e.id == speaker else e.name if e.labels else unknown for e in people]


def who_do_you_see(lang: Language, snapshot: Snapshot, speaker: str) -> str:
    people = [e for e in snapshot.visible() if e.kind == "person"]
    if not people:
        return say(lang, "answers.no_one_seen")
    return say(lang, "answers.see", things=listing(lang, _people(lang, people, speaker)))


def how_many_people(lang: Language, snapshot: Snapshot, speaker: str) -> str:
    """ "How many people can you see?": the people "who do you see?" names, counted."""
    people = [e for e in snapshot.visible() if e.kind == "person"]
    if not people:
        return say(lang, "answers.no_one_seen")
    noun = say(lang, "answers.person" if len(people) == 1 else "answers.people")
    return say(lang, "answers.count_of", count=number(lang, len(people)), noun=noun,
               things=listing(lang, _people(lang, people, speaker)))


def who_is_in(lexicon: Lexicon, words: Sequence[str], speaker: str) -> tuple[str, bool]:
    """ "Who's at the box office?": the people the KB puts there, else those in the room it is in,
    said as such; and whether the answer is a clarifying question (which office)."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    found = resolve(lexicon, words, frozenset({"zone", "thing"}))
    if found.ambiguous:
        return clarifying_question(lang, snapshot, found.matches), True
    if found.one is None and set(words) & lang.words.determiners:  # "who's in the kitchen", none here
        return say(lang, "sorry.no_place", phrase=" ".join(content_words(lang, words))), False
    if found.one is None:  # "who's in today": no place, who is there
        return who_do_you_see(lang, snapshot, speaker), False
    place = found.one
    # ("who is sitting at the lunch table": whom the KB puts next to it, or by it, too)
    there = [e for e in snapshot.entities.values() if e.kind == "person"
             and (place.id in (e.zone, e.support) or any(r == place.id for _, r in e.relations))]  # fmt: skip
    at = "at" if place.kind == "thing" else "in"
    zone = snapshot.get(place.zone or "") if at == "at" else None
    around = [e for e in snapshot.entities.values() if e.kind == "person" and zone is not None
              and e.zone == zone.id] if not there else []  # fmt: skip
    if around and zone is not None:  # ("who is at the help desk": no one by it, but in its room)
        return say(lang, "answers.people_around", place=the(lang, snapshot, place),
                   zone=the(lang, snapshot, zone), people=listing(lang, _people(lang, around, speaker)),
                   there=_there(lang, around)), False
    if not there:
        return say(lang, f"answers.no_one_{at}", place=the(lang, snapshot, place)), False
    people = listing(lang, _people(lang, there, speaker))
    return say(lang, f"answers.people_{at}", place=the(lang, snapshot, place), people=people,
               there=_there(lang, there)), False


def where_is(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    snapshot, lang = lexicon.snapshot, lexicon.lang
    asked = lang.questions.situation
    if len(words) == 1 and words[0] in (asked.where_me, asked.where_you):
        me = words[0] == asked.where_me
        entity = snapshot.get(speaker if me else snapshot.robot)
        where = location(lang, snapshot, entity) if entity is not None else ""
        if where:
            return say(lang, "answers.you_are" if me else "answers.i_am", where=where)
        return say(lang, "answers.where_you_unknown" if me else "answers.where_i_unknown")
    # ("where's the mug": of two, the one in sight is not the one meant more than the other: both)
    found = resolve(lexicon, words, ALL_KINDS, owner=owner, sight=False)
    phrase = " ".join(content_words(lang, words)) or say(lang, "answers.that")
    if not found.matches:
        return say(lang, "answers.where_unknown", phrase=phrase)
    return " ".join(_where(lexicon, e, speaker) for e in found.matches[:3])


def _where(lexicon: Lexicon, e: Entity, speaker: str) -> str:
    """Where one thing the phrase names is, as a sentence."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    name = the(lang, snapshot, e, speaker, apart=lexicon.shares_name(e))
    where = location(lang, snapshot, e)
    # "the keys are", "Ines is"; a person is "them" when not seen (the KB says no one's gender)
    plural = is_plural(e, lang)
    them = plural or e.kind == "person"
    if e.id == speaker:
        return say(lang, "answers.right_here")
    if where:
        tail = "" if e.seen else say(lang, "answers.unseen_them" if them else "answers.unseen_it")
        key = "answers.are_at" if plural else "answers.is_at"
        return capitalised(say(lang, key, name=name, where=where)) + tail
    if e.seen and e.kind == "person":
        return say(lang, "answers.person_here", name=name)
    if e.seen:
        return say(lang, "answers.seen_them_somewhere" if them else "answers.seen_it_somewhere", name=name)
    return say(lang, "answers.unknown_where_are" if plural else "answers.unknown_where_is", name=name)


def what_is_on(lexicon: Lexicon, words: Sequence[str], asked: str = "") -> tuple[str, bool]:
    """The answer, and whether it is a clarifying question."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    found = resolve(lexicon, words, frozenset({"thing", "zone"}))
    content = content_words(lang, words)
    phrase = " ".join(content) or say(lang, "answers.that")
    if found.ambiguous and _plural(content):  # "what is on the shelves": each of them
        return " ".join(_on(lang, snapshot, place, asked) for place in found.matches[:MAX_PLACES]), False
    if found.ambiguous:
        return clarifying_question(lang, snapshot, found.matches), True
    place = found.one
    if place is None:
        return say(lang, "sorry.unknown", phrase=phrase), False
    return _on(lang, snapshot, place, asked), False


def which_are_on(
    lexicon: Lexicon, kind: Sequence[str], words: Sequence[str], asked: str = ""
) -> tuple[str, bool] | None:
    """ "Which oars are on the rack?": the things of the kind asked about that the KB puts on (or
    in) the place; and whether the answer is a clarifying question (which rack). None when the
    kind names nothing the KB knows: what it asks, the rules cannot tell."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    of_kind = resolve(lexicon, kind, frozenset({"thing"}), sight=False).matches
    if not of_kind:
        return None
    found = resolve(lexicon, words, frozenset({"thing", "zone"}))
    if found.ambiguous:
        return clarifying_question(lang, snapshot, found.matches), True
    if found.one is None:
        phrase = " ".join(content_words(lang, words)) or say(lang, "answers.that")
        return say(lang, "sorry.unknown", phrase=phrase), False
    place = found.one
    there = [e for e in of_kind if held(snapshot, e, place.id)]
    within = place.kind == "zone" or asked in template(lang, "answers.asked_in")
    if not there:
        phrase = " ".join(content_words(lang, kind))
        key = "answers.none_in" if within else "answers.none_on"
        return say(lang, key, phrase=phrase, place=place.name), False
    if {e.id for e in there} <= {e.id for e in snapshot.placed_at(place.id)}:
        return _on(lang, snapshot, place, asked, {e.id for e in there}), False
    # ("which cups are in the clubhouse": on the bar there, each said where)
    things = [f"{n} {location(lang, snapshot, e)}".strip()
              for e, n in zip(there, told_apart(lang, there, snapshot), strict=True)]  # fmt: skip
    key = "answers.things_in" if within else "answers.things_on"
    return say(lang, key, place=place.name, things=listing(lang, things), there=_there(lang, there)), False


def what_is_near(lexicon: Lexicon, words: Sequence[str], relation: Sequence[str]) -> tuple[str, bool]:
    """ "What's next to the window?": the things a spatial fact puts there; and whether the answer
    is a clarifying question (which window)."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    found = resolve(lexicon, words, frozenset({"thing", "zone"}))
    content = content_words(lang, words)
    if found.ambiguous:
        noun = singular(content[-1]) if content else None
        return clarifying_question(lang, snapshot, found.matches, noun), True
    said = " ".join(relation)
    phrase = " ".join(content) or say(lang, "answers.that")
    if found.one is None:
        return say(lang, "sorry.unknown", phrase=phrase), False
    # (the relations of the snapshot, dialogue.reference.facts.RELATIONS, each way of asking names)
    row = lexicon.lang.prepositions.row(relation)
    place, wanted = found.one, row.relations if row is not None else frozenset()
    near = [e for e in snapshot.entities.values()
            if e.kind == "thing" and any(r in wanted and o == place.id for r, o in e.relations)]  # fmt: skip
    there = the(lang, snapshot, place)
    if not near:
        return say(lang, "answers.nothing_related", relation=said, place=there), False
    things = listing(lang, told_apart(lang, near, snapshot))
    return capitalised(say(lang, "answers.related", relation=said, place=there, things=things,
                           there=_there(lang, near))), False


def _there(lang: Language, things: Sequence[Entity]) -> str:
    """ "there is" one thing, "there are" several or one that is many ("the keys")."""
    several = len(things) > 1 or (len(things) == 1 and is_plural(things[0], lang))
    return say(lang, "answers.there_are" if several else "answers.there_is")


def _plural(content: Sequence[str]) -> bool:
    return bool(content) and singular(content[-1]) != content[-1]


def _on(lang: Language, snapshot: Snapshot, place: Entity, asked: str = "",
        only: Collection[str] = ()) -> str:  # fmt: skip
    """What is on (or in) one place, as a sentence: in a zone, on a support, in a container (the
    fridge: what `isIn` it); of the things `only` names when it names any."""
    held = [e for e in snapshot.placed_at(place.id) if e.kind == "thing" and (not only or e.id in only)]
    inside = [e for e in held if e.zone == place.id or ("in", place.id) in e.relations]
    on = [e for e in held if e.support == place.id]
    held_by = (("answers.things_in", inside), ("answers.things_on", on))
    sentences = [say(lang, key, place=place.name, things=listing(lang, told_apart(lang, items)),
                     there=_there(lang, items))
                 for key, items in held_by if items]  # fmt: skip
    if not sentences:
        # as asked: "what's in the box"
        within = place.kind == "zone" or asked in template(lang, "answers.asked_in")
        return say(lang, "answers.nothing_in" if within else "answers.nothing_on", place=place.name)
    return " ".join(sentences)


def can_you_see(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    snapshot, lang = lexicon.snapshot, lexicon.lang
    found = resolve(lexicon, words, ALL_KINDS, owner=owner)
    phrase = said_phrase(lang, words) or say(lang, "answers.that")
    if not found.matches:
        return say(lang, "answers.none_such", phrase=phrase)
    seen = [e for e in found.matches if e.seen]
    if seen:
        described = [f"{indefinite(lang, e)} {location(lang, snapshot, e)}".strip() for e in seen]
        return say(lang, "answers.yes_seen", things=listing(lang, described))
    e = found.matches[0]
    where = location(lang, snapshot, e)
    name = the(lang, snapshot, e, speaker)
    known = say(lang, "answers.last_known", name=name, where=where) if where else ""
    return say(lang, "answers.not_seen", name=name) + known


def what_is(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    snapshot, lang = lexicon.snapshot, lexicon.lang
    found = resolve(lexicon, words, ALL_KINDS, owner=owner)
    phrase = " ".join(content_words(lang, words)) or say(lang, "answers.that")
    if not found.matches:
        return say(lang, "answers.what_unknown", phrase=phrase)
    e = found.matches[0]
    kind = article(lang, e.class_names[0] if e.class_names else say(lang, "naming.thing"))
    where = location(lang, snapshot, e)
    name = the(lang, snapshot, e, speaker)
    if where:
        return capitalised(say(lang, "answers.what_it_is_where", name=name, kind=kind, where=where))
    return capitalised(say(lang, "answers.what_it_is", name=name, kind=kind))


def which_do_you_see(lexicon: Lexicon, words: Sequence[str]) -> str:
    lang = lexicon.lang
    found = resolve(lexicon, words, frozenset({"thing", "person"}))
    seen = [e for e in found.matches if e.seen]
    if not seen:
        phrase = said_phrase(lang, words) or say(lang, "answers.such_thing")
        return say(lang, "answers.none_seen", phrase=phrase)
    snapshot = lexicon.snapshot
    the_ = say(lang, "naming.the", name="")
    coloured = [say(lang, "naming.the_coloured", colour=e.colour, name=n[len(the_) :])
                if e.colour and n.startswith(the_) and e.colour not in n else n
                for e, n in zip(seen, told_apart(lang, seen), strict=True)]  # fmt: skip
    placed = [f"{n} {location(lang, snapshot, e)}".strip() for e, n in zip(seen, coloured, strict=True)]
    return say(lang, "answers.see", things=listing(lang, placed))


def how_many(lexicon: Lexicon, words: Sequence[str]) -> str:
    lang = lexicon.lang
    # ("how many cups are on the bar": the cups there are counted, the bar only says where)
    cut = split_at(words, lang.prepositions.having("asked-on"))
    counted = cut[0] if cut is not None and cut[0] else words
    place = resolve(lexicon, cut[2], PLACES).one if cut is not None and cut[0] else None
    found = resolve(lexicon, words if place is None else counted, frozenset({"thing", "person"}))
    phrase = said_phrase(lang, words) or say(lang, "answers.things")
    seen = [e for e in found.matches if e.seen and (place is None or held(lexicon.snapshot, e, place.id))]
    if not seen:
        return say(lang, "answers.none_seen", phrase=phrase)
    count = number(lang, len(seen))
    content = content_words(lang, counted)
    options = describe_options(lang, lexicon.snapshot, seen) if len(seen) > 1 and content else []
    if options and not any(e.id in o for e, o in zip(seen, options, strict=True)):
        # several of the kind asked about, each as a person tells it apart: "the blue one"
        noun = plural_of(" ".join([*content[:-1], singular(content[-1])]))  # "watering cans"
        return say(lang, "answers.count_of", count=count, noun=noun, things=listing(lang, options))
    things = listing(lang, told_apart(lang, seen, lexicon.snapshot))
    return say(lang, "answers.count", count=count, things=things)


def colour_of(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    lang = lexicon.lang

    def sentence(e: Entity, several: bool) -> str:
        if e.colour:
            key = "answers.colour_one" if several else "answers.colour_the"
            return say(lang, key, name=e.name, colour=e.colour)
        return say(lang, "answers.colour_unknown", name=the(lang, lexicon.snapshot, e, speaker))

    return _about_each_thing(lexicon, words, sentence, owner)


def whose(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    """ "Whose phone is on the bookcase?": the owner (`belongsTo`) of each thing the phrase names."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    the_ = say(lang, "naming.the", name="")

    def sentence(e: Entity, several: bool) -> str:
        name = the(lang, snapshot, e, speaker)
        if several and e.colour and e.colour not in name and name.startswith(the_):
            # "which suitcase is mine": the red one
            name = say(lang, "naming.the_coloured", colour=e.colour, name=name[len(the_) :])
        plural = is_plural(e, lang)
        held = snapshot.get(e.owner) if e.owner else None
        where = location(lang, snapshot, e) if several else ""
        named = f"{name}{' ' + where if where else ''}"
        if held is None:
            return say(lang, "answers.owners_unknown" if plural else "answers.owner_unknown", name=named)
        owner_name = the(lang, snapshot, held, speaker)
        yours = held.id == speaker
        whom = say(lang, "answers.yours") if yours else say(lang, "answers.whose", name=owner_name)
        key = "answers.owner_are" if plural else "answers.owner_is"
        return capitalised(say(lang, key, name=named, owner=whom))

    return _about_each_thing(lexicon, words, sentence, owner)


def _about_each_thing(lexicon: Lexicon, words: Sequence[str], sentence: Callable[[Entity, bool], str],
                      owner: str | None = None) -> str:
    """One sentence about each of (at most three) things the phrase names (`owner`'s when the
    phrase says whose: "my mug"); `sentence` is told whether there are several, to tell them apart."""
    lang = lexicon.lang
    found = resolve(lexicon, words, frozenset({"thing"}), owner=owner)
    if not found.matches:
        phrase = " ".join(content_words(lang, words)) or say(lang, "answers.such_thing")
        return say(lang, "sorry.unknown", phrase=phrase)
    several = len(found.matches) > 1
    return " ".join(sentence(e, several) for e in found.matches[:3])
