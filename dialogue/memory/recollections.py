"""Each person's `lastSpokeAt` and `dialogueSummary`, kept in memory from the KB's commits.

A turn of a model that reads prompts gets the speaker's note (dialogue.memory.people): reading it
from this index costs a dictionary lookup on the event loop instead of two KB queries off it. The
index is loaded once, then follows every commit's changes to the two properties in the robot's
model (the listener runs under the KB's lock, so it only updates the dictionary); a cleared KB
empties it. A KB that reports no commits (a read replica) has no index: callers ask the KB.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from rdflib import URIRef

from kb.protocol import KnowledgeBase
from kb.terms import ORO, format_term, shorten

LAST_SPOKE = URIRef(ORO + "lastSpokeAt")
SUMMARY = URIRef(ORO + "dialogueSummary")
_FIELDS = {LAST_SPOKE: 0, SUMMARY: 1}

Entry = tuple[str | None, str]


class Recollections:
    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._entries: dict[str, Entry] = {}
        self._unwatch: Callable[[], None] | None = None

    @classmethod
    def follow(cls, kb: KnowledgeBase) -> Recollections | None:
        """The index of `kb`, following its commits; None when it reports none."""
        on_commit = getattr(kb, "on_commit", None)
        if not callable(on_commit):
            return None
        index = cls()
        with kb.lock:  # no commit between the load and the listener
            for prop, field in _FIELDS.items():
                for row in kb.find([f"?p {format_term(prop)} ?v"]):
                    index._set(str(row["p"]), field, str(row["v"]))
            index._unwatch = on_commit(index._commit)
        return index

    def get(self, person: str) -> Entry:
        with self._lock:
            return self._entries.get(person, (None, ""))

    def close(self) -> None:
        if self._unwatch is not None:
            self._unwatch()
            self._unwatch = None

    def _commit(self, commit: Any) -> None:
        if getattr(commit, "cleared", None) is not None:
            with self._lock:
                self._entries.clear()
            return
        for delta in commit.deltas:
            if delta.model != "default":
                continue
            for triples, present in ((delta.removed, False), (delta.added, True)):
                for s, p, o in triples:
                    field = _FIELDS.get(p)
                    if field is not None:
                        self._set(str(shorten(s)), field, str(o) if present else None)

    def _set(self, person: str, field: int, value: str | None) -> None:
        with self._lock:
            last, summary = self._entries.get(person, (None, ""))
            entry = (value, summary) if field == 0 else (last, value or "")
            if entry == (None, ""):
                self._entries.pop(person, None)
            else:
                self._entries[person] = entry
