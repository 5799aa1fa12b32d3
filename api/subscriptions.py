"""KB subscriptions fanned out to SSE and WebSocket clients (the thread → asyncio bridge).

The KB calls a subscription's callback in the writer's thread. Identical subscriptions share
one KB subscription id (knowledge_core's ``evt_<md5>``), so the hub keeps one KB callback per
id and fans it out to every listener: a stream's, with its own bounded queue on its event loop
(``loop.call_soon_threadsafe``), or any other ``Sink`` (the ROS node's event topics). The KB
subscription is removed when its last listener leaves; all of them count against one limit.

Delivery never takes the hub lock, because a writer may deliver while another thread holds
the hub lock and waits for the KB lock.

Every subscription gets the service's query limits (kb.events): opening one whose starting rows
go past them raises ``QueryTimeout``/``TooManyRows`` (503 ``query_timeout``, 413
``too_many_rows``); a later evaluation past them ends it, and each of its listeners gets that
error (the same body as the HTTP answer) as its last message.
"""

from __future__ import annotations

import asyncio
import threading
from collections import deque
from collections.abc import Callable, Sequence
from typing import Any, Protocol, TypeVar

from api.errors import ApiError, error_body, over_budget
from kb import KbError
from kb.describe import statements
from kb.errors import QueryTimeout, TooManyRows
from kb.events import event_id
from kb.protocol import KnowledgeBase
from kb.writer import Commit, CommitListener

DEFAULT_MODEL = "default"
CHANGES_ID = "changes"
#: Past this many statements, a change event only says that much changed (clients reload).
MAX_CHANGE_STATEMENTS = 500


def change_event(commit: Commit) -> dict[str, Any]:
    """What one commit changed in the robot's model, in the KB's output form."""
    added = [t for d in commit.deltas if d.model == DEFAULT_MODEL for t in d.added]
    removed = [t for d in commit.deltas if d.model == DEFAULT_MODEL for t in d.removed]
    event: dict[str, Any] = {"revision": commit.revision, "cleared": commit.cleared is not None}
    if len(added) + len(removed) > MAX_CHANGE_STATEMENTS:
        event["truncated"] = True
        return event
    event["added"] = statements(added)
    event["removed"] = statements(removed)
    return event


class Sink(Protocol):
    """Where one client's rows go (a stream's ``Listener``, the ROS node's event topic); every
    method may be called from any thread and must not block."""

    def push(self, rows: list[Any], last: bool = False) -> None:
        """New rows; ``last``: the subscription was one-shot and has ended."""

    def fail(self, error: dict[str, Any]) -> None:
        """The KB ended the subscription (an evaluation went past the query limits): the error body."""

    def end(self, reason: str) -> None:
        """The service is stopping."""


S = TypeVar("S", bound=Sink)


class Listener:
    """One client's view of a subscription: rows arrive in order; ``None`` ends the stream."""

    def __init__(self, sub_id: str, loop: asyncio.AbstractEventLoop, max_queued: int) -> None:
        self.sub_id = sub_id
        self.end_reason: str | None = None
        self.error: dict[str, Any] | None = None  # why the subscription was ended, if it was
        self._loop = loop
        self._max = max_queued
        self._rows: deque[list[Any]] = deque()
        self._ready = asyncio.Event()

    def push(self, rows: list[Any], last: bool = False) -> None:
        """Called from any thread."""
        try:
            self._loop.call_soon_threadsafe(self._put, rows, last)
        except RuntimeError:  # the listener's loop is closed: the client is gone
            return

    def end(self, reason: str) -> None:
        try:
            self._loop.call_soon_threadsafe(self._finish, reason)
        except RuntimeError:
            return

    def fail(self, error: dict[str, Any]) -> None:
        """End the stream with an error body (called from any thread)."""
        try:
            self._loop.call_soon_threadsafe(self._fail, error)
        except RuntimeError:
            return

    def _fail(self, error: dict[str, Any]) -> None:
        if self.end_reason is None:
            self.error = error
        self._finish("error")

    def _put(self, rows: list[Any], last: bool) -> None:
        if self.end_reason is not None:
            return
        if len(self._rows) >= self._max:
            self._finish("overflow: the client reads events more slowly than they happen")
            return
        self._rows.append(rows)
        if last:
            self.end_reason = "one_shot"
        self._ready.set()

    def _finish(self, reason: str) -> None:
        if self.end_reason is None:
            self.end_reason = reason
        self._ready.set()

    async def next_rows(self) -> list[Any] | None:
        """The next batch of new rows, or None once the stream has ended."""
        while not self._rows:
            if self.end_reason is not None:
                return None
            self._ready.clear()
            await self._ready.wait()
        return self._rows.popleft()


class _Entry:
    """One KB subscription and the listeners it feeds."""

    def __init__(self, key: str, one_shot: bool) -> None:
        self.key = key
        self.sub_id = key
        self.one_shot = one_shot
        self.listeners: tuple[Sink, ...] = ()  # replaced, never mutated: read without a lock
        self.alive = True
        self.failure: dict[str, Any] | None = None  # why the KB ended it, if it did

    def deliver(self, rows: list[Any]) -> None:
        if self.one_shot:
            self.alive = False  # the KB has removed it
        for listener in self.listeners:
            listener.push(rows, last=self.one_shot)

    def fail(self, error: KbError) -> None:
        self.alive = False  # the KB has ended it
        if isinstance(error, QueryTimeout | TooManyRows):
            failure = over_budget(error)
            body = error_body(failure.status, failure.code, failure.message, failure.details)
        else:
            body = error_body(400, "kb_error", str(error))
        self.failure = body  # before reading the listeners: one joining now sees one or the other
        for listener in self.listeners:
            listener.fail(body)


