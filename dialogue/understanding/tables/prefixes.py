"""How a stage looks a table of phrases up at a text's start (greetings, conditions, leads): the
table indexed by its phrases' first word, made once with a language's derived tables."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence

from dialogue.understanding.tables.base import Words


class Prefixes:
    """A table of word sequences, indexed by their first word (made once, with a language's derived
    tables): which of them a text starts with, in the table's order, looked up rather than each
    one tested (tested one by one, the prefix tables cost ~350 calls of a ~2,900-call rules turn)."""

    def __init__(self, table: Iterable[Sequence[str]]) -> None:
        self.table: tuple[Words, ...] = tuple(tuple(p) for p in table)
        self._by_first: dict[str, list[Words]] = {}
        for p in self.table:
            self._by_first.setdefault(p[0] if p else "", []).append(p)
        #: An empty prefix starts every text: such a table is scanned, to keep the table's order.
        self._scan = "" in self._by_first

    def __iter__(self) -> Iterator[Words]:
        return iter(self.table)

    def __len__(self) -> int:
        return len(self.table)

    def of(self, words: Sequence[str], at: int = 0) -> list[Words]:
        """The prefixes the words start with (from the word at `at`), in the table's order."""
        if self._scan:
            return [p for p in self.table if tuple(words[at : at + len(p)]) == p]
        head = words[at : at + 1]  # (a slice and a test, no call: most words start no prefix)
        if not head or head[0] not in self._by_first:
            return []
        return [p for p in self._by_first[head[0]] if tuple(words[at : at + len(p)]) == p]

    def first(self, words: Sequence[str], at: int = 0) -> Words | None:
        """The first prefix of the table the words start with (from the word at `at`), if any."""
        head = words[at : at + 1]  # (as `of`, without its call: asked at every word of some stages)
        if self._scan or (head and head[0] in self._by_first):
            found = self.of(words, at)
            return found[0] if found else None
        return None
