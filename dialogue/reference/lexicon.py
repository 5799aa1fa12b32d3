"""Names: indexing every name of every entity of a snapshot (`naming` says what they are).

Names come from the KB only (instance labels, ids, class labels of all classes including inferred
superclasses, readable class ids), so a new object is understood as soon as it is in the KB. All
matching is on whole words (D11).
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Hashable, Iterable, Iterator, Mapping, Sequence
from collections.abc import Set as AbstractSet
from dataclasses import dataclass
from typing import Any, TypeVar, cast

from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.layered import GONE, Gone, Layered, layered, rebucket
from dialogue.reference.naming import NO_ENTRY, Entry, Name, Naming, norm, phrase, singular
from dialogue.understanding.language import Language

__all__ = ["Lexicon", "Mention", "Name", "norm", "phrase", "singular"]

T = TypeVar("T")

@dataclass(frozen=True)
class Mention:
    start: int
    end: int
    entities: frozenset[str]


class Lexicon:
    """All names of a snapshot's entities, indexed by their whole (singular) words, with the
    lengths of the names each first word starts: finding the names at a position costs a lookup
    per length, however many entities share a word.

    An entity's names have two parts: its own (its labels, id and colour) and its kind's (the names
    its classes give it, the same for every entity of the same classes). A kind's names are made
    once and indexed once, with the entities of that kind: "cup" names a thousand cups through one
    entry, and a cup that moves or changes colour is indexed again in its own few names only.

    Built from a `previous` lexicon: when the snapshot says which entities changed since the
    previous one's, only those are indexed again (the indexes are copied, the entries they touch
    replaced), so a KB change costs work proportional to what changed; otherwise the entries of
    entities that did not change are reused.

    The names are said in `lang` (its lexicon file, titles, number words), which the lexicon
    carries to what reads words against it.
    """

    def __init__(self, snapshot: Snapshot, lang: Language, previous: Lexicon | None = None) -> None:
        self.snapshot = snapshot
        self.lang = lang
        if previous is not None and previous.lang is not lang:
            previous = None  # (names said in another language share nothing)
        self._naming: Naming = previous._naming if previous is not None else Naming(lang)
        #: The entry of each kind (its class names), shared by every version: a kind's names never
        #: change, only which entities are of it.
        self._kinds: dict[tuple[str, ...], Entry] = previous._kinds if previous is not None else {}
        #: The names of a kind word, one per entity of its kinds, made when first looked up.
        self._found: dict[tuple[str, ...], tuple[frozenset[tuple[str, ...]], list[Name]]] = {}
        #: What was read off this version's names (`analysed`): never carried to the next version.
        self._analyses: dict[Hashable, Any] = {}
        self._analysed_weight = 0
        changed = snapshot.changed_since(previous.snapshot.revision) if previous is not None else None
        if previous is not None and changed is not None:
            self._update(previous, changed)
            return
        by_words: dict[tuple[str, ...], dict[Name, None]] = defaultdict(dict)
        lengths: dict[str, dict[int, int]] = defaultdict(dict)
        by_label: dict[str, dict[str, None]] = defaultdict(dict)
        vocabulary: dict[str, int] = defaultdict(int)
        entries: dict[str, tuple[Entity, Entry]] = {}
        members: dict[tuple[str, ...], dict[str, None]] = defaultdict(dict)
        kind_of: dict[str, tuple[str, ...]] = {}
        old = previous._entries if previous is not None else Layered()
        for entity in snapshot.entities.values():
            entry = _reuse(old.get(entity.id), entity, self._naming)
            entries[entity.id] = (entity, entry)
            for name in entry.names:
                by_words[name.words][name] = None
                counts = lengths[name.words[0]]
                counts[len(name.words)] = counts.get(len(name.words), 0) + 1
            for word in entry.label_words:
                by_label[word][entity.id] = None
            for word in entry.words:
                vocabulary[word] += 1
            if entity.class_names:
                members[entity.class_names][entity.id] = None
                kind_of[entity.id] = entity.class_names
        kind_words: dict[tuple[str, ...], dict[tuple[str, ...], str]] = defaultdict(dict)
        for kind in members:
            self._count_kind(kind, 1, kind_words, lengths, vocabulary)
        #: Each entity's own names, by their words (a set of names: a mapping to None, one removed
        #: in O(1)); a bucket many entities share is layered (`layered.rebucket`).
        self._by_words: Layered[tuple[str, ...], Mapping[Name, None]] = Layered(
            {words: layered(names) for words, names in by_words.items()})
        #: The kinds' names by their words: words -> {kind: the name's source}.
        self._kind_words: Layered[tuple[str, ...], Mapping[tuple[str, ...], str]] = Layered(dict(kind_words))
        #: The entities of each kind, and each entity's kind.
        self._members: Layered[tuple[str, ...], Mapping[str, None]] = Layered(
            {kind: layered(ids) for kind, ids in members.items()})
        self._kind_of: Layered[str, tuple[str, ...]] = Layered(kind_of)
        #: Entities by each (singular) word of their own labels, for "the teddy" ("teddy bear").
        self.by_label_word: Layered[str, Mapping[str, None]] = Layered(
            {word: layered(ids) for word, ids in by_label.items()})
        #: Every (singular) word of every name and qualifier, what the KB can account for, with the
        #: number of entities (and kinds) that have it (a word goes when its last one drops it).
        self.vocabulary: Layered[str, int] = Layered(dict(vocabulary))
        #: Each entity's own entry (its labels, id and colour).
        self._entries: Layered[str, tuple[Entity, Entry]] = Layered(entries)
        #: First word -> {name length: number of names}, longest first when read.
        self._lengths: Layered[str, dict[int, int]] = Layered(dict(lengths))

    @property
    def attributes(self) -> Mapping[str, AbstractSet[str]]:
        """Each entity's qualifying words: its own (label words, colour) and its kind's."""
        return _Attributes(self)

    def _kind(self, kind: tuple[str, ...]) -> Entry:
        found = self._kinds.get(kind)
        if found is None:
            found = self._kinds[kind] = self._naming.entry(Entity("", "", (), (), kind, "thing", False))
        return found

    def _count_kind(self, kind: tuple[str, ...], step: int, kind_words: dict[Any, Any],
                    lengths: dict[str, dict[int, int]], vocabulary: dict[str, int],
                    previous: Lexicon | None = None) -> None:
        """Index a kind that gained its first entity (``step`` 1), or unindex one that lost its
        last (-1); the changes go to the given dicts, copied from ``previous``'s when updating."""
        entry = self._kind(kind)
        for name in entry.names:
            if previous is None:
                kind_words[name.words][kind] = name.source
                counts = lengths[name.words[0]]
            else:
                _own(kind_words, previous._kind_words, name.words, dict)[kind] = name.source
                if step < 0:
                    del kind_words[name.words][kind]
                counts = _own(lengths, previous._lengths, name.words[0], dict)
            counts[len(name.words)] = counts.get(len(name.words), 0) + step
            if not counts[len(name.words)]:
                del counts[len(name.words)]
        for word in entry.words:
            known = previous.vocabulary.get(word, 0) if previous is not None else 0
            vocabulary[word] = vocabulary.get(word, known) + step

    def _update(self, previous: Lexicon, changed: frozenset[str]) -> None:
        # Only the changed entries are written, into small top layers (`Layered`); the buckets
        # they touch are copied first (shared with the previous lexicon).
        entries: dict[str, tuple[Entity, Entry] | Gone] = {}
        by_words: dict[tuple[str, ...], dict[Name, Gone | None]] = {}  # changes per bucket
        by_label: dict[str, dict[str, Gone | None]] = {}
        lengths: dict[str, dict[int, int]] = {}
        vocabulary: dict[str, int] = {}
        kind_of: dict[str, tuple[str, ...] | Gone] = {}
        members: dict[tuple[str, ...], dict[str, Gone | None]] = {}
        for entity_id in sorted(changed, key=self.snapshot.order_key):
            kept = previous._entries.get(entity_id)
            entity = self.snapshot.get(entity_id)
            entry = _reuse(kept, entity, self._naming) if entity is not None else None
            entries[entity_id] = (entity, entry) if entity is not None and entry is not None else GONE
            was, now = previous._kind_of.get(entity_id), entity.class_names if entity is not None else None
            if was != now:
                kind_of[entity_id] = now or GONE
                for kind, present in ((was, GONE), (now, None)):
                    if kind:
                        members.setdefault(kind, {})[entity_id] = present
            before, after = kept[1] if kept is not None else NO_ENTRY, entry or NO_ENTRY
            if before is after:
                continue
            for word in before.words ^ after.words:
                count = vocabulary.get(word, previous.vocabulary.get(word, 0))
                vocabulary[word] = count + (1 if word in after.words else -1)
            if before.names == after.names and before.label_words == after.label_words:
                continue
            for names, step in ((before.names, -1), (after.names, 1)):
                for name in names:
                    by_words.setdefault(name.words, {})[name] = GONE if step < 0 else None
                    counts = _own(lengths, previous._lengths, name.words[0], dict)
                    counts[len(name.words)] = counts.get(len(name.words), 0) + step
                    if not counts[len(name.words)]:
                        del counts[len(name.words)]
            for words, present in ((before.label_words, GONE), (after.label_words, None)):
                for word in words:
                    by_label.setdefault(word, {})[entity_id] = present
        kinds: dict[tuple[str, ...], Mapping[str, None] | Gone] = {}
        kind_words: dict[tuple[str, ...], dict[tuple[str, ...], str]] = {}
        for kind, change in members.items():
            old = previous._members.get(kind)
            kinds[kind] = new = rebucket(old, change)
            if (old is None) != isinstance(new, Gone):  # a kind's first entity, or its last gone
                self._count_kind(kind, 1 if old is None else -1, kind_words, lengths, vocabulary, previous)
        self._entries = previous._entries.evolve(entries)
        self._by_words = previous._by_words.evolve(
            {k: rebucket(previous._by_words.get(k), v) for k, v in by_words.items()})
        self.by_label_word = previous.by_label_word.evolve(
            {k: rebucket(previous.by_label_word.get(k), v) for k, v in by_label.items()})
        self._lengths = previous._lengths.evolve({k: v or GONE for k, v in lengths.items()})
        self.vocabulary = previous.vocabulary.evolve({k: v or GONE for k, v in vocabulary.items()})
        self._kind_of = previous._kind_of.evolve(kind_of)
        self._members = previous._members.evolve(kinds)
        self._kind_words = previous._kind_words.evolve({k: v or GONE for k, v in kind_words.items()})
        # The names found for a kind word stay right while no entity joined or left its kinds.
        found = previous._found.copy()  # (a turn may be adding to it: copied at once)
        self._found = {w: hit for w, hit in found.items()
                       if not hit[0] & kinds.keys() and w not in kind_words}  # fmt: skip

    def _named(self, words: tuple[str, ...]) -> list[Name]:
        """The names that are these words: the entities' own, then their kinds' (an entity named
        both ways once: by the KB's own name rather than by the lexicon file's, else by its own)."""
        own = self._by_words.get(words, ())
        kinds = self._kind_words.get(words)
        if not kinds:
            return list(own)
        of_kinds = self._of_kinds(words, kinds)
        if not own:
            return of_kinds
        own_lost: set[Name] = set()
        kind_lost: set[str] = set()
        for name in own:
            kind = self._kind_of.get(name.entity)
            source = kinds.get(kind) if kind is not None else None
            if source is None:
                continue
            if name.lexical and source not in _LEXICAL:
                own_lost.add(name)
            else:
                kind_lost.add(name.entity)
        kept = [n for n in own if n not in own_lost]
        return kept + ([n for n in of_kinds if n.entity not in kind_lost] if kind_lost else of_kinds)

    def _of_kinds(self, words: tuple[str, ...], kinds: Mapping[tuple[str, ...], str]) -> list[Name]:
        hit = self._found.get(words)
        if hit is None:
            names = [Name(words, entity, source) for kind, source in kinds.items()
                     for entity in self._members.get(kind, ())]  # fmt: skip
            if sum(len(n) for _kinds, n in self._found.values()) + len(names) > _MAX_FOUND:
                self._found = {}  # (a bound on what is kept; looked up again when needed)
            hit = self._found[words] = (frozenset(kinds), names)
        return hit[1]

    def names_at(self, words: Sequence[str], start: int) -> list[Name]:
        """Every name that occurs in `words` starting at `start` (longest first)."""
        # Only the words a candidate name spans are normalised: normalising the whole utterance
        # at every start made a long utterance cost quadratic time.
        found: list[Name] = []
        for length in sorted(self._lengths.get(singular(words[start]), {}), reverse=True):
            if start + length <= len(words):
                found += self._named(norm(words[start : start + length]))
        word = words[start]
        if not found and len(word) > 3 and word.endswith("s") and word[:-1] in self._lengths:
            # "ravis scarf": a person's name with the possessive's apostrophe dropped
            found += [n for n in self._named((word[:-1],)) if self.is_person(n.entity)]
        if start + 1 < len(words):
            # "tea cup" for the "teacup", "tool box" for the "toolbox": a closed compound said apart.
            joined = singular(words[start] + words[start + 1])
            found += [Name((words[start], words[start + 1]), n.entity, n.source)
                      for n in self._named((joined,))]  # fmt: skip
        return found

    def shares_name(self, entity: Entity) -> bool:
        """Whether another entity is called what this one is (two mugs, a thousand cups): a reply
        then names it as a person tells it apart ("the red mug"). Counted, not listed."""
        words = phrase(entity.name)
        if any(n.entity != entity.id for n in self._by_words.get(words, ())):
            return True
        for kind in self._kind_words.get(words) or ():
            members = self._members.get(kind) or {}
            if len(members) > (1 if entity.id in members else 0):
                return True
        return False

    def is_person(self, entity_id: str) -> bool:
        entity = self.snapshot.get(entity_id)
        return entity is not None and entity.kind == "person"

    def mentions(self, words: Sequence[str]) -> list[Mention]:
        """Left-to-right longest mentions of entity names in a word sequence."""
        out: list[Mention] = []
        i = 0
        while i < len(words):
            names = self.names_at(words, i)
            if not names:
                i += 1
                continue
            length = len(names[0].words)
            ents = frozenset([n.entity for n in names if len(n.words) == length])
            out.append(Mention(i, i + length, ents))
            i += length
        return out

    def analysed(self, key: Hashable, make: Callable[[], T], size: Callable[[T], int] = lambda _: 1) -> T:
        """What `make` reads off this version's names (a phrase's referents), made once per `key`:
        the same phrase read again by another reader of the turn, or by a later turn of the same
        snapshot, is looked up. `make` must read nothing but this lexicon and what `key` holds.
        Bounded: what is kept weighs at most `_MAX_ANALYSES` by `size` (cleared when it would
        weigh more: a class word's referents may be thousands of entities), and a lexicon is one
        snapshot's, so nothing kept outlives the snapshot's revision."""
        made = self._analyses.get(key, _NOT_MADE)
        if made is _NOT_MADE:
            made = make()
            weight = size(made)
            if self._analysed_weight + weight > _MAX_ANALYSES:
                self._analyses, self._analysed_weight = {}, 0
            if weight <= _MAX_ANALYSES:
                self._analyses[key] = made
                self._analysed_weight += weight
        return cast(T, made)

    def knows_word(self, word: str) -> bool:
        return singular(word) in self._lengths

    def knows(self, word: str) -> bool:
        """Whether the word is part of any name or qualifier of the snapshot ("'s" ignored)."""
        word = word[:-2] if word.endswith("'s") else word
        return word.isdigit() or singular(word) in self.vocabulary



