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
import queue
import threading
from collections.abc import Callable
from typing import Any

from rdflib import Literal, URIRef

from dialogue.memory.claims import BY_PROPERTY
from dialogue.memory.learn import Memory
from kb import KbError
from kb.terms import format_term, parse_name, shorten

log = logging.getLogger(__name__)

#: Facts queued between the KB's commits and the worker (past it, the newest are not checked).
MAX_PENDING = 10_000
_WATCHED = frozenset(parse_name(prop, "property") for prop in BY_PROPERTY)
_STOP = ("", "", "", False, False)


class Reconciler:
    def __init__(self, memory: Memory) -> None:
        self.memory = memory
        #: (subject, property, value, literal, added) of each change to a watched place.
        self._pending: queue.Queue[tuple[str, str, str, bool, bool]] = queue.Queue(MAX_PENDING)
        self._thread: threading.Thread | None = None
        self._unwatch: Callable[[], None] | None = None

    def start(self) -> bool:
        """Follow the KB's commits; False when it reports none (a read replica: the writer does it)."""
        on_commit = getattr(self.memory.kb, "on_commit", None)
        if not callable(on_commit):
            return False
        self._thread = threading.Thread(target=self._work, name="memory-reconcile", daemon=True)
        self._thread.start()
        self._unwatch = on_commit(self._commit)
        return True

    def stop(self) -> None:
        if self._unwatch is not None:
            self._unwatch()
            self._unwatch = None
        if self._thread is not None:
            self._pending.put(_STOP)
            self._thread.join(timeout=5)
            self._thread = None

    def join(self) -> None:
        """Wait until every fact queued so far has been checked."""
        self._pending.join()

    def _commit(self, commit: Any) -> None:
        for delta in commit.deltas:
            if delta.model != "default":
                continue
            for triples, added in ((delta.asserted_added, True), (delta.asserted_removed, False)):
                for s, p, o in triples:
                    if p in _WATCHED and isinstance(s, URIRef):
                        literal = isinstance(o, Literal)
                        value = str(o) if literal else format_term(o)
                        try:
                            self._pending.put_nowait((str(shorten(s)), format_term(p), value, literal, added))
                        except queue.Full:
                            log.warning("memory: too many changes at once; %s %s not checked", shorten(s), p)

    def _work(self) -> None:
        while (item := self._pending.get()) != _STOP:
            subject, prop, value, literal, added = item
            try:
                if not added:
                    self.memory.forget_if_gone(subject, prop, value, literal)
                elif retracted := self.memory.reconcile(subject, prop, value, literal):
                    log.info("perception of %s %s retracted %d told value(s)", subject, prop, retracted)
            except KbError as exc:
                log.warning("memory: told values not reconciled with %s %s: %s", subject, prop, exc)
            finally:
                self._pending.task_done()
        self._pending.task_done()
