"""The intent bus: every pushed intent numbered, kept in a bounded buffer, fanned out to readers.

`publish` may be called from any thread (a dialogue turn on the event loop, the initiative's
worker thread) and never blocks on a reader: each reader has its own bounded queue on its event
loop, and one that falls too far behind is ended ("overflow") rather than slowing the others; it
reconnects and replays what it missed from the buffer. A reader subscribes after a sequence number
(`after`): the buffered events after it come first, then the live ones, with no gap and no repeat
(both are taken under the bus's lock). When the buffer no longer holds all of what the reader
missed, or the number is from before a restart, the reader learns it from its `gap` before the
events it does get. A bus numbers from `first`: the service starts it from the clock
(`clock_first`), so that a restarted service numbers after every number the earlier run gave and a
client resuming after one of those is told of the restart, however many intents the new run has
pushed since (numbering from 1 again, its 42 would have been taken for the old run's 42). `stream`
names the bus too.

The buffer is bounded in events and in bytes (each event's JSON): past either, the oldest go (the
newest always stays), so neither a flood of large intents nor a client reading the whole buffer
(`GET /intents`) costs more than `buffer_bytes`. A reader's queue is bounded the same way.

Listeners (`on_publish`, the webhooks) are called in the publisher's thread and must only queue.
"""

from __future__ import annotations

import asyncio
import threading
import time
import uuid
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass

from dialogue.intents import Intent
from dialogue.pushed.events import IntentFilter, Origin, Pushed, emitted
from dialogue.sessions.observers import TurnRecord

Listener = Callable[[Pushed], None]
#: Bytes of events a buffer (and a reader's queue) holds at most, by default.
DEFAULT_BUFFER_BYTES = 8 * 1024 * 1024


def clock_first() -> int:
    """A bus's first number from the wall clock (milliseconds): above every number an earlier run
    gave, unless it pushed more than one intent per millisecond on average."""
    return time.time_ns() // 1_000_000


@dataclass(frozen=True)
class Gap:
    """Events a reader asked for that the bus no longer has: numbers `first` to `last`, or, with
    `restarted`, a number from an earlier run of the service (this one's events all follow; `first`
    to `last` are then those of this run no longer buffered)."""

    first: int
    last: int
    restarted: bool = False

    def as_json(self) -> dict[str, object]:
        return {"first": self.first, "last": self.last, "restarted": self.restarted}


class Reader:
    """One subscriber's events, in order; `None` from `next` ends them (see `end_reason`)."""

    def __init__(self, loop: asyncio.AbstractEventLoop, flt: IntentFilter, max_queued: int,
                 max_bytes: int = DEFAULT_BUFFER_BYTES) -> None:
        self.filter = flt
        self.end_reason: str | None = None
        self.gap: Gap | None = None
        self._loop = loop
        self._max = max_queued
        self._max_bytes = max_bytes
        self._bytes = 0
        self._events: deque[Pushed] = deque()
        self._ready = asyncio.Event()

    def push(self, event: Pushed) -> None:
        """From any thread."""
        try:
            self._loop.call_soon_threadsafe(self._put, event)
        except RuntimeError:  # its loop is closed: the client is gone
            return

    def end(self, reason: str) -> None:
        try:
            self._loop.call_soon_threadsafe(self._finish, reason)
        except RuntimeError:
            return

    def _put(self, event: Pushed) -> None:
        if self.end_reason is not None:
            return
        if self._events and (len(self._events) >= self._max or self._bytes + event.size > self._max_bytes):
            self._finish("overflow: the client reads intents more slowly than they come; reconnect "
                         f"after {self._events[-1].seq} to replay what is still buffered")
            return
        self._events.append(event)
        self._bytes += event.size
        self._ready.set()

    def _finish(self, reason: str) -> None:
        if self.end_reason is None:
            self.end_reason = reason
        self._ready.set()

    async def next(self) -> Pushed | None:
        while not self._events:
            if self.end_reason is not None:
                return None
            self._ready.clear()
            await self._ready.wait()
        event = self._events.popleft()
        self._bytes -= event.size
        return event


