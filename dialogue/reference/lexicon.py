"""Words and names: tokenising utterances and indexing every name of every entity of a snapshot.

Names come from the KB only (instance labels, ids, class labels of all classes including inferred
superclasses, readable class ids), so a new object is understood as soon as it is in the KB. All
matching is on whole words (D11).
"""

from __future__ import annotations

import re
import threading
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

from lemminflect import getLemma

from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.synonyms import synonyms
from dialogue.rules.words import word_set

_WORD = re.compile(r"[a-z0-9]+(?:'[a-z]+)?")

#: Words that never distinguish a referent.
DETERMINERS = frozenset(
    {
        "the",
        "a",
        "an",
        "some",
        "any",
        "this",
        "that",
        "these",
        "those",
        "my",
        "your",
        "our",
        "its",
        "one",
        "ones",
        "please",
        "thing",
        "there",
        "here",
    }
)


def tokens(text: str) -> list[str]:
    """Lower-case whole words; `cup_1` gives `cup 1`, "don't" stays one word."""
    text = text.lower().replace("\u2019", "'")
    return _WORD.findall(text)


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


@dataclass(frozen=True)
class Name:
    words: tuple[str, ...]
    entity: str
    source: str  # "label", "id" or "class"


@dataclass(frozen=True)
class Mention:
    start: int
    end: int
    entities: frozenset[str]


class Lexicon:
    """All names of a snapshot's entities, indexed by their first (singular) word.

    Built from a `previous` lexicon, the entries of entities that did not change are reused, so a
    KB change costs work proportional to what changed.
    """

    def __init__(self, snapshot: Snapshot, previous: Lexicon | None = None) -> None:
        self.snapshot = snapshot
        self._by_first: dict[str, list[Name]] = defaultdict(list)
        self.attributes: dict[str, frozenset[str]] = {}
        #: Entities by each (singular) word of their own labels, for "the teddy" ("teddy bear").
        self.by_label_word: dict[str, list[str]] = defaultdict(list)
        #: Every (singular) word of every name and qualifier: what the KB can account for.
        self.vocabulary: set[str] = set()
        self._entries: dict[Entity, tuple[list[Name], frozenset[str], frozenset[str]]] = {}
        old = previous._entries if previous is not None else {}
        for entity in snapshot.entities.values():
            entry = old.get(entity) or _entry(entity)
            self._entries[entity] = entry
            for name in entry[0]:
                self._by_first[name.words[0]].append(name)
                self.vocabulary.update(name.words)
            self.vocabulary.update(entry[1])
            self.attributes[entity.id] = entry[1]
            for word in entry[2]:
                self.by_label_word[word].append(entity.id)
        for names in self._by_first.values():
            names.sort(key=lambda n: -len(n.words))

    def names_at(self, words: Sequence[str], start: int) -> list[Name]:
        """Every name that occurs in `words` starting at `start` (longest first)."""
        # Only the words a candidate name spans are normalised: normalising the whole utterance
        # at every start made a long utterance cost quadratic time.
        found = []
        for name in self._by_first.get(singular(words[start]), ()):
            end = start + len(name.words)
            span = words[start:end]
            if end <= len(words) and all(singular(w) == n for w, n in zip(span, name.words, strict=True)):
                found.append(name)
        if start + 1 < len(words):
            # "tea cup" for the "teacup", "tool box" for the "toolbox": a closed compound said apart.
            joined = singular(words[start] + words[start + 1])
            found += [Name((words[start], words[start + 1]), n.entity, n.source)
                      for n in self._by_first.get(joined, ()) if n.words == (joined,)]  # fmt: skip
        return found

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
            ents = frozenset(n.entity for n in names if len(n.words) == length)
            out.append(Mention(i, i + length, ents))
            i += length
        return out

    def knows_word(self, word: str) -> bool:
        return singular(word) in self._by_first

    def knows(self, word: str) -> bool:
        """Whether the word is part of any name or qualifier of the snapshot ("'s" ignored)."""
        word = word[:-2] if word.endswith("'s") else word
        return word.isdigit() or singular(word) in self.vocabulary


def _names(entity: Entity) -> list[Name]:
    out: list[Name] = []
    seen: set[tuple[str, ...]] = set()

    def add(text: str, source: str) -> None:
        words = norm(tokens(text))
        if words and words not in seen and not (len(words) == 1 and words[0] in DETERMINERS):
            seen.add(words)
            out.append(Name(words, entity.id, source))

    for label in entity.labels:
        add(label, "label")
    add(entity.id, "id")
    for class_name in entity.class_names:
        add(class_name, "class")
    # The head noun of a multi-word name names the thing too: "the mug" for the "green mug",
    # "the remote" for the "TV remote"; the other words stay usable as qualifiers.
    for text in (*entity.labels, *entity.class_names):
        words = tokens(text)
        if len(words) > 1:
            add(words[-1], "head")
    # Other ways of saying a name or its ending ("cell phone" for the "mobile phone", "the fridge"
    # for the "kitchen refrigerator").
    syn = synonyms(phrase)
    for text in (*entity.labels, *entity.class_names):
        said = phrase(text)
        for k in range(len(said)):
            for other in syn.of(said[k:]):
                add(" ".join((*said[:k], *other)), "synonym")
                if k:
                    add(" ".join(other), "head")
    return out


def _entry(entity: Entity) -> tuple[list[Name], frozenset[str], frozenset[str]]:
    """Names, qualifying words (label words, colour, class names: "red" in "red cup") and label words."""
    label_words = frozenset(w for label in entity.labels for w in norm(tokens(label)))
    words: set[str] = set(label_words)
    if entity.colour:
        words.update(norm(tokens(entity.colour)))
    for class_name in entity.class_names:
        words.update(norm(tokens(class_name)))
    syn = synonyms(phrase)
    words.update(o[0] for w in tuple(words) for o in syn.of((w,)) if len(o) == 1)
    return _names(entity), frozenset(words), label_words


class LexiconCache:
    """One lexicon per snapshot revision (snapshots are immutable, so this is safe to share)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._lexicon: Lexicon | None = None
        # The lemma tables and the synonyms file load on first use (a few hundred ms): here, when
        # an engine is made, rather than inside its first turn's deadline.
        singular("cups")
        synonyms(phrase)

    def get(self, snapshot: Snapshot) -> Lexicon:
        with self._lock:
            lex = self._lexicon
        if lex is not None and lex.snapshot is snapshot:
            return lex
        lex = Lexicon(snapshot, lex)
        with self._lock:
            self._lexicon = lex
        return lex
