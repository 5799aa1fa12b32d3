"""KB events over Server-Sent Events and WebSocket, against a real server and real sockets."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import httpx
import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from api.settings import Limits, Settings
from tests.api.conftest import SCENE, Live
from tests.waiting import until


def _events(lines: Iterator[str]) -> Iterator[tuple[str, Any]]:
    """(event name, decoded data) pairs from an SSE line stream; comments are skipped."""
    name, data = "message", list[str]()
    for line in lines:
        if line.startswith(":"):
            continue
        if not line:
            if data:
                yield name, json.loads("\n".join(data))
            name, data = "message", list[str]()
        elif line.startswith("event:"):
            name = line[6:].strip()
        elif line.startswith("data:"):
            data.append(line[5:].strip())


def _revise(live: Live, *statements: str, method: str = "add") -> None:
    response = live.client.post("/kb/revise", json={"statements": list(statements), "method": method})
    assert response.status_code == 200, response.text


def test_sse_streams_new_rows_only_and_unsubscribes_on_disconnect(live: Live) -> None:
    params: list[tuple[str, str | int | float | bool | None]] = [
        ("pattern", "myself sees ?o"), ("pattern", "?o rdf:type dbr:Cup")]
    with httpx.Client(base_url=live.url, timeout=60) as stream_client, \
            stream_client.stream("GET", "/kb/events", params=params) as response:
        assert response.headers["content-type"].startswith("text/event-stream")
        events = _events(response.iter_lines())
        name, subscribed = next(events)
        assert name == "subscribed" and subscribed["id"].startswith("evt_")
        _revise(live, "cup_2 rdf:type dbr:Cup", "book_2 rdf:type dbr:Book")
        _revise(live, "myself sees book_2")  # no new row for this subscription
        _revise(live, "myself sees cup_2")
        assert next(events) == ("message", [{"o": "cup_2"}])
        _revise(live, "cup_3 rdf:type dbr:Cup", "myself sees cup_3")
        assert next(events) == ("message", [{"o": "cup_3"}])
        assert live.services.hub.listener_count == 1
    until(lambda: live.services.hub.listener_count == 0)
    assert live.services.kb.unsubscribe(subscribed["id"]) is False  # already gone


def test_sse_one_shot_ends_after_the_first_firing(live: Live) -> None:
    with httpx.Client(base_url=live.url, timeout=60) as stream_client, stream_client.stream(
            "GET", "/kb/events", params={"pattern": "?p sees myself", "one_shot": "true"}) as response:
        events = _events(response.iter_lines())
        assert next(events)[0] == "subscribed"
        _revise(live, "person_tom sees myself")
        assert next(events) == ("message", [{"p": "person_tom"}])
        assert next(events) == ("end", {"reason": "one_shot"})
    until(lambda: live.services.hub.listener_count == 0)


def test_two_listeners_share_one_kb_subscription(live: Live) -> None:
    params = {"pattern": "?x isOn table_1"}
    with httpx.Client(base_url=live.url, timeout=60) as one, \
            httpx.Client(base_url=live.url, timeout=60) as two, \
            one.stream("GET", "/kb/events", params=params) as first, \
            two.stream("GET", "/kb/events", params=params) as second:
        a, b = _events(first.iter_lines()), _events(second.iter_lines())
        assert next(a)[1]["id"] == next(b)[1]["id"]
        _revise(live, "plate_1 isOn table_1")
        assert next(a) == next(b) == ("message", [{"x": "plate_1"}])
        first.close()
        until(lambda: live.services.hub.listener_count == 1)
        _revise(live, "fork_1 isOn table_1")
        assert next(b) == ("message", [{"x": "fork_1"}])


def test_bad_subscription_is_a_clear_error(live: Live) -> None:
    response = live.client.get("/kb/events", params={"pattern": "?x sees"})
    assert response.status_code == 400 and response.json()["code"] == "kb_error"
    assert live.client.get("/kb/events").status_code == 422


def test_websocket_streams_rows_over_a_real_socket(live: Live) -> None:
    with connect(live.ws_url + "/kb/events/ws") as ws:
        ws.send(json.dumps({"patterns": ["?h sees ?o", "?h rdf:type Human"]}))
        subscribed = json.loads(ws.recv(timeout=30))
        assert subscribed["subscribed"].startswith("evt_")
        _revise(live, "person_tom sees cup_1")
        assert json.loads(ws.recv(timeout=30)) == [{"h": "person_tom", "o": "cup_1"}]
        assert live.services.hub.listener_count == 1
    until(lambda: live.services.hub.listener_count == 0)


def test_websocket_one_shot_closes_and_bad_messages_are_refused(live: Live) -> None:
    with connect(live.ws_url + "/kb/events/ws") as ws:
        ws.send(json.dumps({"patterns": ["?x isIn kitchen"], "one_shot": True}))
        json.loads(ws.recv(timeout=30))
        _revise(live, "sink_1 isIn kitchen")
        assert json.loads(ws.recv(timeout=30)) == [{"x": "sink_1"}]
        with pytest.raises(ConnectionClosed):
            ws.recv(timeout=30)
    with connect(live.ws_url + "/kb/events/ws") as ws:
        ws.send(json.dumps({"patterns": []}))
        error = json.loads(ws.recv(timeout=30))
        assert error["status"] == 422 and error["message"].startswith("subscription message: patterns")
        with pytest.raises(ConnectionClosed) as closed:
            ws.recv(timeout=30)
        assert closed.value.rcvd is not None and closed.value.rcvd.code == 1008


def test_subscriber_limit_is_429(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(Settings(scene=SCENE, limits=Limits(max_subscribers=1)))
    with httpx.Client(base_url=live.url, timeout=60) as stream_client, \
            stream_client.stream("GET", "/kb/events", params={"pattern": "?a sees ?b"}) as response:
        events = _events(response.iter_lines())  # kept: dropping it closes the stream
        next(events)
        refused = live.client.get("/kb/events", params={"pattern": "?a isOn ?b"})
        assert refused.status_code == 429 and refused.json()["code"] == "too_many_subscribers"
        with connect(live.ws_url + "/kb/events/ws") as ws:
            ws.send(json.dumps({"patterns": ["?a isOn ?b"]}))
            assert json.loads(ws.recv(timeout=30))["code"] == "too_many_subscribers"
    until(lambda: live.services.hub.listener_count == 0)
    with connect(live.ws_url + "/kb/events/ws") as ws:
        ws.send(json.dumps({"patterns": ["?a isOn ?b"]}))
        assert "subscribed" in json.loads(ws.recv(timeout=30))


def test_changes_stream_reports_additions_and_removals(live: Live) -> None:
    with httpx.Client(base_url=live.url, timeout=60) as client, \
            client.stream("GET", "/kb/changes") as stream:
        lines = stream.iter_lines()
        assert next(lines) == "event: subscribed"
        live.client.post("/kb/revise", json={"statements": ["cup_1 isOn shelf_9"], "method": "add"})
        live.client.post("/kb/revise", json={"statements": ["cup_1 isOn shelf_9"], "method": "retract"})
        events = []
        for line in lines:
            if line.startswith("data: ") and "revision" in line:
                events.append(json.loads(line[len("data: "):])[0])
                if len(events) == 2:
                    break
    assert ["cup_1", "isOn", "shelf_9"] in events[0]["added"] and ["shelf_9", "placeOf", "cup_1"] in events[0]["added"]
    assert ["cup_1", "isOn", "shelf_9"] in events[1]["removed"] and events[1]["revision"] > events[0]["revision"]
