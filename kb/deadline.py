"""A read's time budget: one deadline covers waiting for the KB lock and evaluating the query.

The KB lock is held by every read and write, so a read that ran unbounded would hold back every
writer (and ``/health``) for as long as it runs. A read given a deadline waits for the lock only
until the deadline and then reads through ``TimedIndex``, which raises ``QueryTimeout`` from the
next index access past the deadline: the join and rdflib's SPARQL engine both read the index
constantly, so even an aggregate over a cartesian product stops on time and releases the lock.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

from kb.errors import KbError, QueryTimeout
from kb.index import TripleIndex
from kb.terms import Node, Triple

# Reading the clock costs about as much as producing one triple: look every this many triples.
_CHECK_EVERY = 256


class Deadline:
    """A point in time (monotonic clock) after which a read stops."""

    __slots__ = ("_at", "seconds")

    def __init__(self, seconds: float) -> None:
        if not seconds > 0:
            raise KbError(f"a query's time budget must be a positive number of seconds, got {seconds!r}")
        self.seconds = seconds
        self._at = time.monotonic() + seconds

    @classmethod
    def after(cls, seconds: float | None) -> Deadline | None:
        return None if seconds is None else cls(seconds)

    def earlier(self, other: Deadline | None) -> Deadline:
        return other if other is not None and other._at < self._at else self

    def remaining(self) -> float:
        return max(0.0, self._at - time.monotonic())

    def check(self) -> None:
        if time.monotonic() > self._at:
            raise QueryTimeout(self.seconds)


@dataclass(frozen=True)
class Budget:
    """The bounds of a subscription's every evaluation: seconds (``None``: unbounded) and
    distinct rows (``None``: unbounded)."""

    timeout: float | None = None
    max_rows: int | None = None

    def __post_init__(self) -> None:
        Deadline.after(self.timeout)  # refuses a budget that is not a positive number
        rows = self.max_rows
        if rows is not None and (isinstance(rows, bool) or not isinstance(rows, int) or rows < 1):
            raise KbError(f"max_rows must be a positive integer, got {rows!r}")

    @property
    def bounded(self) -> bool:
        return self.timeout is not None or self.max_rows is not None


UNBOUNDED = Budget()


@contextmanager
def holding(lock: threading.RLock, deadline: Deadline | None) -> Iterator[None]:
    """Hold ``lock``, waiting for it no longer than the deadline allows."""
    if deadline is None:
        with lock:
            yield
        return
    if not lock.acquire(timeout=deadline.remaining()):
        raise QueryTimeout(deadline.seconds, waiting=True)
    try:
        yield
    finally:
        lock.release()


def timed(index: TripleIndex, deadline: Deadline | None) -> TripleIndex | TimedIndex:
    """The index, read through ``TimedIndex`` when there is a deadline."""
    return index if deadline is None else TimedIndex(index, deadline)


class TimedIndex:
    """The read paths of a ``TripleIndex`` that the join and the SPARQL store use, checking the
    deadline as they go."""

    __slots__ = ("_deadline", "_index")

    def __init__(self, index: TripleIndex, deadline: Deadline) -> None:
        self._index = index
        self._deadline = deadline

    def __len__(self) -> int:
        return len(self._index)

    def __contains__(self, triple: Triple) -> bool:
        return triple in self._index

    def canonical(self, term: Node) -> Node:
        return self._index.canonical(term)

    def count(self, s: Node | None, p: Node | None, o: Node | None) -> int:
        return self._index.count(s, p, o)

    def scan(self, s: Node | None, p: Node | None, o: Node | None) -> Iterator[Triple]:
        return self._checked(self._index.scan(s, p, o))

    def triples(self, s: Node | None, p: Node | None, o: Node | None) -> Iterator[Triple]:
        return self._checked(self._index.triples(s, p, o))

    def _checked(self, triples: Iterator[Triple]) -> Iterator[Triple]:
        check = self._deadline.check
        check()  # a join calls scan once per partial binding: each call is a unit of work
        for n, triple in enumerate(triples, 1):
            if not n % _CHECK_EVERY:
                check()
            yield triple
