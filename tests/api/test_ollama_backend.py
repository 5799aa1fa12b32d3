"""The ollama backend through the service, against a fake Ollama server on loopback that checks
it received ``format`` with the turn's JSON schema."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from typing import Any

import pytest
from fastapi import FastAPI

from api.app import create_app
from api.server import serve_in_thread
from api.settings import Settings
from tests.api.conftest import SCENE, Live, serve


@pytest.fixture
def fake_ollama() -> Iterator[tuple[str, list[dict[str, Any]]]]:
    received: list[dict[str, Any]] = []
    app = FastAPI()

    @app.get("/api/tags")
    async def tags() -> dict[str, Any]:
        return {"models": [{"name": "tiny:1b"}]}

    @app.post("/api/chat")
    async def chat(payload: dict[str, Any]) -> dict[str, Any]:
        received.append(payload)
        schema = payload.get("format")
        if not isinstance(schema, dict) or "user_intent" not in schema.get("properties", {}):
            return {"model": payload["model"], "message": {"role": "assistant", "content": "no schema!"},
                    "done": True, "done_reason": "stop"}
        intent_schema = next(s for s in schema["properties"]["user_intent"]["anyOf"]
                             if "object" in s.get("properties", {}))
        if "cup_1" not in intent_schema["properties"]["object"]["enum"]:
            return {"model": payload["model"], "message": {"role": "assistant", "content": "no cup_1!"},
                    "done": True, "done_reason": "stop"}
        answer = {"verbal_ack": "Sure, the cup.",
                  "user_intent": {"type": "__intent_grab_object__", "object": "cup_1", "recipient": None,
                                  "goal": None, "input": None}}
        return {"model": payload["model"], "created_at": "2026-01-01T00:00:00Z",
                "message": {"role": "assistant", "content": json.dumps(answer)},
                "done": True, "done_reason": "stop", "eval_count": 12}

    with serve_in_thread(app) as url:
        yield url, received


def test_ollama_backend_sends_the_schema_and_its_answer_is_grounded(
        live_factory: Callable[..., Live], fake_ollama: tuple[str, list[dict[str, Any]]]) -> None:
    url, received = fake_ollama
    live = live_factory(Settings(scene=SCENE, llm=f"ollama:tiny:1b@{url}"))
    health = live.client.get("/health").json()
    assert health["model"]["reachable"] is True and health["model"]["remote"] is True
    reply = live.client.post("/dialogues/default/interactions",
                             json={"user_id": "person_alice", "input": "could you fetch me that mug"}).json()
    assert reply["error_msg"] == ""
    assert reply["intents"][0]["intent"] == "__intent_grab_object__"
    assert reply["intents"][0]["data"] == {"object": "cup_1"}
    (payload,) = received
    assert payload["model"] == "tiny:1b" and payload["stream"] is False
    assert payload["format"]["type"] == "object"
    assert payload["options"]["temperature"] == 0


def test_unreachable_ollama_is_reported_and_the_turn_falls_back(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(Settings(scene=SCENE, llm="ollama:tiny:1b@http://127.0.0.1:9", deadline=2))
    health = live.client.get("/health").json()
    assert health["status"] == "degraded" and health["model"]["reachable"] is False
    reply = live.client.post("/dialogues/default/interactions",
                             json={"user_id": "person_alice", "input": "could you fetch me that mug"}).json()
    assert reply["intents"][0]["intent"] == "__raw_user_input__" and reply["error_msg"]


def test_the_service_keeps_one_client_and_closes_it_at_shutdown(
        fake_ollama: tuple[str, list[dict[str, Any]]]) -> None:
    url, received = fake_ollama
    with serve(create_app(Settings(scene=SCENE, llm=f"ollama:tiny:1b@{url}"))) as live:
        for _ in range(3):
            reply = live.client.post("/dialogues/default/interactions",
                                     json={"user_id": "person_alice", "input": "could you fetch me that mug"})
            assert reply.json()["error_msg"] == ""
        model = live.services.model
        assert len(received) == 3 and model.client.made == 1 and model.client.open
    assert not model.client.open  # closed by the lifespan


def test_a_hybrid_service_asks_ollama_only_for_what_the_rules_do_not_understand(
        fake_ollama: tuple[str, list[dict[str, Any]]], live_factory: Callable[..., Live]) -> None:
    url, received = fake_ollama
    live = live_factory(Settings(scene=SCENE, llm=f"hybrid:ollama:tiny:1b@{url}"))
    health = live.client.get("/health").json()
    assert health["model"]["reachable"] is True and health["model"]["name"] == f"ollama:tiny:1b@{url}"
    rules = live.client.post("/dialogues/default/interactions",
                             json={"user_id": "person_alice", "input": "pick up the cup"}).json()
    assert rules["intents"][0]["data"] == {"object": "cup_1"} and received == []
    model = live.client.post("/dialogues/default/interactions",
                             json={"user_id": "person_alice", "input": "how is the weather today?"}).json()
    assert model["response"] == "Sure, the cup." and len(received) == 1