class IntentBus:
    """Numbers and buffers the intents of one service and hands them to readers and listeners."""

    def __init__(self, buffer: int = 1000, max_queued: int = 1000, max_readers: int = 64,
                 first: int = 1, buffer_bytes: int = DEFAULT_BUFFER_BYTES) -> None:
        if buffer < 1 or max_queued < 1 or max_readers < 1 or first < 1 or buffer_bytes < 1:
            raise ValueError("the intent bus's bounds and first number must be positive")
        #: Names this bus: a client seeing another stream id knows the numbers started again.
        self.stream = uuid.uuid4().hex
        self.max_readers = max_readers
        #: The number of this bus's first event; `after` 0 (nothing seen yet) means just before it.
        self.first = first
        self._lock = threading.Lock()
        self._buffer: deque[Pushed] = deque()
        self._max_buffered = buffer
        self._max_bytes = buffer_bytes
        self._bytes = 0  # of the buffered events
        self._seq = first - 1
        self._max_queued = max_queued
        self._readers: tuple[Reader, ...] = ()
        self._listeners: tuple[Listener, ...] = ()

    @property
    def last_seq(self) -> int:
        return self._seq

    @property
    def reader_count(self) -> int:
        return len(self._readers)

    def on_publish(self, listener: Listener) -> None:
        with self._lock:
            self._listeners = (*self._listeners, listener)

    def publish(self, origin: Origin, intent: Intent, dialogue_id: str | None = None,
                response: str = "", at: float | None = None) -> Pushed:
        """Number and push an intent emitted `at` (seconds since the epoch; None: now)."""
        when = time.time() if at is None else at
        with self._lock:
            self._seq += 1
            event = Pushed(self._seq, when, origin, intent, dialogue_id, response)
            self._keep(event)
            readers, listeners = self._readers, self._listeners
            # Handed out under the lock, so that a reader subscribing now gets each event once,
            # from the buffer or live, and in order.
            for reader in readers:
                if reader.filter.matches(event):
                    reader.push(event)
        for listener in listeners:
            listener(event)
        return event

    def _keep(self, event: Pushed) -> None:
        """Buffer the event, dropping the oldest past the bounds (under the lock)."""
        self._buffer.append(event)
        self._bytes += event.size
        buffer = self._buffer
        while len(buffer) > 1 and (len(buffer) > self._max_buffered or self._bytes > self._max_bytes):
            self._bytes -= buffer.popleft().size

    async def observe(self, record: TurnRecord) -> None:
        """The dialogue manager's observer: a turn's intents, in order, its reply with the first."""
        for event in emitted(record):
            self.publish(event.origin, event.intent, event.dialogue_id, event.response, event.time)

    def subscribe(self, loop: asyncio.AbstractEventLoop, flt: IntentFilter | None = None,
                  after: int | None = None) -> Reader:
        """A reader of the events after `after` (None: from now on). ValueError past the readers'
        bound (the caller says so: too many subscribers)."""
        reader = Reader(loop, flt or IntentFilter(), self._max_queued, self._max_bytes)
        with self._lock:
            if len(self._readers) >= self.max_readers:
                raise ValueError(f"{len(self._readers)} intent readers are connected; the limit is "
                                 f"{self.max_readers}")
            if after is not None:
                missed, reader.gap = self._since(after, reader.filter)
                for event in missed:
                    reader.push(event)
            self._readers = (*self._readers, reader)
        return reader

    def since(self, after: int, flt: IntentFilter | None = None) -> tuple[list[Pushed], Gap | None]:
        """The buffered events after `after` that `flt` wants, and what the buffer no longer has."""
        with self._lock:
            return self._since(after, flt or IntentFilter())

    def _since(self, after: int, flt: IntentFilter) -> tuple[list[Pushed], Gap | None]:
        after = after or self.first - 1
        gap = self._gap(after)
        start = self.first - 1 if gap is not None and gap.restarted else after
        return [e for e in self._buffer if e.seq > start and flt.matches(e)], gap

    def _gap(self, after: int) -> Gap | None:
        oldest = self._buffer[0].seq if self._buffer else self._seq + 1
        if after > self._seq or after < self.first - 1:  # a number this run never gave
            return Gap(self.first, oldest - 1, restarted=True)
        return Gap(after + 1, oldest - 1) if after + 1 < oldest else None

    def close(self, reader: Reader) -> None:
        with self._lock:
            self._readers = tuple(r for r in self._readers if r is not reader)

    def shutdown(self) -> None:
        with self._lock:
            readers, self._readers = self._readers, ()
        for reader in readers:
            reader.end("service stopping")
