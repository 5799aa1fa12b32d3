"""Statements with a lifespan: when each expires, and which are due (kb-compat §3.5).

Expiry is by wall clock so that a journal can carry it across restarts. Re-adding a statement
with a lifespan refreshes it; re-adding it without one makes it permanent.
"""

from __future__ import annotations

import heapq
from collections.abc import Callable, Iterable

from kb.terms import Triple

Key = tuple[str, Triple]
#: An expiry a commit set (0.0: made permanent again), as the journal records it.
Change = tuple[str, Triple, float]


class Expiries:
    """Expiry times of (model, triple) pairs, with a heap for the next one due."""

    def __init__(self) -> None:
        self._when: dict[Key, float] = {}
        self._heap: list[tuple[float, int, Key]] = []
        self._tie = 0

    def __len__(self) -> int:
        return len(self._when)

    def set(self, model: str, triple: Triple, at: float) -> None:
        key = (model, triple)
        self._when[key] = at
        self._tie += 1
        heapq.heappush(self._heap, (at, self._tie, key))

    def discard(self, model: str, triple: Triple) -> None:
        self._when.pop((model, triple), None)

    def expires_at(self, model: str, triple: Triple) -> float | None:
        return self._when.get((model, triple))

    def next_due(self) -> float | None:
        """The earliest live expiry time, dropping heap entries made stale by refreshes."""
        heap = self._heap
        while heap:
            at, _, key = heap[0]
            if self._when.get(key) == at:
                return at
            heapq.heappop(heap)
        return None

    def pop_due(self, now: float) -> list[Key]:
        due: list[Key] = []
        heap = self._heap
        while heap and heap[0][0] <= now:
            at, _, key = heapq.heappop(heap)
            if self._when.get(key) == at:
                del self._when[key]
                due.append(key)
        return due

    def remember(self, model: str, triples: Iterable[Triple], before: dict[Key, float | None]) -> None:
        """Note in ``before`` the expiry of each of ``triples`` that has one (what undoing a
        batch puts back); a KB without lifespans pays nothing per triple."""
        if not self._when:
            return
        when = self._when
        for triple in triples:
            at = when.get((model, triple))
            if at is not None:
                before.setdefault((model, triple), at)

    def stamp(self, model: str, added: Iterable[Triple], lifespan: Callable[[Triple], float], now: float,
              before: dict[Key, float | None], changes: list[Change]) -> None:
        """Give each added triple its lifespan's expiry, or make it permanent again if it had one
        and has none now; ``before`` and ``changes`` as for ``remember`` and the journal."""
        for triple in added:
            seconds = lifespan(triple)
            if seconds > 0:
                before.setdefault((model, triple), None)
                self.set(model, triple, now + seconds)
                changes.append((model, triple, now + seconds))
            elif self._when and (model, triple) in self._when:
                before.setdefault((model, triple), self._when[(model, triple)])
                self.discard(model, triple)
                changes.append((model, triple, 0.0))

    def items(self) -> list[tuple[str, Triple, float]]:
        return [(model, triple, at) for (model, triple), at in self._when.items()]

    def clear(self) -> None:
        self._when.clear()
        self._heap.clear()
