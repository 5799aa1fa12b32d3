"""What an entity is called: every name its labels, id and class names give it, in a language.

Names come from the KB only (instance labels, ids, class labels of all classes including inferred
superclasses, readable class ids) and from the language's lexicon file's other ways of saying them
(`synonyms`); all matching is on whole, singular words (D11). `lexicon` indexes them.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from functools import lru_cache
from typing import NamedTuple

from lemminflect import getLemma

from dialogue.reference.english import tokens, word_set
from dialogue.reference.snapshot import Entity
from dialogue.reference.synonyms import Synonyms, synonyms
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of

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
    return tuple(map(singular, words))  # (no generator frame: a first build norms every name)


def phrase(text: str) -> tuple[str, ...]:
    """A text as normalised words (the form names are indexed in)."""
    return norm(_tokens(text))


@lru_cache(maxsize=4096)
def _tokens(text: str) -> tuple[str, ...]:
    """`tokens` of a name's text, kept: an entity's names and entry read each of its labels and
    class names some six times over, and a first build does so for every entity of the KB."""
    return tuple(tokens(text))


class Name(NamedTuple):
    """One name of an entity (a tuple: hashed in C, and a class word's bucket holds thousands)."""

    words: tuple[str, ...]
    entity: str
    source: str  # "label", "id", "class", "head", "joined", or the lexicon file's "synonym", "kind"

    @property
    def lexical(self) -> bool:
        """Whether the name comes from the lexicon file rather than the KB's own names."""
        return self.source in {"synonym", "kind"}


class Entry(NamedTuple):
    """What one entity adds to the indexes (kept per entity, so an update can take it out again)."""

    names: list[Name]
    #: Qualifying words: label words, colour, class names ("red" in "red cup"), their synonyms.
    qualifiers: frozenset[str]
    label_words: frozenset[str]
    #: Its share of the vocabulary: every word of its names and qualifiers.
    words: frozenset[str]


NO_ENTRY = Entry([], frozenset(), frozenset(), frozenset())


class Naming:
    """What entities are called in a language: their names, said as its lexicon file, titles and
    number words allow."""

    def __init__(self, lang: Language) -> None:
        self.lang = lang
        self.synonyms: Synonyms = synonyms(lang, phrase)
        self.determiners = lang.words.determiners
        self.compound_heads = lang.words.compound_heads
        self.head_sizes = sorted({len(head) for head in self.compound_heads if len(head) > 2}, reverse=True)
        #: Each title to the other words said for it ("mister" for "mr").
        self.titles = {w: tuple(o for o in group if o != w) for group in lang.words.titles for w in group}

    def names(self, entity: Entity, kind: bool = True) -> list[Name]:
        """Every name of the entity; with ``kind`` False, its own only (none of its class names)."""
        out: list[Name] = []
        seen: set[tuple[str, ...]] = set()
        class_names = entity.class_names if kind else ()

        def add(text: str, source: str) -> None:
            words = norm(_tokens(text))
            if words and words not in seen and not (len(words) == 1 and words[0] in self.determiners):
                seen.add(words)
                out.append(Name(words, entity.id, source))

        for label in entity.labels:
            add(label, "label")
            numbered = self.lang.words.other_numbers(_tokens(label))
            if numbered is not None:  # "screen two" for "screen 2", "table 9" for "table nine"
                add(" ".join(numbered), "label")
            for other in self.otherwise(_tokens(label)):
                add(" ".join(other), "label")
        add(entity.id, "id")
        for class_name in class_names:
            add(class_name, "class")
        # The head noun of a multi-word name names the thing too: "the mug" for the "green mug",
        # "the remote" for the "TV remote"; the other words stay usable as qualifiers.
        for text in (*entity.labels, *class_names):
            words = _tokens(text)
            # "food or drink" is no drink; "cheese and onion crisps" are crisps
            if len(words) > 1 and words[-2] not in self.lang.words.coordinators:
                add(words[-1], "head")
            if len(words) == 2 and all(w.isalpha() for w in words):
                add("".join(words), "joined")  # "the eyeglass" for the "eye glass" (the converse of names_at)
            tail = self._compound_head(words[-1]) if words else None
            if tail is not None:  # "the bench" for the "workbench", yielding to a bench of the KB's own
                add(" ".join((*words[:-1], tail)) if len(words) > 1 else tail, "kind")
        for text in (*entity.labels, *class_names):
            for name, source in self._lexical(text):
                add(name, source)
        return out

    def _lexical(self, text: str) -> Iterator[tuple[str, str]]:
        """Other ways of saying a name or its ending ("cell phone" for the "mobile phone", "the
        fridge" for the "kitchen refrigerator"), and the general names of its kind ("the bag" for
        the "handbag", "a drink" for the "lemonade"): the lexicon file's, which yield to the KB's
        own names (`Name.lexical`)."""
        syn = self.synonyms
        said = phrase(text)
        # Only the endings a synonym may be: each one tried is a copy (a label of 30,000 words
        # once made every split of it one, minutes of work for every turn).
        for k in range(max(0, len(said) - syn.longest), len(said)):
            for other in syn.of(said[k:]):
                yield " ".join((*said[:k], *other)), "synonym"
                if k:
                    yield " ".join(other), "synonym"
            alike = (said[k:], *syn.of(said[k:]))
            for general in (g for o in alike for g in syn.broader_than(o)):
                yield " ".join(general), "kind"

    def _compound_head(self, word: str) -> str | None:
        """The general noun a closed compound ends with ("workbench": "bench"), if it is one of the
        language's compound heads after a word of its own (of 3 letters or more); None otherwise.
        Only the endings as long as a head are tried, the longest first: trying every split copied
        the word's rest at each, which a label of a million letters made minutes of work for every
        turn."""
        for size in self.head_sizes:
            k = len(word) - size
            if k >= 3 and word[k:] in self.compound_heads and lemmas_of(word[:k]):
                return word[k:]
        return None

    def _compound_modifiers(self, labels: Sequence[str]) -> list[str]:
        """The food or drink a label's closed compound of a container starts with ("tea" of the
        "china teacup"): a word of its label as "tea" is of the "big tea mug", so that "my tea"
        names the teacup as it names the tea mug (`words.toml`: `held`; "the book" never names a
        "bookcase")."""
        out = []
        held = self.lang.words.held
        for label in labels:
            words = _tokens(label)
            tail = self._compound_head(words[-1]) if words else None
            if tail is None or tail not in self.lang.words.containers:
                continue
            modifier = words[-1][: -len(tail)]
            if any(len(kind) == 1 and kind[0] in held for kind in self.synonyms.broader_than((modifier,))):
                out.append(modifier)
        return out

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

    def entry(self, entity: Entity, kind: bool = True) -> Entry:
        """What the entity adds to a lexicon's indexes; with ``kind`` False, its own names and
        words only (a lexicon indexes its kind's once for all the entities of that kind)."""
        label_words = frozenset((*(w for label in entity.labels
                                   for said in (_tokens(label), *self.otherwise(_tokens(label)))
                                   for w in norm(said)),
                                 *self._compound_modifiers(entity.labels)))
        words: set[str] = set(label_words)
        if entity.colour:
            words.update(phrase(entity.colour))
        for class_name in entity.class_names if kind else ():
            words.update(phrase(class_name))
        syn = self.synonyms
        words.update(o[0] for w in tuple(words) for o in syn.of((w,)) if len(o) == 1)
        names = self.names(entity, kind)
        qualifiers = frozenset(words)
        return Entry(names, qualifiers, label_words, qualifiers.union(*(n.words for n in names)))
