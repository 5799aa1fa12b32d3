"""Outgoing webhooks: every pushed intent POSTed as JSON to each configured URL.

One courier (api.courier) per URL: a worker thread and a bounded queue, so a slow or failing
receiver delays nobody else, and a turn never waits for any of them (the bus hands an event over
with a non-blocking put; a full queue drops its oldest event, counted). A delivery that fails (a
transport error, any status but 2xx, or no whole answer within the timeout: the timeout bounds
the whole delivery, not each read, so a receiver trickling a byte at a time is a slow receiver,
reported as such) is retried with a backoff that doubles, then given up (counted); events are
delivered in order per URL. While a URL's deliveries fail, `/health` reports it degraded, with
the reason and the counts; once it recovers, it is ok, with the counts as long as any intent was
lost (given up or dropped). A URL's credentials, secret parameters and path (where Slack's and
Discord's webhooks hold their secret) are never shown: /health and the log name it without them
(dialogue.trace.urlsecrets).
"""

from __future__ import annotations

import asyncio
from collections.abc import Sequence

import httpx

from api.courier import Courier, DeliveryConfig
from dialogue.pushed.events import Pushed
from dialogue.trace.urlsecrets import hide_path, redact


class Webhook(Courier[Pushed]):
    """Deliveries to one URL. They are sent by an asyncio client on the worker's own event loop:
    a timeout there cancels the request wherever it is (a synchronous client's timeout is per
    read)."""

    def __init__(self, url: str, config: DeliveryConfig) -> None:
        super().__init__(hide_path(url), config, "webhook_failing")
        self.url = url
        self._loop: asyncio.AbstractEventLoop | None = None
        self._client: httpx.AsyncClient | None = None

    def _send(self, item: Pushed) -> str | None:
        if self._loop is None:  # on the worker's thread, where the loop runs
            self._loop = asyncio.new_event_loop()
            self._client = httpx.AsyncClient(timeout=self.config.timeout)
        return self._loop.run_until_complete(self._post(item))

    async def _post(self, item: Pushed) -> str | None:
        assert self._client is not None
        try:
            async with asyncio.timeout(self.config.timeout):
                response = await self._client.post(self.url, json=item.as_json())
        except TimeoutError:
            return (f"slow receiver: no whole answer within {self.config.timeout:g} s "
                    "(the delivery's time in all)")
        except httpx.HTTPError as exc:
            return redact(f"{type(exc).__name__}: {exc}".replace(self.url, self.name))
        if response.is_success:
            return None
        return f"HTTP {response.status_code}"

    def _closing(self) -> None:
        if self._loop is not None and self._client is not None:
            self._loop.run_until_complete(self._client.aclose())
            self._loop.close()

    def _what(self, item: Pushed) -> str:
        return f"intent {item.seq}"


class Webhooks:
    """The webhooks of one service: `enqueue` is the bus listener, `stop` at shutdown."""

    def __init__(self, urls: Sequence[str], config: DeliveryConfig | None = None) -> None:
        self.hooks = [Webhook(url, config or DeliveryConfig()) for url in urls]

    def start(self) -> None:
        for hook in self.hooks:
            hook.start()

    def enqueue(self, event: Pushed) -> None:
        for hook in self.hooks:
            hook.enqueue(event)

    def stop(self) -> None:
        for hook in self.hooks:
            hook.stop()
