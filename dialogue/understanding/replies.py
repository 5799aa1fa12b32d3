"""What the robot says: every reply of the offline understanding is a template of the language's
`replies.toml`, rendered here. The readers decide which sentence and with what; the words are the
language's.

Besides `say` (a template, its slots filled), the naming every reply shares: how an entity is named
in a sentence ("you", "Maria", "the cookbook", "screen 2"), a list of names ("two cups, a plate and
Ana"), where a thing is ("on the table in the kitchen"), and how an intent taken on is said back
(`acknowledgement`).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from dialogue import intents as I
from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.understanding.language import Language, LanguageError
from dialogue.understanding.outcome import Ref

#: At most this many names in a list (the rest are counted: "3 more things").
MAX_LISTED = 12


def template(lang: Language, key: str) -> Any:
    """The language's template for `key` ("request.grab"), or its list or table ("naming.ok")."""
    section, _, name = key.partition(".")
    found = lang.replies.get(section, {}).get(name) if name else None
    if found is None:
        raise LanguageError(f"{lang.code}/replies.toml: no template {key!r}")
    return found


def say(lang: Language, key: str, **slots: object) -> str:
    """The language's sentence for `key`, its slots filled."""
    return str(template(lang, key)).format(**slots)


def capitalised(text: str) -> str:
    """The text with its first letter in capitals ("the keys are..." -> "The keys are...")."""
    return text[:1].upper() + text[1:]


def the(lang: Language, snapshot: Snapshot, entity: Entity, speaker: str = "", apart: bool = False) -> str:
    """How to name an entity in a sentence: "you", "Maria", "the cookbook", "the cup"; `apart`: a
    thing that shares its name with others, as a person tells it from them ("the red mug",
    "Harold's spade", "the spade in the shed")."""
    if apart and entity.kind == "thing" and entity.id != speaker:
        return _apart(lang, entity, the(lang, snapshot, entity, speaker), snapshot, speaker)
    if entity.id == speaker:
        return say(lang, "naming.you")
    if entity.kind == "person":
        return entity.name if entity.labels else say(lang, "naming.a_person")
    if entity.colour and not entity.labels and entity.colour not in entity.name:
        return say(lang, "naming.the_coloured", colour=entity.colour, name=entity.name)
    if entity.labels and (_numbered(lang, entity.name) or _possessive(entity.name)):
        # "screen 2", "gate nine", "Walter's armchair": a name of its own, said without "the"
        return entity.name
    return say(lang, "naming.the", name=entity.name)


def _possessive(name: str) -> bool:
    """Whether a name starts with someone's ("Walter's armchair"): it takes no article."""
    first = name.partition(" ")[0]
    return first[:1].isupper() and first.endswith(("'s", "\u2019s"))


def _numbered(lang: Language, name: str) -> bool:
    """Whether a name ends with its number ("screen 2", "table four"; not "the key card for room
    309", whose number is another thing's)."""
    words = tokens(name)
    spoken = {w for said in lang.words.spoken_numbers.values() for w in said} - set(lang.words.units[:1])
    if set(words[:-1]) & lang.words.any_function_word:
        return False
    return len(words) > 1 and (words[-1].isdigit() or words[-1] in spoken)


def article(lang: Language, noun: str) -> str:
    """A noun with its indefinite article ("a cup", "an apple")."""
    vowel = noun[:1].lower() in str(template(lang, "naming.vowels"))
    return say(lang, "naming.an" if vowel else "naming.a", noun=noun)


def indefinite(lang: Language, entity: Entity) -> str:
    if entity.kind == "person":
        return entity.name if entity.labels else say(lang, "naming.a_person")
    if entity.labels:
        return say(lang, "naming.the", name=entity.labels[0])
    return article(lang, entity.class_names[0] if entity.class_names else say(lang, "naming.thing"))


def number(lang: Language, n: int) -> str:
    """A count said in words up to ten ("two"), else in digits."""
    words = lang.words.units[:11]
    return words[n] if n < len(words) else str(n)


def listing(lang: Language, items: Sequence[str]) -> str:
    counts = Counter(items)
    counted = tuple(template(lang, "naming.counted"))
    parts: list[str] = []
    for item, n in counts.items():
        if n > 1 and item.startswith(counted):
            parts.append(say(lang, "naming.several", count=number(lang, n), name=item.split(" ", 1)[1]))
        else:
            parts.append(item)
    if len(parts) > MAX_LISTED:
        parts = [*parts[:MAX_LISTED], say(lang, "naming.more", count=len(parts) - MAX_LISTED)]
    if len(parts) == 1:
        return parts[0]
    return say(lang, "naming.separator").join(parts[:-1]) + say(lang, "naming.last_separator") + parts[-1]


