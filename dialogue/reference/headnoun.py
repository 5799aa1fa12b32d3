"""Open-world reference: a phrase names the things its head noun names, unless a known fact says no.

Used when no entity accounts for every word of a phrase ("the salt box", "the bottle of water on the
table", "the knife on the cutting board" with no `isOn` fact for the knife). The KB is an open world:
a modifier it cannot evaluate (a word it does not know, a relation with no fact either way) neither
confirms nor eliminates a candidate; a modifier that contradicts a known fact (the cup is red, not
green; the cup is on the shelf, not the table) eliminates it. Modifiers that hold are evidence: among
several candidates, those with the most confirmed modifiers are kept, the rest asked about.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass

from dialogue.reference.english import tokens
from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.lexicon import Lexicon, norm, phrase, singular
from dialogue.reference.synonyms import synonyms
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of


@dataclass(frozen=True)
class _Words:
    """The language's words a head is found with (lang/<code>/words.toml, [head_noun])."""

    #: Qualifiers of position or size the KB does not model: never a head, never evidence.
    qualifiers: frozenset[str]
    skip: frozenset[str]
    #: Words of a clause, never of a noun phrase's core.
    clause: frozenset[str]
    #: Determiners that start a noun phrase of their own after a core has begun.
    new_phrase: frozenset[str]
    #: Coordinated or quantified phrases name several things: never one by its head.
    several: frozenset[str]
    determiners: frozenset[str]
    modifier_start: frozenset[str]
    support: frozenset[str]
    colours: frozenset[str]
    parts: frozenset[str]
    containers: frozenset[str]
    #: Words of a label that never name what a container holds: its colour, size, material.
    not_contents: frozenset[str]
    #: Prepositions of a thing nearby, and the relations of the KB (`isNextTo`, `near`,
    #: `isBelow`...) that say it ("the printer by the window").
    beside: dict[str, frozenset[str]]
    #: Phrases of a thing nearby read as one preposition ("next to": "beside").
    joined: frozenset[tuple[str, ...]]


def _words(lang: Language) -> _Words:
    head, closed = lang.words.head_noun, lang.words
    return _Words(
        qualifiers=closed.positions | head.qualifiers | head.postures,
        skip=(closed.determiners - lang.modifier_start) | head.skipped,
        clause=head.clause_words,
        new_phrase=head.new_phrase,
        several=closed.many | head.several,
        determiners=closed.determiners,
        modifier_start=lang.modifier_start,
        support=lang.support,
        colours=closed.colours,
        parts=closed.parts,
        containers=closed.containers,
        not_contents=closed.colours | closed.positions | head.qualifiers | closed.materials,
        beside=lang.prepositions.column("evidence"),
        joined=frozenset(lang.prepositions.having("beside")),
    )


@dataclass(frozen=True)
class _Phrase:
    core: tuple[str, ...]
    #: (preposition, its noun phrase) for each modifier after the core.
    modifiers: tuple[tuple[str, tuple[str, ...]], ...]
    #: A preposition with no noun phrase after it ("the bay for"): the phrase is cut short.
    dangling: bool = False


def _split(lang: _Words, words: Sequence[str]) -> _Phrase:
    modifier_start = lang.modifier_start
    words = [w for w in words if w not in lang.skip]
    core: list[str] = []
    i = 0
    while i < len(words) and (words[i] not in modifier_start or not core):
        if words[i] not in modifier_start and words[i] not in lang.determiners:
            core.append(words[i])
        i += 1
    mods: list[tuple[str, tuple[str, ...]]] = []
    dangling = False
    while i < len(words):
        prep, i = words[i], i + 1
        if (prep, *words[i : i + 1]) in lang.joined:  # "next to", "close to": one word
            prep, i = "beside", i + 1
        np: list[str] = []
        while i < len(words) and words[i] not in modifier_start:
            np.append(words[i])
            i += 1
        if np:
            mods.append((prep, tuple(np)))
        dangling = dangling or (not np and i == len(words))
    core_words = tuple(w for w in core if w not in lang.qualifiers) or tuple(core)
    # "the head of the table": the part's owner is the head.
    if core_words and core_words[-1] in lang.parts and mods and mods[0][0] == "of":
        return _split(lang, mods[0][1] + tuple(w for p, np in mods[1:] for w in (p, *np)))
    return _Phrase(core_words, tuple(mods), dangling)


