"""A reader's intent relay (api.relay): what its turns emit reaches the writer's stream, in order,
numbered there; a writer that does not take them is retried, then given up, and /health says so."""

from __future__ import annotations

import asyncio
from typing import Any

from api.client import ServiceClient
from api.courier import DeliveryConfig
from api.relay import IntentRelay
from bench.oxigraph import free_port
from dialogue import intents as I
from dialogue.engine import TurnResult
from dialogue.sessions.observers import TurnRecord
from tests.api.conftest import scene_settings
from tests.waiting import until

TOKEN = "relay-token"
TURN_AT = 1_750_000_000.5


def turn(dialogue: str = "kitchen_talk") -> TurnRecord:
    fetch = I.make_intent(I.BRING_OBJECT, {"object": "cup_1", "recipient": "person_alice"}, source="person_alice",
                          confidence=0.9)
    greet = I.make_intent(I.GREET, {"recipient": "person_alice"}, source="person_alice", confidence=1.0)
    result = TurnResult("Hello! OK, I will bring the cup to you.", (greet, fetch))
    return TurnRecord(dialogue, "person_alice", "hi, bring me the cup", result, TURN_AT)


def test_a_turns_intents_reach_the_writers_stream_in_order(live_factory: Any) -> None:
    writer = live_factory(scene_settings(token=TOKEN))
    relay = IntentRelay(ServiceClient(writer.url, TOKEN, name="writer"), DeliveryConfig(backoff=0.05))
    relay.start()
    try:
        before = writer.client.get("/intents").json()["last_seq"]
        record = turn()
        asyncio.run(relay.observe(record))
        until(lambda: relay.counts.delivered == 2)
    finally:
        relay.stop()
    pushed = writer.client.get("/intents", params={"after": before}).json()["intents"]
    assert [p["seq"] for p in pushed] == [before + 1, before + 2]
    assert [p["intent"] for p in pushed] == [i.model_dump(mode="json") for i in record.result.intents]
    assert [(p["origin"], p["dialogue_id"], p["response"], p["time"]) for p in pushed] == [
        ("dialogue", "kitchen_talk", record.result.response, TURN_AT), ("dialogue", "kitchen_talk", "", TURN_AT)]
    assert relay.status().ok and relay.status().reason == ""


def test_a_writer_that_refuses_them_is_retried_then_given_up_and_health_says_so(live_factory: Any) -> None:
    writer = live_factory(scene_settings(token=TOKEN))
    relay = IntentRelay(ServiceClient(writer.url, "not-the-token", name="writer"),
                        DeliveryConfig(retries=2, backoff=0.01))
    relay.start()
    try:
        asyncio.run(relay.observe(turn()))  # returns at once: the relay works off the turn
        until(lambda: relay.counts.failed == 2)
        status = relay.status()
        assert not status.ok and status.code == "intent_relay_failing"
        assert f"the writer at {writer.url}" in status.reason and "HTTP 403" in status.reason
        assert "0 delivered, 2 given up" in status.reason and status.failures == 6  # each tried three times
        assert relay.report() == {"delivered": 0, "given_up": 2, "dropped": 0, "queued": 0}
    finally:
        relay.stop()
    assert writer.client.get("/intents").json()["intents"] == []


def test_a_writer_that_cannot_be_reached_is_an_error_that_says_where() -> None:
    relay = IntentRelay(ServiceClient(f"http://127.0.0.1:{free_port()}", name="writer"),
                        DeliveryConfig(retries=0))
    relay.start()
    try:
        asyncio.run(relay.observe(turn()))
        until(lambda: relay.counts.failed == 2)
        assert "cannot be reached" in relay.status().reason
    finally:
        relay.stop()