def location(lang: Language, snapshot: Snapshot, entity: Entity) -> str:
    parts = []
    if entity.support:
        parts.append(say(lang, "naming.on", place=snapshot.name_of(entity.support)))
    parts.extend(say(lang, "naming.related", preposition=prep, place=_beside(lang, snapshot, entity, other))
                 for prep, other in entity.relations[:2])  # fmt: skip
    if entity.zone:
        parts.append(say(lang, "naming.in", place=snapshot.name_of(entity.zone)))
    return " ".join(parts)


def _beside(lang: Language, snapshot: Snapshot, entity: Entity, other: str) -> str:
    """The thing another is placed by, told from it by its colour when they share a name ("the
    yellow torch is to the right of the black torch")."""
    found = snapshot.get(other)
    if found is None or found.name != entity.name or not found.colour or found.colour in found.name:
        return snapshot.name_of(other)
    return say(lang, "naming.coloured", colour=found.colour, name=found.name)


def told_apart(lang: Language, entities: Sequence[Entity], snapshot: Snapshot | None = None) -> list[str]:
    """Each entity as a listing names it; one that shares its name by its colour ("the red marker"),
    else, given the snapshot, by whose it is ("Harold's spade") or where it is ("the spade in the
    shed")."""
    names = [indefinite(lang, e) for e in entities]
    shared = {n for n in names if names.count(n) > 1}
    the_ = say(lang, "naming.the", name="")
    return [_apart(lang, e, n, snapshot) if n in shared and n.startswith(the_) else n
            for e, n in zip(entities, names, strict=True)]  # fmt: skip


def _apart(lang: Language, entity: Entity, name: str, snapshot: Snapshot | None, speaker: str = "") -> str:
    the_ = say(lang, "naming.the", name="")
    if not name.startswith(the_):
        return name  # "screen 2": a name of its own
    bare = name[len(the_) :]
    if entity.colour and entity.colour in tokens(bare):
        return name  # "the black phone": told apart already
    if entity.colour:
        return say(lang, "naming.the_coloured", colour=entity.colour, name=bare)
    if speaker and entity.owner == speaker:
        return say(lang, "naming.yours", name=bare)
    owner = snapshot.get(entity.owner) if snapshot is not None and entity.owner else None
    if owner is not None and owner.labels:
        return say(lang, "naming.owned", owner=owner.name, name=bare)
    where = location(lang, snapshot, entity) if snapshot is not None else ""
    return f"{name} {where}" if where else name


def hello(lang: Language, snapshot: Snapshot, speaker: str) -> str:
    """A greeting, by name for a speaker the KB knows by name ("Hello Alice!")."""
    me = snapshot.get(speaker)
    if me is not None and me.labels:
        return say(lang, "social.hello_you", name=me.name)
    return say(lang, "social.hello")


def said_back(lang: Language, words: Words) -> str:
    """The speaker's words (as written: `Said.written`) as the robot says them back to the speaker
    ("tell me where my keys are" -> "tell you where your keys are")."""
    back: dict[str, str] = template(lang, "naming.back")
    return " ".join(back.get(w.lower(), w) for w in words)


def whose_it_is(lang: Language, snapshot: Snapshot, entity: Entity, speaker: str) -> str:
    """What the KB says of whose a thing called the speaker's is: another's ("The book is Marcus's,
    not yours."), or nobody's ("As far as I know, the diary is nobody's.")."""
    name = the(lang, snapshot, entity, speaker)
    owner = snapshot.get(entity.owner) if entity.owner else None
    if owner is None:
        return say(lang, "naming.nobodys", name=name)
    return capitalised(say(lang, "naming.not_yours", name=name, owner=the(lang, snapshot, owner, speaker)))


def goodbye(lang: Language, snapshot: Snapshot, speaker: str) -> str:
    """A farewell, by name for a speaker the KB knows by name ("Goodbye Alice, see you soon!")."""
    me = snapshot.get(speaker)
    if me is not None and me.labels:
        return say(lang, "social.goodbye_you", name=me.name)
    return say(lang, "social.goodbye")


def abilities(lang: Language) -> str:
    """What the robot can do: each intent of the catalogue it acts on, as the language says it."""
    said = template(lang, "abilities.intents")
    can = [str(said[intent]) for intent in I.CATALOGUE if intent in said]
    return say(lang, "abilities.can", abilities=listing(lang, can))


def unprefixed(lang: Language, reply: str) -> str:
    """A later part of a compound reply: "OK, I will pick up the plate." -> "I will pick up the
    plate." (one without the "OK" capitalised)."""
    rest = reply
    for prefix in template(lang, "naming.ok"):
        rest = rest.removeprefix(prefix)
    return capitalised(rest) if rest == reply else rest


