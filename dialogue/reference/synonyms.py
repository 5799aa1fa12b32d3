"""Other ways of saying a name: synonyms, kinds and general names, as data (a language's
`lexicon.txt`, `dialogue/understanding/lang/en/lexicon.txt`: "a = b", "kind < general", "general >
kind kind").

The file is parsed once per language, on first use. Phrases are normalised by the caller's function
(the lexicon's noun lemmas), so "fridges" and "refrigerators" meet.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property

from dialogue.understanding.language import Language

Phrase = tuple[str, ...]
Normaliser = Callable[[str], Phrase]


class SynonymError(ValueError):
    """A line of the synonyms file that is not a group; the message names the line."""


@dataclass(frozen=True)
class Synonyms:
    #: Each phrase to the other phrases that may name what it names.
    others: Mapping[Phrase, tuple[Phrase, ...]]
    #: A kind to the more general names it may be said by ("handbag" -> "bag", "lemonade" ->
    #: "drink"): a handbag is always a bag ("kind < general" and "general > kind" lines).
    broader: Mapping[Phrase, tuple[Phrase, ...]]
    #: A kind to the general names of things that may be one ("paperback" -> "book"): a guess,
    #: tried only when nothing has the specific name ("kind < general" lines only: "the lemonade"
    #: is no other drink).
    general: Mapping[Phrase, tuple[Phrase, ...]]

    @cached_property
    def longest(self) -> int:
        """The most words of a phrase `of` or `broader_than` knows: a longer one has nothing."""
        return max((len(p) for p in (*self.others, *self.broader)), default=0)

    def of(self, phrase: Sequence[str]) -> tuple[Phrase, ...]:
        return self.others.get(tuple(phrase), ())

    def kind_of(self, phrase: Sequence[str]) -> tuple[Phrase, ...]:
        return self.general.get(tuple(phrase), ())

    def broader_than(self, phrase: Sequence[str]) -> tuple[Phrase, ...]:
        return self.broader.get(tuple(phrase), ())


def parse(text: str, normalise: Normaliser) -> Synonyms:
    others: dict[Phrase, list[Phrase]] = defaultdict(list)
    broader: dict[Phrase, list[Phrase]] = defaultdict(list)
    general: dict[Phrase, list[Phrase]] = defaultdict(list)
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if "<" in line or ">" in line:
            guess = "<" in line  # "kind kind < general"; "general > kind kind" names no kind
            if guess:
                kinds, _, wider = line.partition("<")
            else:
                wider, _, kinds = line.partition(">")
            specific = [normalise(w) for w in kinds.split()]
            target = normalise(wider)
            if not specific or not target or "=" in line or line.count("<") + line.count(">") > 1:
                raise SynonymError(
                    f"line {n}: expected 'kind kind < general' or 'general > kind kind', got {raw!r}")
            for kind in specific:
                broader[kind].append(target)
                if guess:
                    general[kind].append(target)
            continue
        group = [normalise(p) for p in line.split("=")]
        if len(group) < 2 or not all(group):
            raise SynonymError(f"line {n}: expected 'a = b [= c ...]', got {raw!r}")
        for phrase in group:
            others[phrase].extend(p for p in group if p != phrase)

    def frozen(mapping: dict[Phrase, list[Phrase]]) -> dict[Phrase, tuple[Phrase, ...]]:
        return {k: tuple(dict.fromkeys(v)) for k, v in mapping.items()}

    return Synonyms(frozen(others), frozen(broader), frozen(general))


def synonyms(lang: Language, normalise: Normaliser) -> Synonyms:
    """The language's synonyms, normalised with `normalise` (parsed on first use, kept with the
    language)."""
    return lang.derived(_Parsed(normalise))


@dataclass(frozen=True)
class _Parsed:
    """The synonyms of a language normalised one way (a key of the language's derived tables)."""

    normalise: Normaliser

    def __call__(self, lang: Language) -> Synonyms:
        return parse(lang.lexicon, self.normalise)
