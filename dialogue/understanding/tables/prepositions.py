"""The model of `prepositions.toml`: the one table of prepositions."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from pydantic import ConfigDict

from dialogue.understanding.tables.base import (
    Table,
    Words,
    WordSet,
)


class Preposition(Table):
    """One row of the preposition table (its columns are described in prepositions.toml)."""

    model_config = ConfigDict(frozen=True, extra="forbid", alias_generator=lambda n: n.replace("_", "-"))

    uses: WordSet = frozenset()
    said_back: str | None = None
    relations: frozenset[str] = frozenset()
    evidence: frozenset[str] = frozenset()
    states: str | None = None
    says: str | None = None
    reads_as: str | None = None


class Prepositions(Table):
    """`prepositions.toml`: one table of prepositions (single words and phrases), in order."""

    prepositions: dict[str, Preposition] = {}

    def having(self, use: str) -> tuple[Words, ...]:
        """The prepositions that have a use, as phrases, in the table's order."""
        return tuple(tuple(p.split()) for p, row in self.prepositions.items() if use in row.uses)

    def words(self, use: str) -> frozenset[str]:
        """The one-word prepositions that have a use."""
        return frozenset(p[0] for p in self.having(use) if len(p) == 1)

    def longest_first(self, use: str) -> tuple[Words, ...]:
        """The prepositions that have a use, longest first (then in the table's order): the first
        that a text starts with is the longest it starts with ("on top of" before "on")."""
        return tuple(sorted(self.having(use), key=len, reverse=True))

    def row(self, words: Sequence[str]) -> Preposition | None:
        return self.prepositions.get(" ".join(words))

    def column(self, name: str) -> dict[str, Any]:
        """Each preposition that has a value in a column, with it ("said_back": "beside" -> "next to")."""
        return {p: v for p, row in self.prepositions.items() if (v := getattr(row, name))}

    def phrase_column(self, name: str) -> dict[Words, Any]:
        """A column keyed by each preposition's words ("next to" -> ("next", "to")): what a stage
        matches against the words of an utterance."""
        return {tuple(p.split()): v for p, v in self.column(name).items()}
