"""An immutable mapping that a small change copies in time proportional to the change.

Snapshots and lexicons are immutable per KB revision but differ from the previous one by a few
entries; copying a dict of every entity per revision would make a turn cost the size of the world.
`Layered` shares a base dict with its predecessors and keeps the changes in a small top dict;
when the top grows past a fraction of the base, the next version folds it into a new base (one
copy, amortised over the changes that made the top grow).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Generic, TypeVar

K = TypeVar("K")
V = TypeVar("V")

#: The top is folded into a new base once it holds more than this share of the base's entries.
FOLD_SHARE = 16
MIN_TOP = 256


class Gone:
    """Marks a key removed in the top layer."""


GONE = Gone()


class Layered(Mapping[K, V], Generic[K, V]):
    """Iteration order is not insertion order (folded keys keep their base position)."""

    __slots__ = ("_base", "_len", "_top")

    def __init__(self, base: dict[K, V] | None = None) -> None:
        self._base: dict[K, V] = base if base is not None else {}
        self._top: dict[K, V | Gone] = {}
        self._len = len(self._base)

    def __getitem__(self, key: K) -> V:
        if key in self._top:
            value = self._top[key]
            if isinstance(value, Gone):
                raise KeyError(key)
            return value
        return self._base[key]

    def __contains__(self, key: object) -> bool:
        if key in self._top:
            return not isinstance(self._top[key], Gone)
        return key in self._base

    def __len__(self) -> int:
        return self._len

    def __iter__(self) -> Iterator[K]:
        top = self._top
        for key in self._base:
            if not isinstance(top.get(key), Gone):
                yield key
        for key, value in top.items():
            if key not in self._base and not isinstance(value, Gone):
                yield key

    def evolve(self, changes: Mapping[K, V | Gone]) -> Layered[K, V]:
        """A new version with `changes` applied (a value, or `GONE` to remove the key)."""
        new: Layered[K, V] = Layered.__new__(Layered)
        new._base, new._top, new._len = self._base, dict(self._top), self._len
        for key, value in changes.items():
            before, after = key in new, not isinstance(value, Gone)
            new._len += after - before
            if isinstance(value, Gone) and key not in new._base:
                new._top.pop(key, None)
            else:
                new._top[key] = value
        if len(new._top) > max(MIN_TOP, len(new._base) // FOLD_SHARE):
            base = dict(new._base)
            for key, value in new._top.items():
                if isinstance(value, Gone):
                    base.pop(key, None)
                else:
                    base[key] = value
            new._base, new._top = base, {}
        return new