class EventHub:
    """Bounded set of event listeners over one KB."""

    def __init__(self, kb: KnowledgeBase, max_listeners: int, max_queued: int = 256, *,
                 query_timeout: float | None = None, max_rows: int | None = None,
                 commits: Callable[[CommitListener], Callable[[], None]] | None = None) -> None:
        """``commits``: how to follow every commit (the writer's ``KB.on_commit``); a reader, which
        sees no commits, has none and refuses the commit feed."""
        self._kb = kb
        self._commits = commits
        self._query_timeout = query_timeout
        self._max_rows = max_rows
        self._max_listeners = max_listeners
        self._max_queued = max_queued
        self._lock = threading.Lock()
        self._entries: dict[str, _Entry] = {}
        self._owners: dict[int, _Entry] = {}  # id(sink) -> the entry feeding it
        self._count = 0
        self._changes: tuple[Listener, ...] = ()  # replaced, never mutated: read without a lock
        self._unwatch: Callable[[], None] | None = None

    @property
    def listener_count(self) -> int:
        return self._count

    def open(self, patterns: Sequence[str], one_shot: bool, models: Sequence[str] | None,
             loop: asyncio.AbstractEventLoop) -> Listener:
        """Subscribe a new listener (blocking: call it off the event loop). 429 past the limit;
        KbError for bad patterns or unknown models; ``QueryTimeout``/``TooManyRows`` when the
        starting rows go past the query limits."""
        return self.attach(patterns, one_shot, models,
                           lambda sub_id: Listener(sub_id, loop, self._max_queued))

    @staticmethod
    def key(patterns: Sequence[str], one_shot: bool, models: Sequence[str] | None) -> str:
        """The id the KB gives this subscription (knowledge_core's ``evt_<md5>``)."""
        return event_id(list(patterns), one_shot, list(models) if models else [DEFAULT_MODEL])

    def attach(self, patterns: Sequence[str], one_shot: bool, models: Sequence[str] | None,
               make: Callable[[str], S]) -> S:
        """``open`` for any sink: ``make(sub_id)`` builds it once the subscription exists. The
        same limit, budgets and sharing as a stream's listener; ``close`` it the same way."""
        key = self.key(patterns, one_shot, models)
        with self._lock:
            self._check_limit()
            entry = self._entries.get(key)
            if entry is None or not entry.alive:
                entry = _Entry(key, one_shot)
                names = list(models) if models else [DEFAULT_MODEL]
                entry.sub_id = self._kb.subscribe(list(patterns), entry.deliver, one_shot, names,
                                                  timeout=self._query_timeout, max_rows=self._max_rows,
                                                  on_error=entry.fail)
                self._entries[key] = entry
            sink = make(entry.sub_id)
            entry.listeners = (*entry.listeners, sink)
            if entry.failure is not None:  # ended by a commit while it was being opened
                sink.fail(entry.failure)
            self._owners[id(sink)] = entry
            self._count += 1
            return sink

    def open_changes(self, loop: asyncio.AbstractEventLoop) -> Listener:
        """A listener of every commit's changes (blocking: call it off the event loop)."""
        with self._lock:
            self._check_limit()
            listener = Listener(CHANGES_ID, loop, self._max_queued)
            self._changes = (*self._changes, listener)
            self._count += 1
            if self._unwatch is None:
                if self._commits is None:
                    raise ApiError(503, "changes_elsewhere", "the commit feed is served by the writer")
                self._unwatch = self._commits(self._commit)
            return listener

    def _commit(self, commit: Commit) -> None:
        # Called by the KB under its lock: build the event once, hand it to the loops.
        listeners = self._changes
        if listeners:
            event = change_event(commit)
            for listener in listeners:
                listener.push([event])

    def _check_limit(self) -> None:
        if self._count >= self._max_listeners:
            raise ApiError(429, "too_many_subscribers",
                           f"{self._count} event subscribers are connected; the limit is "
                           f"{self._max_listeners}", {"limit": self._max_listeners})

    def close(self, listener: Sink) -> None:
        """Remove a listener (blocking); the KB subscription goes with its last listener."""
        with self._lock:
            if listener in self._changes:
                self._changes = tuple(x for x in self._changes if x is not listener)
                self._count -= 1
                if not self._changes and self._unwatch is not None:
                    self._unwatch()
                    self._unwatch = None
                return
            entry = self._owners.pop(id(listener), None)
            if entry is None:
                return
            entry.listeners = tuple(x for x in entry.listeners if x is not listener)
            self._count -= 1
            if entry.listeners:
                return
            if self._entries.get(entry.key) is entry:
                del self._entries[entry.key]
            if entry.alive:
                entry.alive = False
                self._kb.unsubscribe(entry.sub_id)

    def shutdown(self) -> None:
        """End every stream (at service stop) and drop the KB subscriptions."""
        with self._lock:
            entries = {id(e): e for e in self._owners.values()}.values()
            for entry in entries:
                for listener in entry.listeners:
                    listener.end("service stopping")
                if entry.alive:
                    entry.alive = False
                    self._kb.unsubscribe(entry.sub_id)
            for listener in self._changes:
                listener.end("service stopping")
            self._changes = ()
            if self._unwatch is not None:
                self._unwatch()
                self._unwatch = None
            self._entries.clear()
            self._owners.clear()
            self._count = 0
