"""Names: indexing every name of every entity of a snapshot.

Names come from the KB only (instance labels, ids, class labels of all classes including inferred
superclasses, readable class ids), so a new object is understood as soon as it is in the KB. All
matching is on whole words (D11).
"""

from __future__ import annotations

import threading
from collections import defaultdict
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, NamedTuple

from lemminflect import getAllLemmas, getLemma

from dialogue.reference.english import tokens, word_set
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.layered import GONE, Gone, Layered, layered, rebucket
from dialogue.reference.synonyms import Synonyms, synonyms
from dialogue.understanding.language import Language

#: Function words ending in -s that a noun lemmatiser would "singularise" ("was" -> "wa").
_NOT_PLURAL = word_set("is was has does this his us yes its as thus plus whereas always sometimes perhaps")


@lru_cache(maxsize=65536)
def singular(word: str) -> str:
    """The noun lemma of a word ("knives" -> "knife", "buses" -> "bus", "glasses" -> "glass")."""
    if len(word) < 3 or not word.endswith("s") or word in _NOT_PLURAL or "'" in word:
        return word
    lemmas = getLemma(word, "NOUN", lemmatize_oov=True)
    return lemmas[0] if lemmas else word


def norm(words: Sequence[str]) -> tuple[str, ...]:
    return tuple(singular(w) for w in words)


def phrase(text: str) -> tuple[str, ...]:
    """A text as normalised words (the form names are indexed in)."""
    return norm(tokens(text))


class Name(NamedTuple):
    """One name of an entity (a tuple: hashed in C, and a class word's bucket holds thousands)."""

    words: tuple[str, ...]
    entity: str
    source: str  # "label", "id", "class", "head", "joined", or the lexicon file's "synonym", "kind"

    @property
    def lexical(self) -> bool:
        """Whether the name comes from the lexicon file rather than the KB's own names."""
        return self.source in {"synonym", "kind"}


@dataclass(frozen=True)
class Mention:
    start: int
    end: int
    entities: frozenset[str]


