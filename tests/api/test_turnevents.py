"""The interaction route as Server-Sent Events (`Accept: text/event-stream`): the early ack, then the
JSON answer; without that header nothing changes."""

from __future__ import annotations

import asyncio
import json
import threading
import time
from typing import Any

import httpx
import pytest

from api.settings import Settings
from api.turnevents import wants_events
from dialogue import intents as I
from dialogue.llm.base import ChatModel, ChatRequest, ChatResult
from dialogue.llm.stream import TextSink
from dialogue.llm.testing import ScriptedModel
from tests.api.conftest import SCENE, Live

SSE = {"Accept": "text/event-stream"}
ALICE = "person_alice"


def grab(obj: str, ack: str | None) -> str:
    return json.dumps({"verbal_ack": ack, "user_intent": {"type": I.GRAB_OBJECT, "object": obj}})


def events(client: httpx.Client, url: str, body: dict[str, Any],
           on_event: Any = None) -> list[tuple[str, Any]]:
    """The (event, data) pairs of one streamed answer, in order."""
    seen: list[tuple[str, Any]] = []
    with client.stream("POST", url, json=body, headers=SSE) as response:
        assert response.status_code == 200
        assert response.headers["content-type"].startswith("text/event-stream")
        name, data = "message", ""
        for line in response.iter_lines():
            if line.startswith("event:"):
                name = line[6:].strip()
            elif line.startswith("data:"):
                data += line[5:].strip()
            elif not line and data:
                seen.append((name, json.loads(data)))
                if on_event is not None:
                    on_event(name)
                name, data = "message", ""
    return seen


def new_dialogue(live: Live) -> str:
    return str(live.client.post("/dialogues", json={}).json()["dialogue_id"])


class GatedModel(ChatModel):
    """Streams the part of its answer up to the end of the ack, then waits for the test to let it
    finish: the ack can only reach the client before the answer is complete."""

    name = "gated"

    def __init__(self, answer: str, upto: str) -> None:
        self.answer = answer
        self.split = answer.index(upto) + len(upto)
        self.release = threading.Event()

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        return ChatResult(self.answer)

    async def chat_stream(self, request: ChatRequest, timeout: float, on_text: TextSink) -> ChatResult:
        on_text(self.answer[: self.split])
        await asyncio.to_thread(self.release.wait, 60)
        on_text(self.answer[self.split :])
        return ChatResult(self.answer)


def test_the_ack_comes_before_the_answer_is_complete_then_the_json_answer(live_factory) -> None:  # type: ignore[no-untyped-def]
    answer = grab("cup_1", "On my way.")
    model = GatedModel(answer, '"On my way."')
    live = live_factory(Settings(scene=SCENE, deadline=60), model=model)

    def on_event(name: str) -> None:
        if name == "ack":
            model.release.set()

    url = f"/dialogues/{new_dialogue(live)}/interactions"
    streamed = events(live.client, url, {"user_id": ALICE, "input": "get the cup"}, on_event)
    assert [name for name, _ in streamed] == ["ack", "response"]
    assert streamed[0][1] == {"verbal_ack": "On my way."}
    plain = live.client.post(f"/dialogues/{new_dialogue(live)}/interactions",
                             json={"user_id": ALICE, "input": "get the cup"})
    assert plain.headers["content-type"] == "application/json"
    assert streamed[1][1] == plain.json()
    assert plain.json()["response"] == "On my way." and plain.json()["intents"][0]["data"] == {"object": "cup_1"}


@pytest.mark.parametrize("accept", [None, "*/*", "application/json", "application/json, text/event-stream",
                                    "text/html", "text/event-stream;q=0.5, application/json"])
def test_without_a_preference_for_events_the_answer_is_json(live: Live, accept: str | None) -> None:
    headers = {"Accept": accept} if accept else {}
    reply = live.client.post("/dialogues/default/interactions", headers=headers,
                             json={"user_id": ALICE, "input": "please pick up the cup"})
    assert reply.status_code == 200 and reply.headers["content-type"] == "application/json"
    assert reply.json()["intents"][0]["data"] == {"object": "cup_1"}


@pytest.mark.parametrize(("accept", "expected"), [
    ("text/event-stream", True), ("text/event-stream, */*;q=0.1", True), ("text/*", False),
    ("application/json;q=0.2, text/event-stream", True), (None, False), ("", False),
])
def test_wants_events(accept: str | None, expected: bool) -> None:
    assert wants_events(accept) is expected


def test_the_rules_backend_sends_the_final_response_only(live: Live) -> None:
    body = {"user_id": ALICE, "input": "please pick up the cup"}
    streamed = events(live.client, f"/dialogues/{new_dialogue(live)}/interactions", body)
    plain = live.client.post(f"/dialogues/{new_dialogue(live)}/interactions", json=body).json()
    assert streamed == [("response", plain)]


def test_no_ack_when_the_answer_has_none(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(model=ScriptedModel([grab("cup_1", None)], chunk_size=3))
    streamed = events(live.client, "/dialogues/default/interactions", {"user_id": ALICE, "input": "the cup"})
    assert [name for name, _ in streamed] == ["response"]
    assert streamed[0][1]["intents"][0]["intent"] == I.GRAB_OBJECT


def test_the_deadline_holds_and_the_final_event_says_the_turn_fell_back(live_factory) -> None:  # type: ignore[no-untyped-def]
    """The ack is out at once; the rest of the answer would take 15 s; the deadline is 1 s."""
    answer = grab("cup_1", "On my way.")
    model = ScriptedModel([answer], chunk_size=answer.index(",") + 1, chunk_delay=5.0)
    live = live_factory(Settings(scene=SCENE, deadline=1.0), model=model)
    start = time.monotonic()
    streamed = events(live.client, "/dialogues/default/interactions", {"user_id": ALICE, "input": "the cup"})
    elapsed = time.monotonic() - start
    assert [name for name, _ in streamed] == ["ack", "response"]
    final = streamed[1][1]
    assert final["intents"][0]["intent"] == I.RAW_USER_INPUT and "deadline" in final["error_msg"]
    assert elapsed < 10  # the model alone would have needed 15 s


def test_an_answer_that_does_not_validate_ends_with_the_corrected_reply(live_factory) -> None:  # type: ignore[no-untyped-def]
    model = ScriptedModel([grab("unicorn_9", "Taking the unicorn."), grab("unicorn_9", "Still the unicorn.")])
    live = live_factory(model=model)
    streamed = events(live.client, "/dialogues/default/interactions", {"user_id": ALICE, "input": "the unicorn"})
    assert [name for name, _ in streamed] == ["ack", "response"]
    assert streamed[0][1] == {"verbal_ack": "Taking the unicorn."}  # one ack, from the first answer
    final = streamed[1][1]
    assert final["response"] == "Sorry, I did not understand that."
    assert final["intents"][0]["intent"] == I.RAW_USER_INPUT and final["error_msg"]


def test_an_unknown_dialogue_is_refused_before_any_event(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(model=ScriptedModel([grab("cup_1", "OK")]))
    refused = live.client.post("/dialogues/nope/interactions", headers=SSE,
                               json={"user_id": ALICE, "input": "the cup"})
    assert (refused.status_code, refused.json()["code"]) == (404, "unknown_dialogue")
