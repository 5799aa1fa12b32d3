"""Outgoing webhooks: every pushed intent POSTed as JSON to each configured URL.

One worker thread and one bounded queue per URL, so a slow or failing receiver delays nobody else,
and a turn never waits for any of them: the bus hands an event over with a non-blocking put. When a
queue is full the oldest waiting event is dropped (counted). A delivery that fails (a transport
error, or any status but 2xx) is retried after a backoff that doubles each time, up to `retries`
times, then given up (counted) and the next event is sent; events are delivered in order per URL.
While a URL's deliveries fail, `/health` reports it degraded, with the reason and the counts; once
it recovers, it is ok, with the counts as long as any intent was lost (given up or dropped).
"""

from __future__ import annotations

import contextlib
import logging
import queue
import threading
from collections.abc import Sequence
from dataclasses import dataclass

import httpx

from dialogue.pushed.events import Pushed
from kb.status import ComponentStatus, StatusCell

log = logging.getLogger("situated.webhooks")
_STOP = None


@dataclass(frozen=True)
class WebhookConfig:
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


class Webhook:
    """Deliveries to one URL."""

    def __init__(self, url: str, config: WebhookConfig) -> None:
        self.url = url
        self.config = config
        self.counts = Counts()
        self.cell = StatusCell()
        self._queue: queue.Queue[Pushed | None] = queue.Queue(config.queue)
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._work, name=f"webhook {url}", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        with contextlib.suppress(queue.Full):  # a full queue: the worker sees the flag before its next event
            self._queue.put_nowait(_STOP)
        self._thread.join(timeout=self.config.timeout + 1)

    def enqueue(self, event: Pushed) -> None:
        """Never blocks: a full queue loses its oldest event."""
        with self._lock:
            while True:
                try:
                    self._queue.put_nowait(event)
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
        with httpx.Client(timeout=self.config.timeout) as client:
            while not self._stop.is_set() and (event := self._queue.get()) is not _STOP:
                self._deliver(client, event)

    def _deliver(self, client: httpx.Client, event: Pushed) -> None:
        wait = self.config.backoff
        for attempt in range(self.config.retries + 1):
            error = self._post(client, event)
            if error is None:
                self.counts.delivered += 1
                self.cell.succeeded()
                return
            last = attempt == self.config.retries
            self.cell.failed("webhook_failing", f"{self.url}: {error}", retry_in=None if last else wait)
            if last or self._stop.wait(wait):
                break
            wait = min(wait * 2, self.config.max_backoff)
        self.counts.failed += 1
        log.warning("intent %d not delivered to %s after %d attempts", event.seq, self.url,
                    self.config.retries + 1)

    def _post(self, client: httpx.Client, event: Pushed) -> str | None:
        """None when delivered, else what went wrong."""
        try:
            response = client.post(self.url, json=event.as_json())
        except httpx.HTTPError as exc:
            return f"{type(exc).__name__}: {exc}"
        if response.is_success:
            return None
        return f"HTTP {response.status_code}"


class Webhooks:
    """The webhooks of one service: `enqueue` is the bus listener, `stop` at shutdown."""

    def __init__(self, urls: Sequence[str], config: WebhookConfig | None = None) -> None:
        self.hooks = [Webhook(url, config or WebhookConfig()) for url in urls]

    def start(self) -> None:
        for hook in self.hooks:
            hook.start()

    def enqueue(self, event: Pushed) -> None:
        for hook in self.hooks:
            hook.enqueue(event)

    def stop(self) -> None:
        for hook in self.hooks:
            hook.stop()
