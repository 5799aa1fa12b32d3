import asyncio

import httpx
import ollama
import pytest

from dialogue.llm.base import ModelError
from dialogue.llm.ollama import OllamaModel, OllamaOptions
from tests.dialogue.llm.common import ANSWER, SCHEMA, request
from tests.dialogue.llm.fakeserver import fake_server, free_port_url


def reply(content: str, done_reason: str = "stop") -> dict[str, object]:
    return {
        "model": "gemma3:1b",
        "created_at": "2026-01-01T00:00:00Z",
        "done": True,
        "done_reason": done_reason,
        "message": {"role": "assistant", "content": content},
        "eval_count": 12,
    }


def test_native_chat_with_schema_format_and_explicit_options() -> None:
    with fake_server() as server:
        server.replies.append((200, reply(ANSWER)))
        model = OllamaModel("gemma3:1b", server.url, OllamaOptions(num_ctx=8192, num_predict=200))
        result = asyncio.run(model.chat(request(), timeout=5))
    assert result.content == ANSWER and result.done_reason == "stop"
    path, body = server.requests[0]
    assert path == "/api/chat"
    assert body["format"] == SCHEMA
    assert body["options"]["temperature"] == 0
    assert body["options"]["num_ctx"] == 8192 and body["options"]["num_predict"] == 200
    assert body["stream"] is False and body["think"] is False
    assert body["messages"][0] == {"role": "system", "content": "be nice"}
    assert "response_format" not in body


@pytest.mark.parametrize(
    ("status", "body", "message"),
    [
        (200, reply(ANSWER[:20], "length"), "truncated"),
        (200, reply("   "), "empty content"),
        (404, {"error": "model 'x' not found"}, "HTTP 404"),
    ],
)
def test_failures_are_model_errors(status: int, body: dict[str, object], message: str) -> None:
    with fake_server() as server:
        server.replies.append((status, body))
        with pytest.raises(ModelError, match=message):
            asyncio.run(OllamaModel("gemma3:1b", server.url).chat(request(), timeout=5))


def test_unreachable_server_is_a_model_error() -> None:
    with pytest.raises(ModelError, match="unreachable"):
        asyncio.run(OllamaModel("gemma3:1b", free_port_url()).chat(request(), timeout=2))


def test_timeout_is_a_model_error() -> None:
    with fake_server() as server:
        server.delay = 0.6
        server.replies.append((200, reply(ANSWER)))
        with pytest.raises(ModelError, match=r"within 0\.2 s"):
            asyncio.run(OllamaModel("gemma3:1b", server.url).chat(request(), timeout=0.2))


def test_think_can_be_left_to_the_model() -> None:
    model = OllamaModel("gpt-oss:20b", options=OllamaOptions(think=None))
    assert "think" not in model.payload(request())
    with pytest.raises(ValueError, match="model name"):
        OllamaModel("")


def test_preload_sends_an_empty_chat_with_keep_alive() -> None:
    with fake_server() as server:
        server.replies.append((200, reply("")))
        asyncio.run(OllamaModel("gemma3:1b", server.url, OllamaOptions(keep_alive="1h")).preload(timeout=5))
    path, body = server.requests[0]
    assert path == "/api/chat" and body["messages"] == [] and body["keep_alive"] == "1h"
    with pytest.raises(ModelError, match="unreachable"):
        asyncio.run(OllamaModel("gemma3:1b", free_port_url()).preload(timeout=2))


def test_one_client_for_every_turn_closed_by_aclose() -> None:
    seen: list[str] = []

    def answer(req: httpx.Request) -> httpx.Response:
        seen.append(req.url.path)
        return httpx.Response(200, json=reply(ANSWER))

    model = OllamaModel("gemma3:1b", "http://ollama.test:11434", transport=httpx.MockTransport(answer))

    async def turns() -> ollama.AsyncClient:
        await model.preload(timeout=5)
        for _ in range(3):
            assert (await model.chat(request(), timeout=5)).content == ANSWER
        client = model.client.get()
        await model.aclose()
        return client

    client = asyncio.run(turns())
    assert seen == ["/api/chat"] * 4 and model.client.made == 1
    assert client._client.is_closed and not model.client.open


def test_turns_share_one_connection_to_the_server() -> None:
    with fake_server(keep_alive=True) as server:
        server.replies.extend([(200, reply(ANSWER))] * 3)
        model = OllamaModel("gemma3:1b", server.url)

        async def turns() -> None:
            for _ in range(3):
                await model.chat(request(), timeout=5)
            await model.aclose()

        asyncio.run(turns())
    assert len(server.peers) == 3 and len(set(server.peers)) == 1


@pytest.mark.parametrize(("status", "reachable"), [(200, True), (404, True), (500, False)])
def test_probe_lists_the_models_with_the_turns_client(status: int, reachable: bool) -> None:
    def answer(req: httpx.Request) -> httpx.Response:
        if req.url.path == "/api/tags":
            return httpx.Response(status, json={"models": []} if status == 200 else {"error": "no"})
        return httpx.Response(200, json=reply(ANSWER))

    model = OllamaModel("gemma3:1b", "http://ollama.test:11434", transport=httpx.MockTransport(answer))

    async def probe_and_turn() -> dict[str, object]:
        health = await model.probe(1.0)
        await model.chat(request(), timeout=5)
        await model.aclose()
        return health

    health = asyncio.run(probe_and_turn())
    assert health == {"remote": True, "reachable": reachable,
                      "detail": f"http://ollama.test:11434/api/tags: HTTP {status}"}
    assert model.client.made == 1


def test_probe_of_an_unreachable_server() -> None:
    health = asyncio.run(OllamaModel("gemma3:1b", free_port_url()).probe(1.0))
    assert health["remote"] is True and health["reachable"] is False and "/api/tags" in str(health["detail"])