def _clause(lang: _Words, words: Sequence[str]) -> bool:
    """Whether the words before the phrase's first modifier run on into another phrase or a clause
    ("my torch I can't see the clock", "gate 9 my bus is late"): no head."""
    begun = False
    for word in words:
        if begun and word in lang.modifier_start:
            return False
        if word in lang.clause or (begun and word in lang.new_phrase):
            return True
        begun = begun or word not in lang.determiners
    return False


def _colours(lang: _Words, entity: Entity) -> frozenset[str]:
    said = {w for label in entity.labels for w in tokens(label) if w in lang.colours}
    if entity.colour:
        said |= {w for w in tokens(entity.colour) if w in lang.colours}
    return frozenset(said)


def _named(lexicon: Lexicon, np: Sequence[str]) -> set[str]:
    """Entities whose name ends the noun phrase (its head), whatever their kind; failing that, those
    a more general word for the head names ("the paperback": a book)."""
    return set(_name_starts(lexicon, np))


def _name_starts(lexicon: Lexicon, np: Sequence[str]) -> dict[str, int]:
    """`_named`, with where in the phrase each entity's (longest) name starts."""
    found: dict[str, int] = {}
    for start in range(len(np)):
        for name in lexicon.names_at(np, start):
            if start + len(name.words) == len(np):
                found.setdefault(name.entity, start)
    if not found and np:
        # ("the paperback" for the book: only a thing the KB itself calls a book, never one the
        # lexicon file makes a book; "the banana" is no apple because both are fruit)
        for general in synonyms(lexicon.lang, phrase).kind_of(phrase(np[-1])):
            own = {n.entity for n in lexicon.names_at(general, 0) if len(n.words) == len(general)
                   and not n.lexical}  # fmt: skip
            found.update(dict.fromkeys(own, len(np) - 1))
    if not found and np:  # "the thermos" for the "thermos flask": a word of its label
        found.update(dict.fromkeys(lexicon.by_label_word.get(singular(np[-1]), ()), len(np) - 1))
    return found


def _entities(lexicon: Lexicon, np: Sequence[str]) -> list[Entity]:
    return [e for eid in _named(lexicon, np) if (e := lexicon.snapshot.get(eid)) is not None]


def resolve_head(lexicon: Lexicon, words: Sequence[str], kinds: Collection[Kind]) -> list[Entity]:
    """Entities of `kinds` the phrase's head noun names that no modifier contradicts, best first."""
    lang = lexicon.lang.derived(_words)
    if lang.several & set(words) or _clause(lang, words):
        return []
    phrase = _split(lang, words)
    if not phrase.core or phrase.dangling:  # a modifier cut short may have named anything
        return []
    snapshot = lexicon.snapshot
    starts = _name_starts(lexicon, phrase.core)
    heads = snapshot.among(starts, kinds)
    scored: list[tuple[int, Entity]] = []
    for entity in heads:
        score = _evidence(lexicon, lang, entity, phrase, starts[entity.id])
        if score is not None:
            scored.append((score, entity))
    if not scored:
        return []
    best = max(s for s, _ in scored)
    found = snapshot.in_order(e for s, e in scored if s == best)
    seen = {e.seen for e in found}
    if len(seen) > 1 and _told_apart_by_nothing(lexicon, lang, found, phrase.core, starts):
        # "the staff room" among the waiting room the robot sees and rooms it does not: the one it
        # sees is not meant any more than the others (when it sees all or none, it asks which)
        return []
    return found


def _told_apart_by_nothing(
    lexicon: Lexicon, lang: _Words, found: Sequence[Entity], core: Sequence[str], starts: dict[str, int]
) -> bool:
    """Whether a word of the core before the candidates' names, said to tell them apart, holds for
    none of them ("the staff room" among several rooms)."""
    said = [set(norm(core[: starts[e.id]])) - lang.colours for e in found]
    unconfirmed = set.intersection(*said) if said else set()
    for entity in found:
        unconfirmed -= lexicon.attributes.get(entity.id, frozenset())
    return bool(unconfirmed)


