"""The grounder: the current situation snapshot of a KB, maintained from the KB's commits.

The first snapshot asks the KB a handful of set-wide questions (`entities.EntityIndex`); after
that, each commit's added and removed statements update only what they touch, so a turn after a
perception tick costs what the tick changed, not what the KB holds. A full rebuild happens only
when the KB was cleared, its TBox changed, or it does not report its commits (a remote store).

A grounder that `follow`s its KB takes the changes up as they come, on a worker thread of its own
(the first build too), so that a turn finds the snapshot current, or a commit or two behind,
whatever happened while nobody spoke: minutes of perception never become one long turn. The
thread ends when the KB has been quiet for a while and starts again with the next commit.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from typing import Any

from rdflib import RDF

from dialogue.reference.entities import EntityIndex
from dialogue.reference.facts import PERSON_CLASSES, ROBOT_ID, ZONE_CLASSES
from dialogue.reference.snapshot import ROBOT_CLASSES, Entity, Kind, Snapshot, readable_id
from kb.errors import KbError
from kb.gcpause import BULK, paused
from kb.protocol import KnowledgeBase
from kb.tbox import is_schema_triple

log = logging.getLogger(__name__)

__all__ = [
    "PERSON_CLASSES", "ROBOT_CLASSES", "ROBOT_ID", "ZONE_CLASSES",
    "Entity", "Grounder", "Kind", "Snapshot", "build_snapshot", "readable_id",
]  # fmt: skip

#: Past this many pending changed statements between two turns, a full rebuild is cheaper.
MAX_PENDING = 200_000
#: Snapshot steps a snapshot remembers (a lexicon that missed a few revisions still catches up).
MAX_STEPS = 16
#: Seconds a following grounder's worker waits for the next commit before it ends.
IDLE = 2.0

_Triples = list[tuple[Any, Any, Any]]


class Grounder:
    """Builds snapshots from a KB and caches the last one per revision (thread-safe).

    With a KB that reports its commits (``kb.KB.on_commit``), the commits' closure changes are
    queued (the listener runs under the KB's lock, so it only queues) and applied at the next
    snapshot, which a following grounder makes at once (`follow`). ``max_entities`` is kept for
    the prompt's share (see ``relevance``): the snapshot itself holds every entity, so the rules
    understand any of them. ``then`` is called with each new snapshot before anyone can have it
    (the engine's lexicon of it: made by whoever makes the snapshot, never by a turn that finds it).
    """

    def __init__(self, max_entities: int = 300, lang: str = "en",
                 then: Callable[[Snapshot], object] | None = None) -> None:
        self.max_entities = max_entities
        self.lang = lang
        self._then = then
        self._wakeup = threading.Condition()  # a commit to take up, or the end of following
        self._due = False
        self._following = False
        self._worker: threading.Thread | None = None
        self._built: Callable[[], object] | None = None
        self._lock = threading.Lock()  # guards the cache and the queue; never held while calling the KB
        self._build = threading.Lock()  # one build at a time: the index is mutable
        self._cached: Snapshot | None = None
        self._index: EntityIndex | None = None
        self._watched: KnowledgeBase | None = None
        self._unwatch: Callable[[], None] | None = None
        self._pending: list[tuple[_Triples, _Triples]] | None = None  # None: rebuild everything
        self._pending_size = 0

    def cached(self, revision: int) -> Snapshot | None:
        """The cached snapshot if it is still current (cheap: callable on an event loop)."""
        with self._lock:
            cached = self._cached
        return cached if cached is not None and cached.revision == revision else None

    def snapshot(self, kb: KnowledgeBase) -> Snapshot:
        cached = self.cached(kb.revision)
        if cached is not None:
            return cached
        with self._build:
            with self._lock:
                watched = self._watched is kb
            if not watched:
                self._watch(kb)
            # The KB moves its revision on before it tells its listeners, all under its lock: read
            # outside it, a commit's revision could be stamped on a snapshot its changes never reach
            # (taken from the queue before `_changed` queued them), and that snapshot then passes
            # for current. Under it, the queue holds every commit up to the revision read.
            with kb.lock:
                revision = kb.revision
                cached = self.cached(revision)
                if cached is not None:
                    return cached
                with self._lock:
                    pending, self._pending = self._pending, ([] if self._unwatch is not None else None)
                    self._pending_size = 0
                    previous = self._cached
            index = self._index
            built = pending is None or index is None or previous is None
            # A full build makes hundreds of thousands of objects to last (the index, the snapshot,
            # its lexicon): one pause of the collector for all of it, and what `built` does (the
            # service settles them, `gcpause.settle`) done before the collector is back, so no
            # pass walks them first (one did after the index and again after the lexicon).
            with paused(BULK if built else 0):
                if pending is None or index is None or previous is None:
                    index = self._index = EntityIndex(kb, self.lang)
                    snap = index.freeze(revision)
                else:
                    changed: set[str] = set()
                    for added, removed in pending:
                        changed |= index.apply(added, removed)
                    steps = (*previous.changed, (previous.revision, frozenset(changed)))[-MAX_STEPS:]
                    snap = index.freeze(revision, steps)
                if self._then is not None:
                    self._then(snap)
                with self._lock:
                    settled = self._built
                if built and settled is not None:
                    settled()
                with self._lock:
                    self._cached = snap
        return snap

    def follow(self, kb: KnowledgeBase, built: Callable[[], object] | None = None) -> None:
        """Keep the snapshot of ``kb`` current on a worker thread, from now on: the first one is
        built there (a turn that comes before it is done waits for it), then each commit is taken
        up as it comes. A KB that reports no commits is grounded turn by turn, as without.
        ``built`` is called after each full build, before the cyclic collector runs again (the
        service settles what it made: no pass walks it first), under the grounder's build lock."""
        with self._lock:
            self._built = built
            watched = self._watched is kb
        if not watched:
            self._watch(kb)
        with self._wakeup:
            self._following = True
        self._kick()

    def close(self) -> None:
        with self._wakeup:
            self._following = False
            self._wakeup.notify_all()
            worker = self._worker
        if worker is not None and worker is not threading.current_thread():
            worker.join(timeout=10)
        with self._lock:
            unwatch, self._unwatch, self._watched, self._pending = self._unwatch, None, None, None
        if unwatch is not None:  # takes the KB's lock: never under ours (`_changed` takes them the other way)
            unwatch()

    def _kick(self) -> None:
        """A commit to take up: wake the worker, or start one (it ends after `IDLE` quiet seconds)."""
        with self._wakeup:
            if not self._following:
                return
            self._due = True
            if self._worker is None:
                self._worker = threading.Thread(target=self._follow, name="grounding", daemon=True)
                self._worker.start()
            else:
                self._wakeup.notify()

    def _follow(self) -> None:
        while True:
            with self._wakeup:
                if not self._due and self._following:
                    self._wakeup.wait(IDLE)
                if not self._due or not self._following:
                    self._worker = None
                    return
                self._due = False
            with self._lock:
                kb = self._watched
            if kb is None:
                continue
            try:
                self.snapshot(kb)
            except KbError as exc:  # the KB refused a read (closed, or a store that went away)
                log.warning("the grounding could not follow the KB: %s", exc)

    def _watch(self, kb: KnowledgeBase) -> None:
        """Follow ``kb``'s commits from now on (everything rebuilt first). Called without our lock:
        (un)registering takes the KB's lock, and the KB calls `_changed`, which takes ours, under
        its lock — holding ours meanwhile would deadlock with a commit made at the same moment."""
        with self._lock:
            old, self._unwatch = self._unwatch, None
            self._watched, self._pending, self._cached, self._index = kb, None, None, None
        if old is not None:
            old()
        on_commit = getattr(kb, "on_commit", None)
        unwatch = on_commit(self._changed) if callable(on_commit) else None
        with self._lock:
            if self._watched is kb:
                unwatch, self._unwatch = None, unwatch
        if unwatch is not None:  # another KB was watched meanwhile: this registration is stale
            unwatch()

    def _changed(self, commit: Any) -> None:
        """Called by the KB under its lock with every commit: queue what it changed."""
        with self._lock:
            self._queue(commit)
        self._kick()

    def _queue(self, commit: Any) -> None:
        if self._pending is None:
            return
        if getattr(commit, "cleared", None) is not None:
            self._pending = None
            return
        for delta in commit.deltas:
            if delta.model != "default":
                continue
            if any(map(is_schema_triple, (*delta.asserted_added, *delta.asserted_removed))):
                self._pending = None  # the TBox changed: classes and names may all change
                return
            self._pending.append((list(delta.added), list(delta.removed)))
            self._pending_size += len(delta.added) + len(delta.removed)
            retyped = _retyped(delta)
            if retyped:
                # a type asserted that was only inferred (or no longer asserted but still
                # inferred) changes no fact of the closure, yet which classes are the entity's
                # own (its name: "cup", not "mug"): its classes are asked again
                self._pending.append((retyped, []))
        if self._pending_size > MAX_PENDING:
            self._pending = None


def _retyped(delta: Any) -> list[tuple[Any, Any, Any]]:
    """The asserted types that changed where the closure's changes do not show it (each still
    holds in the closure: asserted and inferred, or no longer asserted but inferred)."""
    asserted = [t for t in (*delta.asserted_added, *delta.asserted_removed) if t[1] == RDF.type]
    if not asserted:
        return []
    shown = {*delta.added, *delta.removed}
    return [t for t in asserted if t not in shown]


def build_snapshot(kb: KnowledgeBase, max_entities: int = 300, lang: str = "en") -> Snapshot:
    """A snapshot from scratch (no commit tracking): what a grounder's snapshots must equal."""
    del max_entities  # the prompt's share is chosen per turn (relevance), not here
    return EntityIndex(kb, lang).freeze(kb.revision)
