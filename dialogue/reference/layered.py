"""An immutable mapping that a small change copies in time proportional to the change.

Snapshots and lexicons are immutable per KB revision but differ from the previous one by a few
entries; copying a dict of every entity per revision would make a turn cost the size of the world.
`Layered` shares a base dict with its predecessors and keeps the changes in a small top dict;
when the top grows past a fraction of the base, the next version folds it into a new base (one
copy, amortised over the changes that made the top grow).
"""

from __future__ import annotations

from bisect import bisect_left, insort
from collections.abc import Iterable, Iterator, Mapping
from typing import Any, Generic, TypeVar

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

    def get(self, key: K, default: Any = None) -> Any:
        # Mapping.get goes through __getitem__ and a KeyError: resolving a class word looks up
        # thousands of entities per phrase.
        top = self._top
        if key in top:
            value = top[key]
            return default if isinstance(value, Gone) else value
        return self._base.get(key, default)

    def __contains__(self, key: object) -> bool:
        if key in self._top:
            return not isinstance(self._top[key], Gone)
        return key in self._base

    def __len__(self) -> int:
        return self._len

    def __iter__(self) -> Iterator[K]:
        top, base = self._top, self._base
        gone = [key for key, value in top.items() if isinstance(value, Gone)]
        if gone:  # only then is each base key looked up (a layered bucket may hold thousands)
            dropped = set(gone)
            yield from (key for key in base if key not in dropped)
        else:
            yield from base
        for key, value in top.items():
            if key not in base and not isinstance(value, Gone):
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


#: A bucket (a set of keys, as a mapping to None) past this size is layered: changing one member
#: of a bucket that a class name shares with thousands of entities must not copy it.
SMALL_BUCKET = 64


def rebucket(bucket: Mapping[K, None] | None, changes: Mapping[K, Gone | None]) -> Mapping[K, None] | Gone:
    """``bucket`` with ``changes`` applied (None: add the key, ``GONE``: remove it), sharing what
    it can with ``bucket``; ``GONE`` when nothing is left."""
    new: Mapping[K, None]
    if isinstance(bucket, Layered):
        new = bucket.evolve(changes)
    else:
        members = dict(bucket) if bucket else {}
        for key, value in changes.items():
            if isinstance(value, Gone):
                members.pop(key, None)
            else:
                members[key] = None
        new = layered(members)
    return new if len(new) else GONE


def layered(members: dict[K, None]) -> Mapping[K, None]:
    """A new bucket: a dict while small, layered once large."""
    return Layered(members) if len(members) > SMALL_BUCKET else members


#: Items per chunk of a `SortedChunks` (a chunk splits at twice this).
CHUNK = 256


class SortedChunks(Generic[K]):
    """An immutable sorted sequence (of comparable items) that an insertion or a removal copies
    in time proportional to the number of chunks plus one chunk, not to the sequence: the
    deterministic order of the entities, shared by every snapshot it did not change in."""

    __slots__ = ("_chunks", "_lasts", "_len")

    def __init__(self, items: Iterable[K] = ()) -> None:
        ordered: list[Any] = sorted(items)
        self._chunks: list[list[Any]] = [ordered[i : i + CHUNK] for i in range(0, len(ordered), CHUNK)]
        self._lasts: list[Any] = [chunk[-1] for chunk in self._chunks]
        self._len = len(ordered)

    def __len__(self) -> int:
        return self._len

    def __iter__(self) -> Iterator[K]:
        for chunk in self._chunks:
            yield from chunk

    def before(self, bound: Any) -> Iterator[K]:
        """The items less than ``bound``, in order."""
        for chunk in self._chunks:
            if chunk[0] >= bound:
                return
            if chunk[-1] < bound:
                yield from chunk
            else:
                yield from chunk[: bisect_left(chunk, bound)]
                return

    def insert(self, item: K) -> SortedChunks[K]:
        if not self._chunks:
            return self._with([], 0, [[item]], 1)
        at = min(bisect_left(self._lasts, item), len(self._chunks) - 1)
        chunk = list(self._chunks[at])
        insort(chunk, item)
        parts = [chunk] if len(chunk) <= 2 * CHUNK else [chunk[:CHUNK], chunk[CHUNK:]]
        return self._with(self._chunks, at, parts, 1)

    def remove(self, item: K) -> SortedChunks[K]:
        """Without ``item``, which must be there."""
        at = bisect_left(self._lasts, item)
        chunk = list(self._chunks[at])
        del chunk[bisect_left(chunk, item)]
        return self._with(self._chunks, at, [chunk] if chunk else [], -1)

    def _with(self, chunks: list[list[Any]], at: int, parts: list[list[Any]], grew: int) -> SortedChunks[K]:
        new: SortedChunks[K] = SortedChunks.__new__(SortedChunks)
        new._chunks = [*chunks[:at], *parts, *chunks[at + 1 :]]
        new._lasts = [chunk[-1] for chunk in new._chunks]
        new._len = self._len + grew
        return new

