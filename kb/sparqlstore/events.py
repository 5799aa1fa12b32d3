"""Subscriptions of a read replica: a background thread polls the store's revision and, when it
moved, re-runs each subscription's query and fires with the rows that are new.

The semantics are kb.events' (baseline rows do not fire, each evaluation fires once with all its
new rows, one-shot subscriptions go after the first evaluation that fires, kb-compat §3.6) with
one difference that polling cannot avoid: commits made by other processes between two polls are
seen as one change. A write made through the replica waits (``sync``) until the poller has
evaluated the state it produced, so such writes fire one by one, as in-process.

No thread runs until the first subscription; ``close`` stops it.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable, Sequence

from kb.arguments import compiled, render
from kb.deadline import UNBOUNDED, Budget, Deadline
from kb.errors import KbError, QueryTimeout, TooManyRows
from kb.events import (
    ALL,
    Callback,
    Delivery,
    Ending,
    ErrorCallback,
    Firing,
    SharedBudget,
    Subscription,
    in_cost_order,
)
from kb.models import DEFAULT_MODEL
from kb.query import Query, Row
from kb.sparqlstore.query import Meta, StoreQueries
from kb.terms import shorten

log = logging.getLogger(__name__)
ActiveListener = Callable[[list[str]], None]
_ACTIVE = compiled(("?concept rdf:type ActiveConcept",), None)
SYNC_TIMEOUT = 30.0


class Poller:
    """Polls one dataset for changes and evaluates the subscriptions of one replica."""

    def __init__(self, queries: StoreQueries, interval: float) -> None:
        self._queries = queries
        self._interval = interval
        self._lock = threading.Lock()
        self._subscriptions: dict[str, Subscription] = {}
        self._active_listeners: list[ActiveListener] = []
        self._active: frozenset[str] = frozenset()
        # The revision each subscription (and the active concepts) was last evaluated at: a
        # subscription registered while a poll runs is evaluated at the next one.
        self._seen: dict[str, int | None] = {}
        self._active_seen: int | None = None
        self._thread: threading.Thread | None = None
        self._wake = threading.Event()
        self._closed = False
        # Cycles asked for and cycles done: sync() waits for a cycle that began after its request.
        self._progress = threading.Condition()
        self._requested = 0
        self._done = 0

    # --- registration ----------------------------------------------------------------------

    def rows(self, query: Query, models: Sequence[str], known: Sequence[str],
             max_rows: int | None = None, deadline: Deadline | None = None) -> set[Row]:
        """The query's rows over the given models (``all``: every known one) that exist;
        ``QueryTimeout`` past the deadline, ``TooManyRows`` past ``max_rows``."""
        names = known if ALL in models else [m for m in models if m in known]
        limit = None if max_rows is None else max_rows + 1
        found: set[Row] = set()
        for name in names:
            found |= self._queries.rows(query, self._queries.graphs(name), limit, deadline)
            if max_rows is not None and len(found) > max_rows:
                raise TooManyRows(max_rows)
        return found

    def subscribe(self, sub_id: str, query: Query, models: Sequence[str], one_shot: bool,
                  callback: Callback, baseline: set[Row], revision: int | None,
                  budget: Budget = UNBOUNDED, on_error: ErrorCallback | None = None) -> None:
        """Register a subscription whose ``baseline`` rows were read at ``revision`` (or later);
        an evaluation past its ``budget`` ends it and calls ``on_error``."""
        self._require_open()
        with self._lock:
            existing = self._subscriptions.get(sub_id)
            if existing is None:
                existing = self._subscriptions[sub_id] = Subscription(
                    sub_id, query, tuple(models), one_shot, [], None, set(baseline), budget)
                self._seen[sub_id] = revision
            existing.attach(callback, on_error)
        self._start()

    def unsubscribe(self, sub_id: str) -> bool:
        with self._lock:
            self._seen.pop(sub_id, None)
            return self._subscriptions.pop(sub_id, None) is not None

    def on_active_concept(self, callback: ActiveListener) -> Callable[[], None]:
        """Call ``callback`` with the sorted active concepts when a poll finds them changed;
        returns what removes it."""
        self._require_open()
        with self._lock:
            first = not self._active_listeners
        if first:
            revision = self._queries.meta().revision
            active = self._active_concepts()
        with self._lock:
            if first:
                self._active, self._active_seen = active, revision
            self._active_listeners.append(callback)
        self._start()

        def remove() -> None:
            with self._lock:
                if callback in self._active_listeners:
                    self._active_listeners.remove(callback)

        return remove

    def _require_open(self) -> None:
        if self._closed:
            raise KbError("this RemoteKB is closed: it evaluates no subscriptions any more")

    def _start(self) -> None:
        with self._lock:
            if self._thread is not None or self._closed:
                return
            self._thread = threading.Thread(target=self._run, name="kb-remote-poll", daemon=True)
            self._thread.start()

    # --- polling ---------------------------------------------------------------------------

    def sync(self, timeout: float = SYNC_TIMEOUT) -> None:
        """Return once the poller has evaluated a state read after this call began (at once when
        no thread runs, or when called from a callback, which runs on the poller itself)."""
        thread = self._thread
        if thread is None or thread is threading.current_thread() or self._closed:
            return
        with self._progress:
            self._requested += 1
            wanted = self._requested
            self._wake.set()
            if not self._progress.wait_for(lambda: self._done >= wanted or self._closed, timeout):
                log.warning("subscriptions of %s were not evaluated within %.0f s", self._queries.layout.root,
                            timeout)

    def close(self) -> None:
        with self._lock:
            self._closed = True
            thread, self._thread = self._thread, None
        self._wake.set()
        with self._progress:
            self._progress.notify_all()
        if thread is not None and thread is not threading.current_thread():
            thread.join(timeout=SYNC_TIMEOUT)

    def _run(self) -> None:
        while not self._closed:
            self._wake.wait(self._interval)
            self._wake.clear()
            if self._closed:
                return
            with self._progress:
                serving = self._requested
            try:
                firings = self._cycle()
            except KbError as exc:  # the store is down or refused: try again at the next poll
                log.warning("polling %s failed: %s", self._queries.layout.root, exc)
                firings = []
            for firing in firings:
                firing.deliver()
            with self._progress:
                self._done = max(self._done, serving)
                self._progress.notify_all()

    def _cycle(self) -> list[Delivery]:
        meta = self._queries.meta()
        firings = self._evaluate(meta)
        with self._lock:
            listeners = tuple(self._active_listeners)
        if listeners and self._active_seen != meta.revision:
            active = self._active_concepts()
            if active != self._active:
                self._active = active
                firings.append(Firing("active_concepts", listeners, sorted(active)))
            self._active_seen = meta.revision
        return firings

    def _evaluate(self, meta: Meta) -> list[Delivery]:
        with self._lock:
            due = [sub for sub in self._subscriptions.values() if self._seen.get(sub.id) != meta.revision]
        firings: list[Delivery] = []
        poll = SharedBudget()  # one budget for the bounded subscriptions of this poll, as a commit

        def run(sub: Subscription, deadline: Deadline | None) -> set[Row]:
            return self.rows(sub.query, sub.models, meta.models, sub.budget.max_rows, deadline)

        for sub in in_cost_order(due):
            try:
                current = poll.run(sub, run)
            except (QueryTimeout, TooManyRows) as exc:
                with self._lock:
                    if self._subscriptions.get(sub.id) is sub:
                        del self._subscriptions[sub.id]
                        del self._seen[sub.id]
                        firings.append(Ending(sub.id, tuple(sub.on_error), exc))
                continue
            if current is None:
                continue  # the poll's budget is spent: evaluated at the next poll
            with self._lock:
                if self._subscriptions.get(sub.id) is not sub:
                    continue  # unsubscribed meanwhile
                new = current - sub.last
                sub.last = current
                self._seen[sub.id] = meta.revision
                if not new:
                    continue
                if sub.one_shot:
                    del self._subscriptions[sub.id]
                    del self._seen[sub.id]
                callbacks = tuple(sub.callbacks)
            firings.append(Firing(sub.id, callbacks, render(sub.query, new)))
        return firings

    def _active_concepts(self) -> frozenset[str]:
        found = self._queries.rows(_ACTIVE, self._queries.graphs(DEFAULT_MODEL))
        return frozenset(str(shorten(row[0])) for row in found)