#: How much a fact of the relation itself weighs, against the weaker evidence of sharing a zone.
_RELATED, _SAME_ZONE = 2, 1


def _nearby(lexicon: Lexicon, entity: Entity, said: frozenset[str], places: Sequence[Entity]) -> int:
    """The evidence that the entity is where the modifier says, near one of `places`: a fact of the
    relation ("isNextTo"), else the same zone (a thing by the window is in the window's room). No
    evidence contradicts: a thing may be next to several (the open world)."""
    ids = {p.id for p in places if p.id != entity.id}
    if any(prep in said and other in ids for prep, other in entity.relations):
        return _RELATED
    zones = {p.zone for p in places if p.id != entity.id and p.zone is not None}
    if "next to" in said and entity.zone is not None and entity.zone in zones:
        return _SAME_ZONE
    return 0


def _evidence(lexicon: Lexicon, lang: _Words, entity: Entity, phrase: _Phrase, name_start: int) -> int | None:
    """How many modifiers hold for the entity, or None when one contradicts a known fact. The words
    of the core its own name spans count as modifiers that hold ("tea cup" names the teacup fully,
    the espresso cup only by "cup")."""
    attrs = lexicon.attributes.get(entity.id, frozenset())
    colours = _colours(lang, entity)
    score = len(phrase.core) - 1 - name_start
    for word in norm(phrase.core[:name_start]):
        people = {e.id for e in _entities(lexicon, (word,)) if e.kind == "person"}
        if word in attrs:
            score += 1
        elif word in lang.colours and colours:
            return None  # "the green cup" when the cup is known to be red
        elif people and entity.owner is not None:
            if entity.owner not in people:
                return None  # "Dan's mug" when the mug is known to be Bob's
            score += 1
    for prep, np in phrase.modifiers:
        held = _modifier(lexicon, lang, entity, phrase.core[-1], prep, np)
        if held is None:
            return None
        score += held
    return score


def _modifier(
    lexicon: Lexicon, lang: _Words, entity: Entity, head: str, prep: str, np: Sequence[str]
) -> int | None:
    """One modifier of the phrase: 1 when it holds for the entity, 0 when nothing is known either way,
    None when it contradicts a known fact."""
    if prep == "of" and head in lang.containers:
        return _holds(lexicon, lang, entity, head, np)
    if prep in lang.beside:
        return _nearby(lexicon, entity, lang.beside[prep], _entities(lexicon, np))
    if prep not in lang.support:
        return 0
    places = _entities(lexicon, np)
    if not places:
        return 0  # a place the KB does not know: nothing to check
    known = {p.id for p in places if p.kind != "zone"}, {p.id for p in places if p.kind == "zone"}
    if known[0] & {o for p, o in entity.relations if p == "in"}:
        return 1  # "the ball in the toy box": a container it is known to be in
    score = 0
    for fact, candidates in ((entity.support, known[0]), (entity.zone, known[1])):
        if fact is None or not candidates:
            continue
        if fact not in candidates:
            return None  # "the cup on the table" when the cup is known to be on the shelf
        score += 1
    return score


def _holds(lexicon: Lexicon, lang: _Words, entity: Entity, container: str, np: Sequence[str]) -> int | None:
    """ "the box of tissues": 1 when the entity's own words say it holds that, None when its label
    names other contents (the "coin tin" is no box of tissues), 0 when nothing is known either way
    (a "red bottle" may be the bottle of water: the open world)."""
    said = [w for w in norm(np) if w not in lang.determiners]
    if set(said) & lexicon.attributes.get(entity.id, frozenset()):
        return 1
    own = {w for label in entity.labels for w in norm(tokens(label))}
    others = own - lang.not_contents - {container, *said}
    # An adjective of the label says what the container is like ("insulated flask"), not what it holds.
    return None if any("ADJ" not in lemmas_of(w) for w in others) else 0
