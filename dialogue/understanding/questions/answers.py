"""Verbal answers to questions about the situation, computed from the snapshot (no intent, D19)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence

from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.english import SPOKEN_NUMBERS, tokens
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.lexicon import Lexicon, singular
from dialogue.reference.resolution import ALL_KINDS, content_words, resolve, said_phrase
from dialogue.situation import article

MAX_LISTED = 12
#: Numbers said in words ("nine"), which end a name of its own ("gate nine").
SPOKEN_WORDS = frozenset(w for words in SPOKEN_NUMBERS.values() for w in words) - {"zero"}
#: Places described at most in one answer about several ("what is on the shelves").
MAX_PLACES = 3


def the(snapshot: Snapshot, entity: Entity, speaker: str = "") -> str:
    """How to name an entity in a sentence: "you", "Maria", "the cookbook", "the cup"."""
    if entity.id == speaker:
        return "you"
    if entity.kind == "person":
        return entity.name if entity.labels else "a person"
    if entity.colour and not entity.labels and entity.colour not in entity.name:
        return f"the {entity.colour} {entity.name}"
    if entity.labels and _numbered(entity.name):
        return entity.name  # "screen 2", "gate nine": a name of its own, said without "the"
    return f"the {entity.name}"


def _numbered(name: str) -> bool:
    """Whether a name ends with its number ("screen 2", "table four")."""
    words = tokens(name)
    return len(words) > 1 and (words[-1].isdigit() or words[-1] in SPOKEN_WORDS)


def indefinite(entity: Entity) -> str:
    if entity.kind == "person":
        return entity.name if entity.labels else "a person"
    if entity.labels:
        return f"the {entity.labels[0]}"
    return article(entity.class_names[0] if entity.class_names else "thing")


def listing(items: Sequence[str]) -> str:
    counts = Counter(items)
    parts: list[str] = []
    for item, n in counts.items():
        if n > 1 and item.startswith(("a ", "an ")):
            parts.append(f"{_number(n)} {item.split(' ', 1)[1]}s")
        else:
            parts.append(item)
    if len(parts) > MAX_LISTED:
        parts = [*parts[:MAX_LISTED], f"{len(parts) - MAX_LISTED} more things"]
    if len(parts) == 1:
        return parts[0]
    return ", ".join(parts[:-1]) + " and " + parts[-1]


def _number(n: int) -> str:
    words = ["zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten"]
    return words[n] if n < len(words) else str(n)


def location(snapshot: Snapshot, entity: Entity) -> str:
    parts = []
    if entity.support:
        parts.append(f"on the {snapshot.name_of(entity.support)}")
    parts.extend(f"{prep} the {snapshot.name_of(other)}" for prep, other in entity.relations[:2])
    if entity.zone:
        parts.append(f"in the {snapshot.name_of(entity.zone)}")
    return " ".join(parts)


def what_do_you_see(snapshot: Snapshot, speaker: str = "") -> str:
    things = [indefinite(e) for e in snapshot.visible() if e.kind == "thing"]
    people = ["you" if e.id == speaker else indefinite(e) for e in snapshot.visible() if e.kind == "person"]
    if not things and not people:
        return "I don't see anything I know right now."
    return f"I see {listing([*things, *people])}."


def who_do_you_see(snapshot: Snapshot, speaker: str) -> str:
    people = [e for e in snapshot.visible() if e.kind == "person"]
    if not people:
        return "I don't see anyone right now."
    names = ["you" if e.id == speaker else e.name if e.labels else "someone I don't know" for e in people]
    return f"I see {listing(names)}."


def who_is_in(lexicon: Lexicon, words: Sequence[str], speaker: str) -> tuple[str, bool]:
    """ "Who's at the box office?": the people the KB puts there; and whether the answer is a
    clarifying question (which office)."""
    snapshot = lexicon.snapshot
    found = resolve(lexicon, words, frozenset({"zone", "thing"}))
    if found.ambiguous:
        return clarifying_question(snapshot, found.matches), True
    if found.one is None:  # "who's in today": no place, who is there
        return who_do_you_see(snapshot, speaker), False
    place = found.one
    there = [e for e in snapshot.entities.values()
             if e.kind == "person" and place.id in (e.zone, e.support)]  # fmt: skip
    if not there:
        return f"I don't know of anyone in {the(snapshot, place)}.", False
    names = ["you" if e.id == speaker else e.name if e.labels else "someone I don't know" for e in there]
    return f"In {the(snapshot, place)}, there is {listing(names)}.", False


def where_is(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    snapshot = lexicon.snapshot
    if tuple(words) in {("me",), ("you",)}:
        me = words[0] == "me"
        entity = snapshot.get(speaker if me else snapshot.robot)
        where = location(snapshot, entity) if entity is not None else ""
        if where:
            return f"{'You are' if me else 'I am'} {where}."
        return f"Sorry, I don't know where {'you are' if me else 'I am'}."
    found = resolve(lexicon, words, ALL_KINDS, owner=owner)
    phrase = " ".join(content_words(lexicon.lang, words)) or "that"
    if not found.matches:
        return f"Sorry, I don't know where the {phrase} is: I don't know any {phrase}."
    sentences = []
    for e in found.matches[:3]:
        name = the(snapshot, e, speaker)
        where = location(snapshot, e)
        if e.id == speaker:
            sentences.append("You are right here, talking to me.")
        elif where:
            plural = _plural(tokens(name))  # "the keys are", "I don't see them"
            tail = "" if e.seen else f" I don't see {'them' if plural else 'it'} right now."
            sentences.append(f"{name[:1].upper()}{name[1:]} {'are' if plural else 'is'} {where}.{tail}")
        elif e.seen and e.kind == "person":
            sentences.append(f"{name} is here, I can see {name}.")
        elif e.seen:
            where_it = "where they are" if _plural(tokens(name)) else "where it is"
            sentences.append(f"I can see {name}, but I don't know exactly {where_it}.")
        else:
            verb = "are" if _plural(tokens(name)) else "is"
            sentences.append(f"I don't know where {name} {verb} right now.")
    return " ".join(sentences)


def what_is_on(lexicon: Lexicon, words: Sequence[str], asked: str = "") -> tuple[str, bool]:
    """The answer, and whether it is a clarifying question."""
    snapshot = lexicon.snapshot
    found = resolve(lexicon, words, frozenset({"thing", "zone"}))
    content = content_words(lexicon.lang, words)
    phrase = " ".join(content) or "that"
    if found.ambiguous and _plural(content):  # "what is on the shelves": each of them
        return " ".join(_on(snapshot, place, asked) for place in found.matches[:MAX_PLACES]), False
    if found.ambiguous:
        return clarifying_question(snapshot, found.matches), True
    place = found.one
    if place is None:
        return f"Sorry, I don't know any {phrase}.", False
    return _on(snapshot, place, asked), False


def what_is_near(lexicon: Lexicon, words: Sequence[str], relation: Sequence[str]) -> tuple[str, bool]:
    """ "What's next to the window?": the things a spatial fact puts there; and whether the answer
    is a clarifying question (which window)."""
    snapshot = lexicon.snapshot
    found = resolve(lexicon, words, frozenset({"thing", "zone"}))
    content = content_words(lexicon.lang, words)
    if found.ambiguous:
        return clarifying_question(snapshot, found.matches, singular(content[-1]) if content else None), True
    said = " ".join(relation)
    phrase = " ".join(content) or "that"
    if found.one is None:
        return f"Sorry, I don't know any {phrase}.", False
    # (the relations of the snapshot, dialogue.reference.facts.RELATIONS, each way of asking names)
    row = lexicon.lang.prepositions.row(relation)
    place, wanted = found.one, row.relations if row is not None else frozenset()
    near = [e for e in snapshot.entities.values()
            if e.kind == "thing" and any(r in wanted and o == place.id for r, o in e.relations)]  # fmt: skip
    if not near:
        return f"I don't know of anything {said} {the(snapshot, place)}.", False
    things = listing(told_apart(near, snapshot))
    return f"{said[:1].upper()}{said[1:]} {the(snapshot, place)}, there is {things}.", False


def _plural(content: Sequence[str]) -> bool:
    return bool(content) and singular(content[-1]) != content[-1]


def _on(snapshot: Snapshot, place: Entity, asked: str = "") -> str:
    """What is on (or in) one place, as a sentence: in a zone, on a support, in a container (the
    fridge: what `isIn` it)."""
    held = [e for e in snapshot.placed_at(place.id) if e.kind == "thing"]
    inside = told_apart([e for e in held if e.zone == place.id or ("in", place.id) in e.relations])
    on = told_apart([e for e in held if e.support == place.id])
    sentences = [f"{prep} the {place.name}, there is {listing(items)}."
                 for prep, items in (("In", inside), ("On", on)) if items]  # fmt: skip
    if not sentences:
        # as asked: "what's in the box"
        prep = "in" if place.kind == "zone" or asked in {"in", "inside"} else "on"
        return f"I don't know of anything {prep} the {place.name}."
    return " ".join(sentences)


def can_you_see(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    snapshot = lexicon.snapshot
    found = resolve(lexicon, words, ALL_KINDS, owner=owner)
    phrase = said_phrase(lexicon.lang, words) or "that"
    if not found.matches:
        return f"No, I don't see any {phrase}."
    seen = [e for e in found.matches if e.seen]
    if seen:
        described = [f"{indefinite(e)} {location(snapshot, e)}".strip() for e in seen]
        return f"Yes, I see {listing(described)}."
    e = found.matches[0]
    where = location(snapshot, e)
    known = f" The last I know, {the(snapshot, e, speaker)} is {where}." if where else ""
    return f"No, I don't see {the(snapshot, e, speaker)} right now.{known}"


def what_is(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    snapshot = lexicon.snapshot
    found = resolve(lexicon, words, ALL_KINDS, owner=owner)
    phrase = " ".join(content_words(lexicon.lang, words)) or "that"
    if not found.matches:
        return f"Sorry, I don't know what {phrase} is."
    e = found.matches[0]
    kind = e.class_names[0] if e.class_names else "thing"
    where = location(snapshot, e)
    name = the(snapshot, e, speaker)
    return f"{name[:1].upper()}{name[1:]} is {article(kind)}{', ' + where if where else ''}."


def which_do_you_see(lexicon: Lexicon, words: Sequence[str]) -> str:
    found = resolve(lexicon, words, frozenset({"thing", "person"}))
    seen = [e for e in found.matches if e.seen]
    if not seen:
        return f"I don't see any {said_phrase(lexicon.lang, words) or 'such thing'}."
    snapshot = lexicon.snapshot
    coloured = [f"the {e.colour} {n[4:]}" if e.colour and n.startswith("the ") and e.colour not in n else n
                for e, n in zip(seen, told_apart(seen), strict=True)]  # fmt: skip
    placed = [f"{n} {location(snapshot, e)}".strip() for e, n in zip(seen, coloured, strict=True)]
    return f"I see {listing(placed)}."


def how_many(lexicon: Lexicon, words: Sequence[str]) -> str:
    found = resolve(lexicon, words, frozenset({"thing", "person"}))
    phrase = said_phrase(lexicon.lang, words) or "things"
    seen = [e for e in found.matches if e.seen]
    if not seen:
        return f"I don't see any {phrase}."
    return f"I see {_number(len(seen))}: {listing(told_apart(seen, lexicon.snapshot))}."


def told_apart(entities: Sequence[Entity], snapshot: Snapshot | None = None) -> list[str]:
    """Each entity as a listing names it; one that shares its name by its colour ("the red marker"),
    else, given the snapshot, by whose it is ("Harold's spade") or where it is ("the spade in the
    shed")."""
    names = [indefinite(e) for e in entities]
    shared = {n for n in names if names.count(n) > 1}
    return [_apart(e, n, snapshot) if n in shared and n.startswith("the ") else n
            for e, n in zip(entities, names, strict=True)]  # fmt: skip


def _apart(entity: Entity, name: str, snapshot: Snapshot | None) -> str:
    if entity.colour:
        return f"the {entity.colour} {name[4:]}"
    owner = snapshot.get(entity.owner) if snapshot is not None and entity.owner else None
    if owner is not None and owner.labels:
        return f"{owner.name}'s {name[4:]}"
    where = location(snapshot, entity) if snapshot is not None else ""
    return f"{name} {where}" if where else name


def colour_of(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    def sentence(e: Entity, several: bool) -> str:
        if e.colour:
            return f"{'One' if several else 'The'} {e.name} is {e.colour}."
        return f"I don't know the colour of {the(lexicon.snapshot, e, speaker)}."

    return _about_each_thing(lexicon, words, sentence, owner)


def whose(lexicon: Lexicon, words: Sequence[str], speaker: str, owner: str | None = None) -> str:
    """ "Whose phone is on the bookcase?": the owner (`belongsTo`) of each thing the phrase names."""
    snapshot = lexicon.snapshot

    def sentence(e: Entity, several: bool) -> str:
        name = the(snapshot, e, speaker)
        if several and e.colour and e.colour not in name and name.startswith("the "):
            name = f"the {e.colour} {name[4:]}"  # "which suitcase is mine": the red one
        plural = _plural(tokens(name))
        held = snapshot.get(e.owner) if e.owner else None
        where = location(snapshot, e) if several else ""
        named = f"{name}{' ' + where if where else ''}"
        if held is None:
            return f"I don't know who {named} {'belong' if plural else 'belongs'} to."
        whom = "yours" if held.id == speaker else f"{the(snapshot, held, speaker)}'s"
        return f"{named[:1].upper()}{named[1:]} {'are' if plural else 'is'} {whom}."

    return _about_each_thing(lexicon, words, sentence, owner)


def _about_each_thing(lexicon: Lexicon, words: Sequence[str], sentence: Callable[[Entity, bool], str],
                      owner: str | None = None) -> str:
    """One sentence about each of (at most three) things the phrase names (`owner`'s when the
    phrase says whose: "my mug"); `sentence` is told whether there are several, to tell them apart."""
    found = resolve(lexicon, words, frozenset({"thing"}), owner=owner)
    if not found.matches:
        return f"Sorry, I don't know any {' '.join(content_words(lexicon.lang, words)) or 'such thing'}."
    several = len(found.matches) > 1
    return " ".join(sentence(e, several) for e in found.matches[:3])
