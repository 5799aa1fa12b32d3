"""With a token configured, every write route (found from the OpenAPI document) refuses callers
without it; with anonymous reads off, every route but /health and /version does."""

from __future__ import annotations

import json
import re

import pytest
from pydantic import SecretStr
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from api.settings import Settings
from tests.api.conftest import SCENE, Live

TOKEN = "t0k3n-for-tests"
#: POSTs that only read (/model/parse is none: it runs a turn, which spends model requests, issue 26).
READ_POSTS = {("/kb/query", "post"), ("/sparql", "post")}
OPEN = {"/health", "/version", "/webhooks/rest/"}  # liveness probes


def _operations(live: Live) -> list[tuple[str, str]]:
    spec = live.client.get("/openapi.json").json()
    found = [(re.sub(r"\{[^}]+\}", "x", path), method) for path, item in spec["paths"].items()
             for method in item if method in ("get", "post", "put", "patch", "delete")]
    assert ("/kb/revise", "post") in found and ("/kb/query", "get") in found
    return found


def _call(live: Live, path: str, method: str, headers: dict[str, str] | None = None) -> int:
    body: dict[str, object] | None = {} if method != "get" else None
    return live.client.request(method.upper(), path, headers=headers, json=body).status_code


def test_every_write_route_needs_the_token(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(Settings(scene=SCENE, token=SecretStr(TOKEN), sparql_update=True))
    writes = [(p, m) for p, m in _operations(live) if m != "get" and (p, m) not in READ_POSTS]
    assert ("/kb/clear", "post") in writes and ("/kb/load", "post") in writes
    assert ("/model/parse", "post") in writes  # as dialogue turns
    assert {("/scene", "put"), ("/scene/entities/x", "put"), ("/scene/entities/x", "delete")} <= set(writes)
    for path, method in writes:
        assert _call(live, path, method) == 401, (path, method)
        assert _call(live, path, method, {"authorization": "Bearer wrong"}) == 403, (path, method)
        authorised = _call(live, path, method, {"authorization": f"Bearer {TOKEN}"})
        assert authorised not in (401, 403), (path, method)
    # SPARQL Update is a write on the read route /sparql
    update = {"update": "INSERT DATA { <http://kb.openrobots.org#a> <http://kb.openrobots.org#b> "
                        "<http://kb.openrobots.org#c> }"}
    assert live.client.post("/sparql", data=update).status_code == 401
    assert live.client.post("/sparql", data=update, headers={"authorization": "Bearer wrong"}).status_code == 403
    assert live.client.post("/sparql", data=update, headers={"authorization": f"Bearer {TOKEN}"}).status_code == 204
    # the Rasa facade also takes ?token=, as Rasa's HTTP API does; a wrong one is refused
    hook = {"sender": "person_alice", "message": "hello"}
    assert live.client.post("/webhooks/rest/webhook", json=hook, params={"token": "wrong"}).status_code == 403
    assert live.client.post("/webhooks/rest/webhook", json=hook, params={"token": TOKEN}).status_code == 200
    # reads stay open by default
    assert live.client.get("/kb/query", params={"pattern": "myself sees ?o"}).status_code == 200
    assert live.services.kb.find(["myself sees ?o"]) == []  # the authorised /kb/clear above ran


def test_closed_reads_need_the_token_everywhere_but_health(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(Settings(scene=SCENE, token=SecretStr(TOKEN), allow_anonymous_reads=False))
    for path, method in _operations(live):
        if path in OPEN or path == "/kb/events":
            continue
        status = _call(live, path, method)
        assert status == 401, (path, method, status)
    assert live.client.get("/health").status_code == 200
    refused = live.client.get("/kb/events", params={"pattern": "?a sees ?b"})
    assert refused.status_code == 401 and refused.headers["www-authenticate"] == "Bearer"
    with live.client.stream("GET", "/kb/events", params={"pattern": "?a sees ?b", "access_token": TOKEN}) as sse:
        assert sse.status_code == 200 and next(sse.iter_lines()).startswith("event: subscribed")
    allowed = live.client.get("/kb/query", params={"pattern": "myself sees ?o"},
                              headers={"authorization": f"Bearer {TOKEN}"})
    assert allowed.status_code == 200 and {"o": "cup_1"} in allowed.json()


def test_websocket_reads_need_the_token_when_closed(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(Settings(scene=SCENE, token=SecretStr(TOKEN), allow_anonymous_reads=False))
    with connect(live.ws_url + "/kb/events/ws") as ws:
        error = json.loads(ws.recv(timeout=30))
        assert error["status"] == 401
        with pytest.raises(ConnectionClosed):
            ws.recv(timeout=30)
    headers = {"Authorization": f"Bearer {TOKEN}"}
    with connect(live.ws_url + "/kb/events/ws", additional_headers=headers) as ws:
        ws.send(json.dumps({"patterns": ["?a sees ?b"]}))
        assert "subscribed" in json.loads(ws.recv(timeout=30))


def test_cors_is_closed_unless_configured(live_factory) -> None:  # type: ignore[no-untyped-def]
    closed = live_factory()
    preflight = {"origin": "http://evil.example", "access-control-request-method": "POST"}
    assert "access-control-allow-origin" not in closed.client.options("/kb/query", headers=preflight).headers
    opened = live_factory(Settings(scene=SCENE, cors_origins=["http://viewer.example"]))
    ok = opened.client.options("/kb/query", headers={**preflight, "origin": "http://viewer.example"})
    assert ok.headers["access-control-allow-origin"] == "http://viewer.example"
    other = opened.client.get("/health", headers={"origin": "http://evil.example"})
    assert "access-control-allow-origin" not in other.headers
    with pytest.raises(ValueError, match="wildcard"):
        Settings(cors_origins=["*"])
