"""Security review, as tests (the route-by-route auth enumeration lives in tests/api/test_auth.py):
error bodies never leak internals, uploads and queries cannot make the service reach other hosts,
hostile nesting and sizes are refused cleanly, and per-client resources stay bounded."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Iterator
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

import httpx
import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from api.settings import Limits, Settings
from dialogue.llm.base import ChatRequest
from dialogue.llm.testing import FunctionModel
from tests.api.conftest import SCENE, Live
from tests.kb.test_formats import NAMES, RDF_BODY, TRIX_BODY, entity_bomb
from tests.reliability.fake_llm import GOOD_ANSWER
from tests.reliability.server import ServerProcess

GENERIC_500 = {"status": 500, "code": "internal_error", "message": "internal server error; see the service log",
               "details": None}
SECRET = "s3cr3t-internal-path /etc/situated/keys"


@pytest.fixture
def listener() -> Iterator[tuple[str, list[str]]]:
    """An HTTP server on loopback that records every request it gets: nothing should reach it."""
    hits: list[str] = []

    class Handler(BaseHTTPRequestHandler):
        def log_message(self, format: str, *args: Any) -> None:
            pass

        def do_GET(self) -> None:
            hits.append(self.path)
            body = b'{"@context": {"name": "http://schema.org/name"}}'
            self.send_response(200)
            self.send_header("content-type", "application/ld+json")
            self.send_header("content-length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        do_POST = do_GET

    server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}", hits
    server.shutdown()
    server.server_close()


def test_an_internal_error_answers_the_generic_500_and_the_service_goes_on(
        live_factory: Callable[..., Live]) -> None:
    broken = {"now": True}

    def model(request: ChatRequest) -> Any:
        if broken["now"]:
            raise RuntimeError(SECRET)  # not a ModelError: a bug in a backend
        return GOOD_ANSWER

    live = live_factory(Settings(scene=str(SCENE), llm="rules"), model=FunctionModel(model, name="buggy"))
    calls = [("/dialogues/default/interactions", {"user_id": "person_alice", "input": "take the cup"}),
             ("/model/parse", {"text": "take the cup"}),
             ("/webhooks/rest/webhook", {"sender": "person_alice", "message": "take the cup"})]
    for path, body in calls:  # one keep-alive connection: a 500 must not break the next request
        response = live.client.post(path, json=body)
        assert response.status_code == 500, (path, response.text)
        assert response.json() == GENERIC_500
        for leak in ("s3cr3t", "RuntimeError", "Traceback", "File \"", ".py"):
            assert leak not in response.text, (path, leak)
    broken["now"] = False
    reply = live.client.post(*calls[0][:1], json=calls[0][1]).json()
    assert reply["error_msg"] == "" and reply["intents"][0]["data"] == {"object": "cup_1"}


def test_validation_errors_do_not_echo_the_input(live: Live) -> None:
    response = live.client.post("/kb/revise", json={"statements": SECRET, "method": "add"})
    assert response.status_code == 422 and "s3cr3t" not in response.text


def test_an_upload_cannot_make_the_service_fetch_a_remote_context(
        live: Live, listener: tuple[str, list[str]]) -> None:
    url, hits = listener
    documents = [{"@context": f"{url}/context.jsonld", "@id": "http://example.org/a", "name": "x"},
                 {"@context": [{"@vocab": "http://example.org/"}, f"{url}/c2"], "@id": "http://example.org/b"},
                 {"@graph": [{"@context": {"@import": f"{url}/c3"}, "@id": "http://example.org/c"}]}]
    for document in documents:
        response = live.client.post("/kb/load", content=json.dumps(document),
                                    headers={"content-type": "application/ld+json"})
        assert response.status_code == 400 and "remote JSON-LD @context" in response.json()["message"]
    for scalar in ("5", '"x"', "null"):
        response = live.client.post("/kb/load", content=scalar, headers={"content-type": "application/ld+json"})
        assert response.status_code == 400, response.text
    assert hits == []
    inline = {"@context": {"name": "http://example.org/name"}, "@id": "http://example.org/d", "name": "ok"}
    assert live.client.post("/kb/load", content=json.dumps(inline),
                            headers={"content-type": "application/ld+json"}).status_code == 200


def test_no_name_of_json_ld_lets_an_upload_fetch_a_remote_context(
        live: Live, listener: tuple[str, list[str]]) -> None:
    """The format may be named by ?format= or the Content-Type, in any spelling: each is the same
    JSON-LD parser, so each gets the same refusal (the red team's SSRF used ?format=application/ld+json)."""
    url, hits = listener
    document = json.dumps({"@context": f"{url}/context.jsonld", "@id": "http://example.org/a", "name": "x"})
    for name in sorted(NAMES["json-ld"]):
        for params, media in (({"format": name}, "text/turtle"), ({"format": name.upper()}, "text/plain"),
                              ({}, f"{name}; charset=utf-8")):
            if "/" not in media.split(";")[0]:
                continue  # only media types name a format in a Content-Type
            response = live.client.post("/kb/load", params=params, content=document,
                                        headers={"content-type": media})
            assert response.status_code == 400, (name, params, media, response.text)
            assert "remote JSON-LD @context" in response.json()["message"]
    assert hits == []
    assert live.client.get("/kb/query", params={"pattern": "?s <http://schema.org/name> ?o"}).json() == []


@pytest.mark.parametrize(("media", "root", "body"), [("application/rdf+xml", "rdf:RDF", RDF_BODY),
                                                      ("application/trix", "TriX", TRIX_BODY)])
def test_an_xml_entity_bomb_upload_is_refused_at_once(live: Live, media: str, root: str, body: str) -> None:
    before = live.services.kb.revision
    for params, content_type in (({}, media), ({"format": media}, "text/turtle")):
        response = live.client.post("/kb/load", params=params, content=entity_bomb(root, body, 9),
                                    headers={"content-type": content_type}, timeout=60)
        assert response.status_code == 400, response.text
        assert "DTD or entity declarations are refused" in response.json()["message"]
    assert live.services.kb.revision == before


def test_a_sparql_query_cannot_reach_another_host(live: Live, listener: tuple[str, list[str]]) -> None:
    url, hits = listener
    queries = [f"SELECT * WHERE {{ SERVICE <{url}/sparql> {{ ?s ?p ?o }} }}",
               f"SELECT * WHERE {{ OPTIONAL {{ SERVICE SILENT <{url}/q> {{ ?s ?p ?o }} }} }}",
               f"SELECT * FROM <{url}/graph.ttl> WHERE {{ ?s ?p ?o }}",
               f"SELECT * FROM NAMED <{url}/g> WHERE {{ GRAPH ?g {{ ?s ?p ?o }} }}",
               "SELECT * WHERE { GRAPH ?g { ?s ?p ?o } }"]
    for query in queries:
        response = live.client.get("/sparql", params={"query": query})
        assert response.status_code == 400, (query, response.text)
    assert hits == []


def test_hostile_nesting_is_a_clear_4xx_never_a_500(live: Live) -> None:
    deep = 20_000
    cases = [("/kb/load", "text/turtle", "<a> <b> " + "(" * deep + ")" * deep + " ."),
             ("/kb/load", "text/turtle", "<a> <b> " + "[ <p> " * deep + "]" * deep + " ."),
             ("/kb/load", "application/ld+json", "[" * deep + "]" * deep),
             ("/sparql", "application/sparql-query", "SELECT * WHERE " + "{" * deep + "}" * deep),
             ("/sparql", "application/sparql-query", "ASK { ?s ?p " + "(" * deep + ")" * deep + " }")]
    for path, media, body in cases:
        response = live.client.post(path, content=body, headers={"content-type": media})
        assert response.status_code == 400, (path, body[:40], response.text[:200])
        assert response.json()["message"]
    scene = live.client.put("/scene", content="[" * deep + "]" * deep, headers={"content-type": "application/json"})
    assert scene.status_code == 400, scene.text
    for entities in ([None], [{"id": "box", "x": 1e400}], [{"id": "box", "x": "nan"}], [{"id": "box", "z": 1e400}]):
        response = live.client.put("/scene", content=json.dumps({"entities": entities}).replace("Infinity", "1e400"),
                                   headers={"content-type": "application/json"})
        assert response.status_code == 400, (entities, response.text)


def test_the_longest_utterance_allowed_is_answered_within_the_deadline(live: Live) -> None:
    limit = live.services.settings.limits.max_input_chars
    text = ("could you please take the red cup from the table " * (limit // 10))[:limit]
    start = time.monotonic()
    response = live.client.post("/dialogues/default/interactions", json={"user_id": "person_alice", "input": text},
                                timeout=60)
    assert response.status_code == 200 and set(response.json()) == {"response", "intents", "error_msg"}
    assert time.monotonic() - start < live.services.settings.deadline + 10.0  # generous: a busy machine
    longer = live.client.post("/dialogues/default/interactions", json={"user_id": "person_alice", "input": text + "x"})
    assert longer.status_code == 413 and longer.json()["code"] == "input_too_long"


def test_dialogues_and_history_are_bounded(live_factory: Callable[..., Live]) -> None:
    live = live_factory(Settings(scene=str(SCENE), limits=Limits(max_dialogues=3, max_history_turns=4)))
    ids = [live.client.post("/dialogues", json={}).json()["dialogue_id"] for _ in range(6)]
    turn = {"user_id": "person_alice", "input": "hello"}
    kept = [i for i in ids if live.client.post(f"/dialogues/{i}/interactions", json=turn).status_code == 200]
    assert 0 < len(kept) <= 3 and kept == ids[-len(kept):]  # the least recently used are forgotten
    assert live.client.post("/dialogues/default/interactions", json=turn).status_code == 200
    for n in range(20):  # Rasa senders each get a dialogue: bounded the same way
        assert live.client.post("/webhooks/rest/webhook", json={"sender": f"p{n}", "message": "hi"}).status_code == 200
    alive = [n for n in range(20) if live.client.post(f"/dialogues/rasa:p{n}/interactions", json=turn).status_code == 200]
    assert 0 < len(alive) <= 3
    history = [{"speaker": "person_alice", "text": "hi"}] * 5
    too_long = live.client.post("/dialogues/default/interactions", json={**turn, "history": history})
    assert too_long.status_code == 413 and too_long.json()["code"] == "too_many_history_turns"


def test_the_served_cli_bounds_bodies_and_websocket_messages(tmp_path: Path) -> None:
    server = ServerProcess(["--scene", "none"], tmp_path / "server.log",
                           env={"SITUATED_LIMITS__MAX_BODY_BYTES": "4096", "SITUATED_TOKEN": "tok"})
    try:
        server.wait_ready()
        auth = {"authorization": "Bearer tok"}
        big = {"method": "add", "statements": ["a b c"] * 1000}
        refused = httpx.post(server.url + "/kb/revise", json=big, headers=auth)
        assert refused.status_code == 413 and refused.json()["code"] == "body_too_large"
        assert httpx.post(server.url + "/kb/revise", json={"method": "add", "statements": ["a b c"]}).status_code == 401
        ws_url = "ws" + server.url[len("http"):] + "/kb/events/ws"
        with connect(ws_url, max_size=None) as ws:
            ws.send(json.dumps({"patterns": ["?s ?p ?o"] * 2000}))
            with pytest.raises(ConnectionClosed) as closed:
                ws.recv(timeout=30)
            assert closed.value.rcvd is not None and closed.value.rcvd.code == 1009  # message too big
        assert httpx.get(server.url + "/health").status_code == 200
    finally:
        server.stop()


def test_tokens_in_urls_are_redacted_from_the_access_log(tmp_path: Path) -> None:
    """Issue 19, item 11: ``?token=`` (Rasa routes) and ``?access_token=`` (event streams) reach
    uvicorn's request log (HTTP lines and WebSocket handshakes); their values must not."""
    secret = "tok-7f3a9c-do-not-log"
    log = tmp_path / "server.log"
    server = ServerProcess(["--scene", "none"], log,
                           env={"SITUATED_TOKEN": secret, "SITUATED_ALLOW_ANONYMOUS_READS": "false"})
    try:
        server.wait_ready()
        hook = httpx.post(f"{server.url}/webhooks/rest/webhook?token={secret}",
                          json={"sender": "person_alice", "message": "hello"}, timeout=30)
        assert hook.status_code == 200, hook.text
        wrong = httpx.get(f"{server.url}/kb/events?pattern=%3Fs%20%3Fp%20%3Fo&access_token={secret}x&TOKEN={secret}")
        assert wrong.status_code == 403
        ws_url = "ws" + server.url[len("http"):] + f"/kb/events/ws?access_token={secret}"
        with connect(ws_url) as ws:
            ws.send(json.dumps({"patterns": ["?s isOn ?o"]}))
            assert "status" not in json.loads(ws.recv(timeout=10))
    finally:
        server.stop()
    text = log.read_text(errors="replace")
    assert secret not in text
    assert "POST /webhooks/rest/webhook?token=[redacted] HTTP/1.1\" 200" in text
    assert "&access_token=[redacted]&TOKEN=[redacted] HTTP/1.1\" 403" in text
    assert '"WebSocket /kb/events/ws?access_token=[redacted]" [accepted]' in text


def test_closed_by_default() -> None:
    settings = Settings()
    assert settings.host == "127.0.0.1" and settings.cors_origins == [] and settings.sparql_update is False
    with pytest.raises(ValueError, match="wildcard"):
        Settings(cors_origins=["http://ok.example", "*"])
