"""api.client.ServiceClient: the one client of the service's REST API (CLI --url mode, a reader's writes)."""

from __future__ import annotations

import json

import httpx
import pytest

from api.client import ClientError, ServiceClient
from kb.sparqlstore.writetarget import WriteTarget


def _client(handler: httpx.MockTransport, name: str = "service") -> ServiceClient:
    return ServiceClient("http://writer.test", "s3cret", name=name, transport=handler)


def test_a_refusal_carries_the_services_status_code_message_and_details() -> None:
    def refuse(request: httpx.Request) -> httpx.Response:
        return httpx.Response(400, json={"status": 400, "code": "kb_error", "message": "bad statement",
                                         "details": {"at": 1}})

    with _client(httpx.MockTransport(refuse)) as client, pytest.raises(ClientError) as caught:
        client.update(["cup_1 isOn"])
    error = caught.value
    assert (error.status, error.code, error.message, error.details) == (400, "kb_error", "bad statement",
                                                                        {"at": 1})
    assert str(error) == "HTTP 400: bad statement"


def test_an_answer_that_is_not_the_error_shape_is_reported_with_its_status() -> None:
    def broken(request: httpx.Request) -> httpx.Response:
        return httpx.Response(502, text="<html>bad gateway</html>")

    with _client(httpx.MockTransport(broken), name="writer") as client, pytest.raises(ClientError) as caught:
        client.find(["?x isOn ?y"])
    assert (caught.value.status, caught.value.code) == (502, "writer_error")
    assert "bad gateway" in caught.value.message


def test_an_unreachable_service_is_503_and_a_write_says_nothing_was_written() -> None:
    def down(request: httpx.Request) -> httpx.Response:
        raise httpx.ConnectError("connection refused", request=request)

    with _client(httpx.MockTransport(down), name="writer") as client:
        with pytest.raises(ClientError) as write:
            client.clear()
        with pytest.raises(ClientError) as read:
            client.lookup("cup")
    assert (write.value.status, write.value.code) == (503, "writer_unavailable")
    assert write.value.message.startswith("the writer at http://writer.test cannot be reached: ")
    assert write.value.message.endswith("nothing was written")
    assert "nothing was written" not in read.value.message
    with _client(httpx.MockTransport(down)) as client, pytest.raises(ClientError) as plain:
        client.lookup("cup")  # the CLI's --url: once "the service service at ..."
    assert plain.value.message.startswith("the service at http://writer.test cannot be reached: ")


def test_writes_send_the_library_calls_as_the_rest_api_expects() -> None:
    seen: list[tuple[str, str, dict[str, object] | None, str | None]] = []

    def record(request: httpx.Request) -> httpx.Response:
        body = json.loads(request.content) if request.headers.get("content-type") == "application/json" else None
        seen.append((request.method, request.url.path, body, request.headers.get("authorization")))
        return httpx.Response(200, json={"removed": 2} if request.url.path == "/kb/revise" else {})

    with _client(httpx.MockTransport(record)) as client:
        assert isinstance(client, WriteTarget)
        client.update("cup_1 isOn table_1", lifespan=5)
        assert client.remove(["?x isOn table_1"], models=["alice"]) == 2
        client.apply(add=["a sees b"], remove=["a sees c"])
        client.apply_models({"bob": {"add": "a sees b"}, "default": {"remove": ["a sees c"]}})
    assert seen[0] == ("POST", "/kb/revise", {"statements": ["cup_1 isOn table_1"], "method": "update",
                                              "models": None, "lifespan": 5}, "Bearer s3cret")
    assert seen[1][2] == {"statements": ["?x isOn table_1"], "method": "retract", "models": ["alice"]}
    assert seen[2][:2] == ("POST", "/kb/apply")
    assert seen[3][:3] == ("POST", "/kb/apply_models", {"changes": {
        "bob": {"add": ["a sees b"], "remove": []}, "default": {"add": [], "remove": ["a sees c"]}}, "lifespan": None})
