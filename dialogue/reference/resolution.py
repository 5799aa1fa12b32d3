"""Referent resolution: a noun phrase (or an id an LLM gave) to exactly one KB entity, none, or several.

A phrase matches an entity when one of the entity's names occurs in it and every other content word
qualifies the entity: a word of its labels or class names ("red" for the "red cup"), its colour
(`hasColor white`), a name of its support or zone ("the cup on the table", "the kitchen table"), or
of its owner ("Ines's phone", `belongsTo`). When the caller knows whose thing is meant ("my phone"),
that person's things are preferred; visible entities are preferred to unseen ones, but for a thing
to fetch (`sight=False`) only among more than a clarifying question can list (of two towels, the
one in sight is not "the towel" to bring: which is asked).
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass

from dialogue import intents as I
from dialogue.reference.clarify import MAX_OPTIONS
from dialogue.reference.english import tokens
from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.headnoun import resolve_head
from dialogue.reference.lexicon import Lexicon, norm
from dialogue.reference.naming import phrase as name_words
from dialogue.reference.unnamed import by_label_words, by_qualifiers, compared, thing_held, thing_measured
from dialogue.understanding.language import Language

#: The ontology's class of what a bottle, a can or a packet holds.
FOOD_OR_DRINK = "cyc:FoodOrDrink"

#: Up to this many entities named by a phrase's words, all are looked at (no sight-first shortcut).
FEW_NAMED = 64

ALL_KINDS: frozenset[Kind] = frozenset({"person", "zone", "robot", "thing"})

PERSON: frozenset[Kind] = frozenset({"person"})
THING: frozenset[Kind] = frozenset({"thing"})
ZONE: frozenset[Kind] = frozenset({"zone"})
PLACE: frozenset[Kind] = frozenset({"zone", "thing"})
ANYWHERE: frozenset[Kind] = frozenset({"person", "zone", "thing"})

#: Which kinds of entity may fill each grounded role, per intent.
ROLE_KINDS: dict[str, dict[str, frozenset[Kind]]] = {
    I.GRAB_OBJECT: {"object": THING},
    I.BRING_OBJECT: {"object": THING, "recipient": ANYWHERE},
    I.PLACE_OBJECT: {"object": THING, "recipient": PLACE},
    I.MOVE_TO: {"goal": ANYWHERE},
    I.GUIDE: {"recipient": PERSON, "goal": PLACE},
    I.GREET: {"recipient": PERSON},
    I.ENGAGE_WITH: {"recipient": PERSON},
    I.SAY: {"recipient": PERSON},
    I.PERFORM_MOTION: {"recipient": PERSON},
    I.PRESENT_CONTENT: {"recipient": PERSON},
    I.START_ACTIVITY: {"recipient": PERSON},
}


@dataclass(frozen=True)
class Resolution:
    phrase: str
    matches: tuple[Entity, ...]

    @property
    def one(self) -> Entity | None:
        return self.matches[0] if len(self.matches) == 1 else None

    @property
    def ambiguous(self) -> bool:
        return len(self.matches) > 1


def content_words(lang: Language, words: Sequence[str]) -> list[str]:
    glue = lang.glue
    return [w for i, w in enumerate(words) if not _glue(glue, words, i)]


def _glue(glue: frozenset[str], words: Sequence[str], i: int) -> bool:
    """Whether the i-th word qualifies nothing: "top" only in "on top of" ("the top shelf" is one)."""
    if words[i] == "top":
        return tuple(words[i + 1 : i + 2]) == ("of",)
    return words[i] in glue


def said_phrase(lang: Language, words: Sequence[str]) -> str:
    """A phrase as a reply says it back: without its leading determiners, its prepositions kept
    ("my mug in the fridge": "mug in the fridge")."""
    glue = lang.glue
    leading = lang.words.determiners | glue | lang.words.unsaid_possessives
    out = [w for w in words if w != "please"]
    while out and out[0] in leading:
        out.pop(0)
    while out and out[-1] in glue:
        out.pop()
    return " ".join(out)


def is_pronoun(lang: Language, words: Sequence[str]) -> bool:
    content = [w for w in words if w not in lang.words.not_said - {"over"}]
    return len(content) == 1 and content[0] in lang.words.pronouns


def resolve(
    lexicon: Lexicon,
    words: Sequence[str],
    kinds: Collection[Kind] = ALL_KINDS,
    *,
    owner: str | None = None,
    sight: bool = True,
) -> Resolution:
    """Entities of the given kinds that the phrase names (see the module docstring); with `sight`
    False, the things in sight are not preferred among a few (a thing to fetch: which is asked).
    Read once per snapshot (`Lexicon.analysed`): the requests' reader asks of the same phrase
    whether it is a person, a place and a thing, and the answer grounding asks again."""
    key = (resolve, tuple(words), frozenset(kinds), owner, sight)
    return lexicon.analysed(key, lambda: _resolve(lexicon, words, kinds, owner, sight), _weight)


def _weight(resolution: Resolution) -> int:
    return 1 + len(resolution.matches)


@dataclass(slots=True)
class _Read:
    """A phrase as resolution reads it (once): its words ("ines's" as "ines"), their normalised and
    compared forms ("bigger": big), where its content words are, and the KB's names found in it."""

    lexicon: Lexicon
    kinds: Collection[Kind]
    phrase: str
    words: list[str]
    normed: Sequence[str]
    bases: list[str]
    content: list[int]
    #: entity -> the word positions its names span
    cover: dict[str, frozenset[int]]
    #: entities a name of the KB's own (not the lexicon file's) occurs for
    own_name: set[str]
    #: entity -> the sources of its names that are all the words said
    whole: dict[str, set[str]]
    head: int | None
    #: Where the phrase's core ends: at its first locative ("the ones on the bench").
    core_end: int


