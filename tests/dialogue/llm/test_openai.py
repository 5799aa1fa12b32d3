import asyncio

import httpx
import pytest

from dialogue.llm.base import ModelError
from dialogue.llm.openai import OpenAIModel, OpenAIOptions
from tests.dialogue.llm.common import ANSWER, SCHEMA, request
from tests.dialogue.llm.fakeserver import fake_server, free_port_url


def reply(content: str | None, finish: str = "stop") -> dict[str, object]:
    return {
        "choices": [
            {"index": 0, "message": {"role": "assistant", "content": content}, "finish_reason": finish}
        ]
    }


def test_json_schema_response_format_with_explicit_sampling() -> None:
    with fake_server() as server:
        server.replies.append((200, reply(ANSWER)))
        model = OpenAIModel("qwen", server.url + "/v1/")
        result = asyncio.run(model.chat(request(), timeout=5))
    assert result.content == ANSWER
    path, body = server.requests[0]
    assert path == "/v1/chat/completions"
    assert body["response_format"] == {
        "type": "json_schema",
        "json_schema": {"name": "chatbot_response", "schema": SCHEMA},
    }
    assert body["temperature"] == 0 and body["max_tokens"] == 256 and body["stream"] is False
    assert not {"format", "options", "think", "keep_alive"} & set(body)  # D16


def test_json_object_variant() -> None:
    with fake_server() as server:
        server.replies.append((200, reply(ANSWER)))
        model = OpenAIModel("m", server.url + "/v1", OpenAIOptions(response_format="json_object"))
        asyncio.run(model.chat(request(), timeout=5))
    assert server.requests[0][1]["response_format"] == {"type": "json_object", "schema": SCHEMA}


@pytest.mark.parametrize(
    ("status", "body", "message"),
    [
        (200, reply(ANSWER, "length"), "truncated"),
        (200, reply(None), "empty content"),
        (200, {"unexpected": True}, "unexpected body"),
        (503, {"error": "loading"}, "HTTP 503"),
    ],
)
def test_failures_are_model_errors(status: int, body: dict[str, object], message: str) -> None:
    with fake_server() as server:
        server.replies.append((status, body))
        with pytest.raises(ModelError, match=message):
            asyncio.run(OpenAIModel("m", server.url + "/v1").chat(request(), timeout=5))


def test_unreachable_and_timeout() -> None:
    with pytest.raises(ModelError, match="unreachable"):
        asyncio.run(OpenAIModel("m", free_port_url() + "/v1").chat(request(), timeout=2))
    with fake_server() as server:
        server.delay = 0.6
        server.replies.append((200, reply(ANSWER)))
        with pytest.raises(ModelError, match="within"):
            asyncio.run(OpenAIModel("m", server.url + "/v1").chat(request(), timeout=0.2))


def test_one_client_for_every_turn_closed_by_aclose() -> None:
    seen: list[httpx.Request] = []

    def answer(req: httpx.Request) -> httpx.Response:
        seen.append(req)
        return httpx.Response(200, json=reply(ANSWER))

    model = OpenAIModel("m", "http://llm.test/v1", transport=httpx.MockTransport(answer))

    async def turns() -> httpx.AsyncClient:
        for _ in range(3):
            assert (await model.chat(request(), timeout=5)).content == ANSWER
        client = model.client.get()
        await model.aclose()
        return client

    client = asyncio.run(turns())
    assert len(seen) == 3 and model.client.made == 1
    assert client.is_closed and not model.client.open


def test_turns_share_one_connection_to_the_server() -> None:
    with fake_server(keep_alive=True) as server:
        server.replies.extend([(200, reply(ANSWER))] * 3)
        model = OpenAIModel("m", server.url + "/v1")

        async def turns() -> None:
            for _ in range(3):
                await model.chat(request(), timeout=5)
            await model.aclose()

        asyncio.run(turns())
    assert len(server.peers) == 3 and len(set(server.peers)) == 1


@pytest.mark.parametrize(("status", "reachable"), [(200, True), (404, True), (503, False)])
def test_probe_lists_the_models_with_the_turns_client(status: int, reachable: bool) -> None:
    def answer(req: httpx.Request) -> httpx.Response:
        if req.url.path == "/v1/models":
            return httpx.Response(status, json={"data": []})
        return httpx.Response(200, json=reply(ANSWER))

    model = OpenAIModel("m", "http://llm.test/v1", transport=httpx.MockTransport(answer))

    async def probe_and_turn() -> dict[str, object]:
        health = await model.probe(1.0)
        await model.chat(request(), timeout=5)
        await model.aclose()
        return health

    health = asyncio.run(probe_and_turn())
    assert health == {"remote": True, "reachable": reachable, "detail": f"http://llm.test/v1/models: HTTP {status}"}
    assert model.client.made == 1


def test_probe_of_an_unreachable_server() -> None:
    health = asyncio.run(OpenAIModel("m", free_port_url() + "/v1").probe(1.0))
    assert health["remote"] is True and health["reachable"] is False and "/v1/models" in str(health["detail"])


def test_a_base_url_with_a_key_keeps_its_query_and_never_shows_the_key() -> None:
    """Red team round 3 rerun: `...?key=K` once became `/v1?key=K/chat/completions` (the path glued
    to the key), and the key was in the model's name, every error, the log and the turns' traces."""
    with fake_server() as server:
        server.replies.append((200, reply(ANSWER)))
        server.replies.append((503, {"error": "loading"}))
        model = OpenAIModel("m", server.url + "/v1?key=k3y&room=4")
        asyncio.run(model.chat(request(), timeout=5))
        with pytest.raises(ModelError) as failed:
            asyncio.run(model.chat(request(), timeout=5))
        probed = asyncio.run(model.probe(timeout=5))
    assert server.requests[0][0] == "/v1/chat/completions?key=k3y&room=4"
    for shown in (model.name, model.setup_hint, str(failed.value), probed["detail"]):
        assert "k3y" not in shown and "key=[redacted]&room=4" in shown, shown
