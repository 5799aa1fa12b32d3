"""A reader's intents handed to the writer's bus: one intent stream for a scaled-out deployment.

Each reader answers its own turns, but the middleware follows one stream, the writer's: a reader's
turn observer hands every intent it emits, with its dialogue id, reply and time, to the writer
(`POST /intents` through api.client.ServiceClient), which numbers it among everything else it
pushes (the other readers' turns, its own, its initiative). A courier (api.courier) does it off the
turn: bounded queue, in order, retried with doubling backoff, a turn never waits; `/health` shows
the relay degraded while the writer does not take them, and how many were lost. A reader's
`/intents` routes are the writer's (api.forward proxies them), so every process serves the same
stream with one numbering.
"""

from __future__ import annotations

from api.client import ClientError, ServiceClient
from api.courier import Courier, DeliveryConfig
from dialogue.pushed.events import Emitted, emitted
from dialogue.sessions.observers import TurnRecord


class IntentRelay(Courier[Emitted]):
    """Hands a reader's emitted intents to the writer; `observe` is the dialogue manager's observer."""

    def __init__(self, writer: ServiceClient, config: DeliveryConfig) -> None:
        super().__init__(f"the writer at {writer.url}", config, "intent_relay_failing")
        self.writer = writer

    async def observe(self, record: TurnRecord) -> None:
        for event in emitted(record):
            self.enqueue(event)

    def _send(self, item: Emitted) -> str | None:
        try:
            self.writer.publish_intent(item.as_json())
        except ClientError as exc:
            return str(exc)
        return None

    def _closing(self) -> None:
        self.writer.close()

    def _what(self, item: Emitted) -> str:
        return f"a {item.intent.intent} of dialogue {item.dialogue_id}"