def _resolve(
    lexicon: Lexicon, words: Sequence[str], kinds: Collection[Kind], owner: str | None, sight: bool
) -> Resolution:
    """The sieves in order: the things whose names the words say, narrowed to those named most
    closely; else what the words say otherwise (label words, qualifiers, a head noun, a measure or
    a container's contents); then the preferred among them."""
    r = _read(lexicon, words, kinds)
    matches = _narrowed(r, _candidates(r, owner, sight))
    matches = _otherwise(r, matches, owner)
    return _preferred(r, matches, owner, sight)


def _read(lexicon: Lexicon, said: Sequence[str], kinds: Collection[Kind]) -> _Read:
    lang = lexicon.lang
    words = [w[:-2] if w.endswith("'s") and len(w) > 2 else w for w in said]  # "ines's" names Ines
    normed = norm(words)
    content = [i for i in range(len(words)) if not _glue(lang.glue, words, i)]
    cover, own_name, whole = _covered(lexicon, words, frozenset(content))
    # "the ones on the bench": no noun before the preposition, and never the bench itself ("one of
    # the baskets")
    core_end = next((i for i, w in enumerate(words) if w in lang.locative), len(words))
    return _Read(lexicon, kinds, " ".join(said), words, normed, [compared(lang, w) for w in normed], content,
                 cover, own_name, whole, _head(lang, words, content), core_end)  # fmt: skip


def _covered(
    lexicon: Lexicon, words: list[str], said_whole: frozenset[int]
) -> tuple[dict[str, frozenset[int]], set[str], dict[str, set[str]]]:
    """The KB's names found in the words: the positions each entity's names span, the entities a
    name of the KB's own names, and the sources of the names that are all the words said."""
    cover: dict[str, frozenset[int]] = {}
    own_name: set[str] = set()
    whole: dict[str, set[str]] = {}
    for start in range(len(words)):
        spans: dict[int, frozenset[int]] = {}  # shared: a class word's name is thousands of things'
        for name in lexicon.names_at(words, start):
            span = spans.get(len(name.words))
            if span is None:
                span = spans[len(name.words)] = frozenset(range(start, start + len(name.words)))
            before = cover.get(name.entity)
            cover[name.entity] = span if before is None else before | span
            if not name.lexical:
                own_name.add(name.entity)
            if span == said_whole:
                whole.setdefault(name.entity, set()).add(name.source)
    return cover, own_name, whole