def then(lang: Language, replies: Sequence[str]) -> str:
    """The replies of a compound request in one: the first, then each later one."""
    return " ".join([replies[0], *(say(lang, "naming.then", reply=unprefixed(lang, r)) for r in replies[1:])])


def _name(lang: Language, snapshot: Snapshot, speaker: str, ref: Ref | None,
          namesakes: Callable[[Entity], bool]) -> str:  # fmt: skip
    if ref is None:
        return say(lang, "naming.it")
    if ref.speaker:
        return say(lang, "naming.you")
    if ref.entity is None:
        return say(lang, "naming.it")
    return the(lang, snapshot, ref.entity, speaker, apart=namesakes(ref.entity))


@dataclass(frozen=True)
class _Taken:
    """An intent taken on, as it is said back: its roles named, its free text, how a place was said."""

    lang: Language
    obj: str
    rec: str
    goal: str
    text: str
    refs: dict[str, Ref]
    said: str | None

    def say(self, key: str, **slots: object) -> str:
        return say(self.lang, key, **slots)

    @property
    def you(self) -> str:
        return self.say("naming.you")


def _start(t: _Taken) -> str:
    """An activity of the language's own words ("OK, I will follow you."), else by its name."""
    own = template(t.lang, "request.activities").get(t.text)
    return str(own).format(recipient=t.rec) if own is not None else t.say("request.start", activity=t.text)


def _place(t: _Taken) -> str:
    obj = t.obj if "object" in t.refs else t.say("naming.it")
    return t.say("request.place", object=obj, preposition=_put(t.lang, t.refs.get("recipient"), t.said),
                 recipient=t.rec)  # fmt: skip


def _motion(t: _Taken) -> str:
    if "recipient" not in t.refs:
        return t.say("request.motion", motion=t.text)
    towards = template(t.lang, "request.towards").get(t.text, t.say("request.motion_for"))
    return t.say("request.motion_to", motion=t.text, preposition=towards, recipient=t.rec)


#: How each intent is said back.
_SAID_BACK: dict[str, Callable[[_Taken], str]] = {
    I.GRAB_OBJECT: lambda t: t.say("request.grab", object=t.obj),
    I.BRING_OBJECT: lambda t: t.say("request.bring", object=t.obj, recipient=t.rec),
    I.PLACE_OBJECT: _place,
    I.MOVE_TO: lambda t: t.say("request.coming") if t.goal == t.you else t.say("request.going", goal=t.goal),
    I.GUIDE: lambda t: (t.say("request.take_you", goal=t.goal) if t.rec == t.you
                        else t.say("request.guide", recipient=t.rec, goal=t.goal)),
    I.GREET: lambda t: t.say("request.greet", recipient=t.rec),
    I.SAY: lambda t: (t.say("request.tell", recipient=t.rec, text=t.text) if "recipient" in t.refs
                      else t.say("request.say", text=t.text)),
    I.ENGAGE_WITH: lambda t: (t.say("request.engage_you") if t.rec == t.you
                              else t.say("request.engage", recipient=t.rec)),
    I.PERFORM_MOTION: _motion,
    I.START_ACTIVITY: lambda t: _start(t),
    I.STOP_ACTIVITY: lambda t: t.say("request.stop_it", activity=t.text) if t.text else t.say("request.stop"),
    I.WAKEUP: lambda t: t.say("request.wake"),
    I.SUSPEND: lambda t: t.say("request.sleep"),
}  # fmt: skip


def acknowledgement(lang: Language, snapshot: Snapshot, speaker: str, intent: str, roles: dict[str, str],
                    refs: dict[str, Ref], said: str | None = None,
                    namesakes: Callable[[Entity], bool] = lambda _e: False) -> str:  # fmt: skip
    """What the robot says when it takes on an intent ("OK, I will bring the red mug to you."); `said`
    is the preposition the person put the place with, if any; `namesakes` says which things share
    their name with others (told apart as they are named)."""
    obj, rec, goal = (_name(lang, snapshot, speaker, refs.get(r), namesakes)
                      for r in ("object", "recipient", "goal"))  # fmt: skip
    taken = _Taken(lang, obj, rec, goal, roles.get("object", "").replace("_", " "), refs, said)
    said_back = _SAID_BACK.get(intent)
    return said_back(taken) if said_back is not None else say(lang, "request.done")


def _put(lang: Language, ref: Ref | None, said: str | None) -> str:
    """The preposition a place is said back with: the one it was said with ("next to the laptop"),
    else in a zone, on a thing."""
    zone = ref is not None and ref.entity is not None and ref.entity.kind == "zone"
    back = lang.prepositions.column("said_back")
    return str(back.get(said or "", say(lang, "request.in_zone" if zone else "request.on_thing")))
