"""Outgoing webhooks: every pushed intent POSTed as JSON to each configured URL.

One courier (api.courier) per URL: a worker thread and a bounded queue, so a slow or failing
receiver delays nobody else, and a turn never waits for any of them (the bus hands an event over
with a non-blocking put; a full queue drops its oldest event, counted). A delivery that fails (a
transport error, or any status but 2xx) is retried with a backoff that doubles, then given up
(counted); events are delivered in order per URL. While a URL's deliveries fail, `/health` reports
it degraded, with the reason and the counts; once it recovers, it is ok, with the counts as long as
any intent was lost (given up or dropped).
"""

from __future__ import annotations

from collections.abc import Sequence

import httpx

from api.courier import Courier, DeliveryConfig
from dialogue.pushed.events import Pushed


class Webhook(Courier[Pushed]):
    """Deliveries to one URL."""

    def __init__(self, url: str, config: DeliveryConfig) -> None:
        super().__init__(url, config, "webhook_failing")
        self.url = url
        self._client = httpx.Client(timeout=config.timeout)

    def _send(self, item: Pushed) -> str | None:
        try:
            response = self._client.post(self.url, json=item.as_json())
        except httpx.HTTPError as exc:
            return f"{type(exc).__name__}: {exc}"
        if response.is_success:
            return None
        return f"HTTP {response.status_code}"

    def _closing(self) -> None:
        self._client.close()

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