def _named(r: _Read, entity: Entity | None) -> bool:
    """Whether the phrase names the entity: one of its names said, every other content word its
    own or its context's (where it is, whose it is)."""
    if entity is None or entity.kind not in r.kinds:
        return False
    own = r.cover[entity.id]
    if not any(i in own for i in r.content):
        return False
    rest = [i for i in r.content if i not in own]
    if not rest:  # every word is the thing's own name: no qualifier or context to look up
        return True
    attrs = r.lexicon.attributes.get(entity.id, frozenset())
    # "the seed shelf" is a shelf: the head is the thing's own word, never its support's.
    if r.head is not None and r.head not in own and r.normed[r.head] not in attrs:
        return False
    context: frozenset[int] = frozenset()
    inside = tuple(o for prep, o in entity.relations if prep == "in")
    for other in (entity.support, entity.zone, entity.owner, *inside):
        if other is not None:
            context |= r.cover.get(other, frozenset())
    return all(i in context or r.normed[i] in attrs or r.bases[i] in attrs for i in rest)


def _candidates(r: _Read, owner: str | None, sight: bool) -> list[Entity]:
    """The entities the phrase names. A class word names thousands of things of which a handful
    are in sight or the speaker's: those are tried first, and the rest only when they cannot settle
    the answer (see _settled)."""
    snapshot = r.lexicon.snapshot
    # A few things named, to fetch or one of them called just what is said: all of them.
    if (not sight or r.whole) and len(r.cover) <= FEW_NAMED:
        return [e for e in snapshot.among(r.cover, r.kinds) if _named(r, e)]
    if owner is None:  # the things in sight, without looking at the others
        near = snapshot.seen_among(r.cover)
    else:
        near = [e for e in snapshot.among(r.cover, r.kinds)
                if e.seen or (owner is not None and e.owner == owner)]  # fmt: skip
    matches = [e for e in near if _named(r, e)]
    if not _settled(matches, owner, r.own_name):
        matches = [e for e in snapshot.among(r.cover, r.kinds) if _named(r, e)]
    return matches


def _narrowed(r: _Read, matches: list[Entity]) -> list[Entity]:
    """Of the entities named, those named most closely."""
    # "the kitchen table" is the one named so, before a table that is in the kitchen.
    matches = [e for e in matches if all(i in r.cover[e.id] for i in r.content)] or matches
    # (and the "wobbly kitchen table", whose own words say "kitchen", before a worktop in the kitchen;
    # "the table in the kitchen" says where, which both are)
    if r.core_end == len(r.words):
        own = [e for e in matches if _own_words(r.lexicon, e, r.cover[e.id], r.content, r.normed, r.bases)]
        matches = own or matches
    # "the desk" is the thing called so, before the "standing desk" it is only the end of.
    said = tuple(r.normed[i] for i in r.content)
    called = [e for e in matches if _called(e, r.whole.get(e.id, ()))]
    # (unless another is called so too but for its colour: "the cup" of a cup and a red cup is asked)
    if called and not any(e not in called and name_words(e.name) == said for e in matches):
        matches = called
    return matches


def _otherwise(r: _Read, matches: list[Entity], owner: str | None) -> list[Entity]:
    """When no name of the KB settles it, what the words say otherwise."""
    lang = r.lexicon.lang
    if not matches and r.content:
        matches = _by_words(r)
    # "the bread on the bread shelf": the shelf is where, not what ("the side of the bath" is the
    # bath; "a tin of soup", "a pair of goggles" are read below without the measure)
    if r.head is not None and r.words[r.head] not in lang.words.parts | lang.words.positions:
        matches = [e for e in matches if not _named_after(r.cover.get(e.id), r.head)]
    if not matches and r.content:
        matches = _measured(r, owner)
    return matches


def _by_words(r: _Read) -> list[Entity]:
    """The entities the content words say by their labels' words, qualifiers or head noun."""
    lexicon, content = r.lexicon, [r.normed[i] for i in r.content]
    matches = by_label_words(lexicon, content, r.kinds)
    if not matches and lexicon.lang.words.one & set(r.words):
        matches = by_qualifiers(lexicon, content, r.kinds)
    if not matches:
        matches = resolve_head(lexicon, r.words, r.kinds)
    return matches


