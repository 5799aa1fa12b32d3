"""Perception wins afterwards too: a perceived value retracts the told values it contradicts.

"The keys are in the drawer" was adopted; later the robot sees the keys on the table: the scene
asserts `keys_1 isOn table_1` (without a record of having been told), and the told place goes,
with its record. A perceived zone that holds the told place contradicts nothing (the keys in the
kitchen, the drawer being in the kitchen). The KB calls the commit listener under its lock, so it
only queues the changed facts of the places the memory keeps (name, owner, location, preference); a
worker thread checks them against what was told (dialogue.memory.learn.Memory.reconcile). A told
fact that anyone retracts takes its record with it (Memory.forget_if_gone): a record never outlives
its fact, or the same fact perceived later would pass for told, and a statement could replace it.
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from typing import Any

from rdflib import Literal, URIRef

from dialogue.follower import CommitFollower
from dialogue.memory.claims import BY_PROPERTY
from dialogue.memory.learn import Memory
from kb.terms import format_term, parse_name, shorten

log = logging.getLogger(__name__)

#: Facts queued between the KB's commits and the worker (past it, the newest are not checked).
MAX_PENDING = 10_000
_WATCHED = frozenset(parse_name(prop, "property") for prop in BY_PROPERTY)
#: (subject, property, value, literal, added) of a change to a watched place.
Change = tuple[str, str, str, bool, bool]


class Reconciler(CommitFollower[Change]):
    """Follows the KB's commits (not on a read replica: the writer does it); `join` waits until
    every change queued so far has been checked."""

    def __init__(self, memory: Memory) -> None:
        super().__init__(memory.kb, "memory-reconcile", _changes, self._check, MAX_PENDING)
        self.memory = memory

    def _check(self, change: Change) -> None:
        subject, prop, value, literal, added = change
        if not added:
            self.memory.forget_if_gone(subject, prop, value, literal)
        elif retracted := self.memory.reconcile(subject, prop, value, literal):
            log.info("perception of %s %s retracted %d told value(s)", subject, prop, retracted)


def _changes(commit: Any) -> Iterator[Change]:
    for delta in commit.deltas:
        if delta.model != "default":
            continue
        for triples, added in ((delta.asserted_added, True), (delta.asserted_removed, False)):
            for s, p, o in triples:
                if p in _WATCHED and isinstance(s, URIRef):
                    literal = isinstance(o, Literal)
                    value = str(o) if literal else format_term(o)
                    yield str(shorten(s)), format_term(p), value, literal, added
