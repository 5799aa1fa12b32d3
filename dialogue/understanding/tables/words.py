"""The model of `words.toml`: closed-class words."""

from __future__ import annotations

from collections.abc import Sequence
from functools import cached_property

from dialogue.understanding.tables.base import (
    Phrases,
    Table,
    WordList,
    Words,
    WordSet,
)


class HeadNounWords(Table):
    """`words.toml` [head_noun]: the words of a noun phrase's head, read by dialogue.reference.headnoun."""

    qualifiers: WordSet = frozenset()
    postures: WordSet = frozenset()
    skipped: WordSet = frozenset()
    clause_words: WordSet = frozenset()
    new_phrase: WordSet = frozenset()
    several: WordSet = frozenset()


class ClosedWords(Table):
    """`words.toml`: closed-class words."""

    determiners: WordSet = frozenset()
    pronouns: WordSet = frozenset()
    personal: WordSet = frozenset()
    neuter: WordSet = frozenset()
    possessives: WordSet = frozenset()
    me: WordSet = frozenset()
    indefinite: WordSet = frozenset()
    colours: WordSet = frozenset()
    positions: WordSet = frozenset()
    parts: WordSet = frozenset()
    containers: WordSet = frozenset()
    materials: WordSet = frozenset()
    held: WordSet = frozenset()
    compound_heads: WordSet = frozenset()
    measures: WordSet = frozenset()
    plural_only: WordSet = frozenset()
    many: WordSet = frozenset()
    relativisers: WordSet = frozenset()
    demonstratives: WordSet = frozenset()
    np_start: WordSet = frozenset()
    owners: dict[str, str] = {}
    objects: dict[str, str] = {}
    sides: dict[str, str] = {}
    wh: WordSet = frozenset()
    titles: Phrases = ()
    numbers: WordSet = frozenset()
    units: WordList = ()
    tens: WordList = ()
    function_words: WordSet = frozenset()
    glue: WordSet = frozenset()
    core_end: WordSet = frozenset()
    not_said: WordSet = frozenset()
    head_noun: HeadNounWords = HeadNounWords()
    unsaid_possessives: WordSet = frozenset()
    one: WordSet = frozenset()
    compared: WordList = ()
    speaker_possessives: WordList = ()
    addressee_possessives: WordList = ()
    coordinators: WordSet = frozenset()
    kin: dict[str, WordList] = {}
    kin_bare: WordSet = frozenset()
    kin_gender: dict[str, str] = {}
    speaker_in_answer: frozenset[str] = frozenset()
    speaker_in_fact: frozenset[str] = frozenset()

    @cached_property
    def spoken_numbers(self) -> dict[str, Words]:
        """Numbers below a hundred as said in words ("7" -> ("seven",), "21" -> ("twenty", "one"))."""
        units = self.units
        tens = {str(20 + 10 * t + u): (w, units[u]) if u else (w,)
                for t, w in enumerate(self.tens) for u in range(10)}  # fmt: skip
        return {**{str(n): (w,) for n, w in enumerate(units)}, **tens}

    @cached_property
    def written(self) -> dict[Words, str]:
        return {words: digits for digits, words in self.spoken_numbers.items()}

    @cached_property
    def any_function_word(self) -> frozenset[str]:
        """Closed-class words in general (pronouns, prepositions, conjunctions, auxiliaries, number
        words): always words of the language, whatever a lexicon of content words says."""
        return self.numbers | self.function_words

    def other_numbers(self, words: Sequence[str]) -> Words | None:
        """The words with each number below a hundred written the other way: "plot 7" -> "plot
        seven", "table nine" -> "table 9", "gate twenty one" -> "gate 21"; None when they have no
        number."""
        written, spoken = self.written, self.spoken_numbers
        out: list[str] = []
        i = 0
        while i < len(words):
            pair, one = tuple(words[i : i + 2]), (words[i],)
            if len(pair) == 2 and pair in written:
                out.append(written[pair])
                i += 2
                continue
            out.extend(spoken.get(words[i]) or ((written[one],) if one in written else one))
            i += 1
        return tuple(out) if out != list(words) else None