def _measured(r: _Read, owner: str | None) -> list[Entity]:
    """A measure's thing ("a pair of 3D glasses": the glasses), or a container's food or drink (what
    a container holds: "a bottle of umbrella" is nothing)."""
    lang = r.lexicon.lang
    matches: list[Entity] = []
    counted = thing_measured(lang, r.words)
    if counted:
        matches = list(resolve(r.lexicon, counted, r.kinds, owner=owner).matches)
    contents = thing_held(lang, r.words, r.normed) if not matches else ()
    if contents:
        held = resolve(r.lexicon, contents, r.kinds, owner=owner).matches
        matches = [e for e in held if FOOD_OR_DRINK in e.classes]
    return matches


def _preferred(r: _Read, matches: list[Entity], owner: str | None, sight: bool) -> Resolution:
    """The matches, the preferred among them when some are."""
    only_one = r.head is None and r.lexicon.lang.words.one & set(r.words[: r.core_end])
    if only_one:  # whatever found them, the place a "one" is said to be at is not that one
        matches = [e for e in matches if not r.cover.get(e.id) or min(r.cover[e.id]) <= r.core_end]
    # Ownership only narrows: "my cup" still means the cup when nobody's cups are recorded.
    owned = [e for e in matches if owner is not None and e.owner == owner]
    matches = owned or matches
    # "the bathroom" is the room labelled so, not the toilets the lexicon file says it may be.
    matches = [e for e in matches if e.id in r.own_name] or matches
    # Without `sight`, sight narrows only a word that names more things than a question can list:
    # of two towels, the one in sight is not "the towel" to fetch (which is asked), of hundreds of
    # apples it is.
    seen = [e for e in matches if e.seen] if sight or len(matches) > MAX_OPTIONS else []
    # Sorted last: a class word names thousands of things of which a handful are in sight.
    return Resolution(r.phrase, tuple(r.lexicon.snapshot.in_order(seen or matches)))


def _own_words(lexicon: Lexicon, entity: Entity, own: frozenset[int], content: Sequence[int],
               normed: Sequence[str], bases: Sequence[str]) -> bool:
    """Whether every content word said is the entity's own (its names, label words, colour, kind),
    none only the name of where it is or whose."""
    attrs = lexicon.attributes.get(entity.id, frozenset())
    return all(i in own or normed[i] in attrs or bases[i] in attrs for i in content)


def _named_after(span: frozenset[int] | None, head: int) -> bool:
    """Whether an entity's names occur in the phrase only after its head noun (in what qualifies
    the head: a place, an owner), so that it is not the thing the phrase names."""
    return span is not None and bool(span) and head not in span and min(span) > head


def _called(entity: Entity, sources: Collection[str]) -> bool:
    """Whether the entity's label is all the words said ("the desk", not the "standing desk"). A
    thing with a colour is not called only that: the "vase" that is blue is the blue vase as much as
    the others are the glass vase and the tall vase ("the vase" is asked about). A thing with no
    label is called by its class as all its kind are (a cup among a "red cup" and a "blue cup")."""
    return entity.colour is None and bool(entity.labels) and "label" in sources


def _settled(near: Sequence[Entity], owner: str | None, own_name: Collection[str]) -> bool:
    """Whether the matches among the seen and the owner's things give the answer the matches among
    all would (the filters below keep the owner's things, then the KB's own names, then the seen)."""
    if not near:
        return False  # nothing in sight: the unseen ones, or the fallbacks, answer
    if owner is not None and any(e.owner == owner for e in near):
        return True  # every owned candidate was tried
    # Not the owner's: the seen matches with a name of the KB's own, else all of them when no
    # unseen thing can have one.
    return any(e.id in own_name for e in near) or not own_name


def _head(lang: Language, words: Sequence[str], content: Sequence[int]) -> int | None:
    """The index of the head noun: the last content word before a preposition ends the core."""
    core_end = lang.locative | lang.words.core_end
    head = None
    for i in content:
        if any(w in core_end for w in words[:i]):
            break
        head = i
    return head


def resolve_id(lexicon: Lexicon, value: str, kinds: Collection[Kind] = ALL_KINDS) -> Resolution:
    """An id (or, from a model that ignored the enum, a name) to entities of the snapshot."""
    entity = lexicon.snapshot.get(value)
    if entity is not None:
        return Resolution(value, (entity,) if entity.kind in kinds else ())
    words = tokens(value)
    if not content_words(lexicon.lang, words):
        return Resolution(value, ())
    return resolve(lexicon, words, kinds)