def _own(changes: dict[Any, Any], source: Mapping[Any, Any], key: Any, empty: Callable[[], Any]) -> Any:
    """The copy of `source[key]` this update writes to (copied once)."""
    if key not in changes:
        changes[key] = source[key].copy() if key in source else empty()
    return changes[key]


def _reuse(kept: tuple[Entity, Entry] | None, entity: Entity, naming: Naming) -> Entry:
    """The entity's own entry (its names without its kind's), reused while what it is made of holds."""
    if kept is not None and kept[0].labels == entity.labels and kept[0].colour == entity.colour:
        return kept[1]
    return naming.entry(entity, kind=False)


#: Sources of the names the lexicon file gives (`Name.lexical`).
_LEXICAL = frozenset({"synonym", "kind"})
#: Names of kind words kept between lookups, in all.
_MAX_FOUND = 200_000
#: What the analyses a lexicon keeps may weigh (`Lexicon.analysed`): for phrases' referents,
#: each phrase and each entity it names is 1 (some hundred phrases, or one class word's thousands).
_MAX_ANALYSES = 4096
#: What `Lexicon.analysed` holds for an analysis not made yet (an analysis may be None).
_NOT_MADE = object()


class _Attributes(Mapping[str, AbstractSet[str]]):
    """`Lexicon.attributes`: an entity's own qualifiers with its kind's, made when asked."""

    __slots__ = ("_lexicon",)

    def __init__(self, lexicon: Lexicon) -> None:
        self._lexicon = lexicon

    def __getitem__(self, entity_id: str) -> AbstractSet[str]:
        own = self._lexicon._entries[entity_id][1].qualifiers
        kind = self._lexicon._kind_of.get(entity_id)
        if kind is None:
            return own
        theirs = self._lexicon._kind(kind).qualifiers
        return _Both(own, theirs) if own else theirs

    def get(self, key: str, default: Any = None) -> Any:
        return self[key] if key in self._lexicon._entries else default

    def __iter__(self) -> Iterator[str]:
        return iter(self._lexicon._entries)

    def __len__(self) -> int:
        return len(self._lexicon._entries)


class _Both(AbstractSet[str]):
    """Two sets of words read as one, without making it."""

    __slots__ = ("_one", "_other")

    def __init__(self, one: frozenset[str], other: frozenset[str]) -> None:
        self._one, self._other = one, other

    def __contains__(self, word: object) -> bool:
        return word in self._one or word in self._other

    def __iter__(self) -> Iterator[str]:
        yield from self._one
        yield from (w for w in self._other if w not in self._one)

    def __len__(self) -> int:
        return len(self._one | self._other)

    @classmethod
    def _from_iterable(cls, words: Iterable[str]) -> frozenset[str]:  # type: ignore[override]
        # what `set - both` and the other operators make: a plain frozenset
        return frozenset(words)