class Lexicon:
    """All names of a snapshot's entities, indexed by their whole (singular) words, with the
    lengths of the names each first word starts: finding the names at a position costs a lookup
    per length, however many entities share a word.

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
        self._said = _Said(lang)
        if previous is not None and previous.lang is not lang:
            previous = None  # (names said in another language share nothing)
        changed = snapshot.changed_since(previous.snapshot.revision) if previous is not None else None
        if previous is not None and changed is not None:
            self._update(previous, changed)
            return
        by_words: dict[tuple[str, ...], dict[Name, None]] = defaultdict(dict)
        lengths: dict[str, dict[int, int]] = defaultdict(dict)
        attributes: dict[str, frozenset[str]] = {}
        by_label: dict[str, dict[str, None]] = defaultdict(dict)
        vocabulary: dict[str, int] = defaultdict(int)
        entries: dict[str, tuple[Entity, _Entry]] = {}
        old = previous._entries if previous is not None else Layered()
        for entity in snapshot.entities.values():
            entry = _reuse(old.get(entity.id), entity, self._said)
            entries[entity.id] = (entity, entry)
            for name in entry.names:
                by_words[name.words][name] = None
                counts = lengths[name.words[0]]
                counts[len(name.words)] = counts.get(len(name.words), 0) + 1
            attributes[entity.id] = entry.qualifiers
            for word in entry.label_words:
                by_label[word][entity.id] = None
            for word in entry.words:
                vocabulary[word] += 1
        #: Names by their words, each bucket a set of names (a mapping to None, one removed in
        #: O(1)); a bucket a class name shares with thousands of entities is layered, so a change
        #: to one of them does not copy it (`layered.rebucket`).
        self._by_words: Layered[tuple[str, ...], Mapping[Name, None]] = Layered(
            {words: layered(names) for words, names in by_words.items()})
        self.attributes: Layered[str, frozenset[str]] = Layered(attributes)
        #: Entities by each (singular) word of their own labels, for "the teddy" ("teddy bear").
        self.by_label_word: Layered[str, Mapping[str, None]] = Layered(
            {word: layered(ids) for word, ids in by_label.items()})
        #: Every (singular) word of every name and qualifier, what the KB can account for, with the
        #: number of entities that have it (a word goes when its last entity drops it).
        self.vocabulary: Layered[str, int] = Layered(dict(vocabulary))
        self._entries: Layered[str, tuple[Entity, _Entry]] = Layered(entries)
        #: First word -> {name length: number of names}, longest first when read.
        self._lengths: Layered[str, dict[int, int]] = Layered(dict(lengths))

    def _update(self, previous: Lexicon, changed: frozenset[str]) -> None:
        # Only the changed entries are written, into small top layers (`Layered`); the buckets
        # they touch are copied first (shared with the previous lexicon).
        entries: dict[str, tuple[Entity, _Entry] | Gone] = {}
        attributes: dict[str, frozenset[str] | Gone] = {}
        by_words: dict[tuple[str, ...], dict[Name, Gone | None]] = {}  # changes per bucket
        by_label: dict[str, dict[str, Gone | None]] = {}
        lengths: dict[str, dict[int, int]] = {}
        vocabulary: dict[str, int] = {}
        for entity_id in sorted(changed, key=self.snapshot.order_key):
            kept = previous._entries.get(entity_id)
            entity = self.snapshot.get(entity_id)
            entry = _reuse(kept, entity, self._said) if entity is not None else None
            entries[entity_id] = (entity, entry) if entity is not None and entry is not None else GONE
            attributes[entity_id] = entry.qualifiers if entry is not None else GONE
            before, after = kept[1] if kept is not None else _NO_ENTRY, entry or _NO_ENTRY
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
        self._entries = previous._entries.evolve(entries)
        self.attributes = previous.attributes.evolve(attributes)
        self._by_words = previous._by_words.evolve(
            {k: rebucket(previous._by_words.get(k), v) for k, v in by_words.items()})
        self.by_label_word = previous.by_label_word.evolve(
            {k: rebucket(previous.by_label_word.get(k), v) for k, v in by_label.items()})
        self._lengths = previous._lengths.evolve({k: v or GONE for k, v in lengths.items()})
        self.vocabulary = previous.vocabulary.evolve({k: v or GONE for k, v in vocabulary.items()})

    def names_at(self, words: Sequence[str], start: int) -> list[Name]:
        """Every name that occurs in `words` starting at `start` (longest first)."""
        # Only the words a candidate name spans are normalised: normalising the whole utterance
        # at every start made a long utterance cost quadratic time.
        found: list[Name] = []
        for length in sorted(self._lengths.get(singular(words[start]), {}), reverse=True):
            if start + length <= len(words):
                found += self._by_words.get(norm(words[start : start + length]), ())
        word = words[start]
        if not found and len(word) > 3 and word.endswith("s") and word[:-1] in self._lengths:
            # "ravis scarf": a person's name with the possessive's apostrophe dropped
            found += [n for n in self._by_words.get((word[:-1],), ()) if self.is_person(n.entity)]
        if start + 1 < len(words):
            # "tea cup" for the "teacup", "tool box" for the "toolbox": a closed compound said apart.
            joined = singular(words[start] + words[start + 1])
            found += [Name((words[start], words[start + 1]), n.entity, n.source)
                      for n in self._by_words.get((joined,), ())]  # fmt: skip
        return found

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

    def knows_word(self, word: str) -> bool:
        return singular(word) in self._lengths

    def knows(self, word: str) -> bool:
        """Whether the word is part of any name or qualifier of the snapshot ("'s" ignored)."""
        word = word[:-2] if word.endswith("'s") else word
        return word.isdigit() or singular(word) in self.vocabulary


class _Said:
    """How the names of a language are said otherwise: its lexicon file, titles, number words."""

    def __init__(self, lang: Language) -> None:
        self.lang = lang
        self.synonyms: Synonyms = synonyms(lang, phrase)
        self.determiners = lang.words.determiners
        self.compound_heads = lang.words.compound_heads
        self.head_sizes = sorted({len(head) for head in self.compound_heads if len(head) > 2}, reverse=True)
        #: Each title to the other words said for it ("mister" for "mr").
        self.titles = {w: tuple(o for o in group if o != w) for group in lang.words.titles for w in group}

    def names(self, entity: Entity) -> list[Name]:  # noqa: C901
        out: list[Name] = []
        seen: set[tuple[str, ...]] = set()

        def add(text: str, source: str) -> None:
            words = norm(tokens(text))
            if words and words not in seen and not (len(words) == 1 and words[0] in self.determiners):
                seen.add(words)
                out.append(Name(words, entity.id, source))

        for label in entity.labels:
            add(label, "label")
            numbered = self.lang.words.other_numbers(tokens(label))
            if numbered is not None:  # "screen two" for "screen 2", "table 9" for "table nine"
                add(" ".join(numbered), "label")
            for other in self.otherwise(tokens(label)):
                add(" ".join(other), "label")
        add(entity.id, "id")
        for class_name in entity.class_names:
            add(class_name, "class")
        # The head noun of a multi-word name names the thing too: "the mug" for the "green mug",
        # "the remote" for the "TV remote"; the other words stay usable as qualifiers.
        for text in (*entity.labels, *entity.class_names):
            words = tokens(text)
            if len(words) > 1 and not {"or", "and"} & set(words):  # "food or drink" is no drink
                add(words[-1], "head")
            if len(words) == 2 and all(w.isalpha() for w in words):
                add("".join(words), "joined")  # "the eyeglass" for the "eye glass" (the converse of names_at)
            tail = self._compound_head(words[-1]) if words else None
            if tail is not None:  # "the bench" for the "workbench", yielding to a bench of the KB's own
                add(" ".join((*words[:-1], tail)) if len(words) > 1 else tail, "kind")
        # Other ways of saying a name or its ending ("cell phone" for the "mobile phone", "the fridge"
        # for the "kitchen refrigerator"), and the general names of its kind ("the bag" for the
        # "handbag", "a drink" for the "lemonade"): the lexicon file's, which yield to the KB's own
        # names (`Name.lexical`).
        syn = self.synonyms
        longest = syn.longest
        for text in (*entity.labels, *entity.class_names):
            said = phrase(text)
            # Only the endings a synonym may be: each one tried is a copy (a label of 30,000 words
            # once made every split of it one, minutes of work for every turn).
            for k in range(max(0, len(said) - longest), len(said)):
                for other in syn.of(said[k:]):
                    add(" ".join((*said[:k], *other)), "synonym")
                    if k:
                        add(" ".join(other), "synonym")
                alike = (said[k:], *syn.of(said[k:]))
                for general in (g for o in alike for g in syn.broader_than(o)):
                    add(" ".join(general), "kind")
        return out

    def _compound_head(self, word: str) -> str | None:
        """The general noun a closed compound ends with ("workbench": "bench"), if it is one of the
        language's compound heads after a word of its own (of 3 letters or more); None otherwise.
        Only the endings as long as a head are tried, the longest first: trying every split copied
        the word's rest at each, which a label of a million letters made minutes of work for every
        turn."""
        for size in self.head_sizes:
            k = len(word) - size
            if k >= 3 and word[k:] in self.compound_heads and getAllLemmas(word[:k]):
                return word[k:]
        return None

    def otherwise(self, words: Sequence[str]) -> list[tuple[str, ...]]:
        """Other ways a label is said: a possessive without its apostrophe, as a recogniser or a
        typist writes it ("hygienists room", "hygienist room" for the "hygienist's room"), and a title
        in full or short ("mister kowalski" for "Mr Kowalski")."""
        out: list[tuple[str, ...]] = []
        if any(w.endswith("'s") for w in words):
            out.append(tuple(w.removesuffix("'s") for w in words))
        if len(words) > 1 and words[0] in self.titles:
            out += [(title, *words[1:]) for title in self.titles[words[0]]]
        return out

    def entry(self, entity: Entity) -> _Entry:
        label_words = frozenset(w for label in entity.labels
                                for said in (tokens(label), *self.otherwise(tokens(label)))
                                for w in norm(said))
        words: set[str] = set(label_words)
        if entity.colour:
            words.update(norm(tokens(entity.colour)))
        for class_name in entity.class_names:
            words.update(norm(tokens(class_name)))
        syn = self.synonyms
        words.update(o[0] for w in tuple(words) for o in syn.of((w,)) if len(o) == 1)
        names = self.names(entity)
        qualifiers = frozenset(words)
        return _Entry(names, qualifiers, label_words, qualifiers.union(*(n.words for n in names)))


class _Entry(NamedTuple):
    """What one entity adds to the indexes (kept per entity, so an update can take it out again)."""

    names: list[Name]
    #: Qualifying words: label words, colour, class names ("red" in "red cup"), their synonyms.
    qualifiers: frozenset[str]
    label_words: frozenset[str]
    #: Its share of the vocabulary: every word of its names and qualifiers.
    words: frozenset[str]


_NO_ENTRY = _Entry([], frozenset(), frozenset(), frozenset())


def _own(changes: dict[Any, Any], source: Mapping[Any, Any], key: Any, empty: Callable[[], Any]) -> Any:
    """The copy of `source[key]` this update writes to (copied once)."""
    if key not in changes:
        changes[key] = source[key].copy() if key in source else empty()
    return changes[key]


def _reuse(kept: tuple[Entity, _Entry] | None, entity: Entity, said: _Said) -> _Entry:
    return kept[1] if kept is not None and kept[0] == entity else said.entry(entity)


class LexiconCache:
    """One lexicon per snapshot revision (snapshots are immutable, so this is safe to share), its
    names said in `lang`."""

    def __init__(self, lang: Language) -> None:
        self.lang = lang
        self._lock = threading.Lock()
        self._lexicon: Lexicon | None = None
        # The lemma tables and the synonyms file load on first use (a few hundred ms): here, when
        # an engine is made, rather than inside its first turn's deadline.
        singular("cups")
        synonyms(lang, phrase)

    def get(self, snapshot: Snapshot) -> Lexicon:
        with self._lock:
            lex = self._lexicon
        if lex is not None and lex.snapshot is snapshot:
            return lex
        lex = Lexicon(snapshot, self.lang, lex)
        with self._lock:
            self._lexicon = lex
        return lex
