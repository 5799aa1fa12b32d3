"""Deliveries to one destination off the caller's thread: in order, retried, bounded, reported.

A courier takes items with a non-blocking `enqueue` (a dialogue turn never waits for it) into a
bounded queue; when the queue is full the oldest waiting item is dropped (counted). One worker thread
sends them in order. A delivery that fails is retried after a backoff that doubles each time, up
to `retries` times, then given up (counted) and the next item is sent. While deliveries fail,
`status` is degraded with the reason and the counts (a `/health` component); once they succeed
again it is ok, with the counts as long as any item was lost (given up or dropped).

The outgoing webhooks (api.webhooks) and a reader's intent relay to the writer (api.relay) are
couriers; each says how it sends one item (`_send`: None when delivered, else what went wrong).
"""

from __future__ import annotations

import contextlib
import logging
import queue
import threading
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Generic, TypeVar

from kb.status import ComponentStatus, StatusCell

log = logging.getLogger("situated.courier")

T = TypeVar("T")


@dataclass(frozen=True)
class DeliveryConfig:
    retries: int = 5
    #: Seconds before the first retry; each next one waits twice as long, up to `max_backoff`.
    backoff: float = 0.5
    max_backoff: float = 30.0
    queue: int = 1000
    timeout: float = 5.0


@dataclass
class Counts:
    delivered: int = 0
    failed: int = 0  # given up after every retry
    dropped: int = 0  # pushed out of a full queue


class _Stop:
    """What `stop` queues so that the worker wakes up and ends."""


class Courier(ABC, Generic[T]):
    """Deliveries to one destination; `code` names its failures in `/health`."""

    def __init__(self, name: str, config: DeliveryConfig, code: str) -> None:
        self.name = name
        self.config = config
        self.code = code
        self.counts = Counts()
        self.cell = StatusCell()
        self._queue: queue.Queue[T | _Stop] = queue.Queue(config.queue)
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._work, name=f"courier {name}", daemon=True)

    @abstractmethod
    def _send(self, item: T) -> str | None:
        """Deliver one item (blocking, within the config's timeout): None, or what went wrong."""

    def _closing(self) -> None:
        """Release what sending held, once the worker has ended."""

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        with contextlib.suppress(queue.Full):  # a full queue: the worker sees the flag before its next item
            self._queue.put_nowait(_Stop())
        if self._thread.is_alive():
            self._thread.join(timeout=self.config.timeout + 1)
        if not self._thread.is_alive():  # a worker still sending keeps what it sends with
            self._closing()

    def enqueue(self, item: T) -> None:
        """Never blocks: a full queue loses its oldest item."""
        with self._lock:
            while True:
                try:
                    self._queue.put_nowait(item)
                    return
                except queue.Full:
                    try:
                        self._queue.get_nowait()
                        self.counts.dropped += 1
                    except queue.Empty:
                        continue

    @property
    def queued(self) -> int:
        return self._queue.qsize()

    def report(self) -> dict[str, int]:
        return {"delivered": self.counts.delivered, "given_up": self.counts.failed,
                "dropped": self.counts.dropped, "queued": self.queued}

    def status(self) -> ComponentStatus:
        status = self.cell.get()
        counts = (f"{self.counts.delivered} delivered, {self.counts.failed} given up, "
                  f"{self.counts.dropped} dropped, {self.queued} queued")
        if status.ok and not self.counts.dropped and not self.counts.failed:
            return status  # nothing lost: nothing to say
        if status.ok:
            return ComponentStatus(ok=True, reason=counts)
        return ComponentStatus(ok=False, code=status.code, reason=f"{status.reason} ({counts})",
                               failures=status.failures, since=status.since, retry_in=status.retry_in)

    def _work(self) -> None:
        while not self._stop.is_set():
            item = self._queue.get()
            if isinstance(item, _Stop):
                return
            self._deliver(item)

    def _deliver(self, item: T) -> None:
        wait = self.config.backoff
        for attempt in range(self.config.retries + 1):
            error = self._send(item)
            if error is None:
                self.counts.delivered += 1
                self.cell.succeeded()
                return
            last = attempt == self.config.retries
            self.cell.failed(self.code, f"{self.name}: {error}", retry_in=None if last else wait)
            if last or self._stop.wait(wait):
                break
            wait = min(wait * 2, self.config.max_backoff)
        self.counts.failed += 1
        log.warning("%s not delivered to %s after %d attempts", self._what(item), self.name,
                    self.config.retries + 1)

    def _what(self, item: T) -> str:
        """An item as the log names it."""
        return "an item"
