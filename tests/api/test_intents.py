"""Intents pushed to the middleware, against a real server: SSE, WebSocket, replay, filters, gaps."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import httpx
import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from api.settings import IntentSettings
from tests.api.conftest import Live, scene_settings

Event = tuple[str, str | None, Any]


def sse(lines: Iterator[str]) -> Iterator[Event]:
    """(event, id, decoded data) from an SSE line stream; comments (keep-alives) skipped."""
    name, ident, data = "message", None, list[str]()
    for line in lines:
        if line.startswith(":"):
            continue
        if not line:
            if data:
                yield name, ident, json.loads("\n".join(data))
            name, ident, data = "message", None, list[str]()
        elif line.startswith("event:"):
            name = line[6:].strip()
        elif line.startswith("id:"):
            ident = line[3:].strip()
        elif line.startswith("data:"):
            data.append(line[5:].strip())


def say(live: Live, text: str, user: str = "person_alice", dialogue: str = "default") -> dict[str, Any]:
    response = live.client.post(f"/dialogues/{dialogue}/interactions", json={"user_id": user, "input": text})
    assert response.status_code == 200, response.text
    body: dict[str, Any] = response.json()
    return body


def test_the_stream_pushes_each_turns_intents_as_the_turn_returns_them(live: Live) -> None:
    with httpx.Client(base_url=live.url, timeout=60) as client, client.stream("GET", "/intents/stream") as stream:
        assert stream.headers["content-type"].startswith("text/event-stream")
        events = sse(stream.iter_lines())
        name, _, hello = next(events)
        n = live.services.bus.first - 1  # numbered from the clock: n + 1 is the first
        assert name == "hello" and hello["last_seq"] == n and hello["gap"] is None
        dialogue = live.client.post("/dialogues", json={}).json()["dialogue_id"]
        turn = say(live, "please bring me the cup", dialogue=dialogue)
        say(live, "what do you see?")  # an answer, no intent: nothing pushed
        say(live, "take the cookbook and put it on the table")
        name, ident, pushed = next(events)
        assert (name, ident, pushed["seq"]) == ("intent", str(n + 1), n + 1)
        assert pushed["intent"] == turn["intents"][0]  # the Intent JSON shape, as the turn returned it
        assert (pushed["origin"], pushed["dialogue_id"], pushed["response"]) == (
            "dialogue", dialogue, turn["response"])
        compound = [next(events)[2] for _ in range(2)]
        assert [(p["seq"], p["intent"]["intent"], p["dialogue_id"]) for p in compound] == [
            (n + 2, "__intent_grab_object__", "default"), (n + 3, "__intent_place_object__", "default")]
        assert compound[0]["response"] and compound[1]["response"] == ""  # the reply goes with the first
    assert live.services.bus.reader_count in (0, 1)  # released once the server sees the disconnect


def test_a_reconnecting_client_replays_what_it_missed_then_gets_the_new(live: Live) -> None:
    n = live.services.bus.first - 1
    say(live, "please bring me the cup")
    with httpx.Client(base_url=live.url, timeout=60) as client:
        with client.stream("GET", "/intents/stream", params={"after": 0}) as stream:
            events = sse(stream.iter_lines())
            next(events)
            last = next(events)[1]
        assert last == str(n + 1)
        say(live, "hello")  # said while the middleware was away
        say(live, "go to the kitchen")
        with client.stream("GET", "/intents/stream", headers={"Last-Event-ID": last}) as stream:
            events = sse(stream.iter_lines())
            assert next(events)[2]["gap"] is None
            missed = [next(events)[2] for _ in range(2)]
            assert [(p["seq"], p["intent"]["intent"]) for p in missed] == [
                (n + 2, "__intent_greet__"), (n + 3, "__intent_move_to__")]
            say(live, "bring me the cookbook")
            assert next(events)[2]["seq"] == n + 4


def test_filters_by_source_and_intent_type(live: Live) -> None:
    n = live.services.bus.first - 1
    say(live, "hello", user="person_tom")
    say(live, "hello")
    say(live, "bring me the cup")
    params: list[tuple[str, str | int | float | bool | None]] = [
        ("after", 0), ("intent", "__intent_greet__"), ("source", "person_alice")]
    with httpx.Client(base_url=live.url, timeout=60) as client, \
            client.stream("GET", "/intents/stream", params=params) as stream:
        events = sse(stream.iter_lines())
        next(events)
        _, _, pushed = next(events)
        assert (pushed["seq"], pushed["intent"]["source"], pushed["intent"]["intent"]) == (
            n + 2, "person_alice", "__intent_greet__")
    buffered = live.client.get("/intents", params={"origin": "dialogue", "source": "person_tom"}).json()
    assert [p["seq"] for p in buffered["intents"]] == [n + 1] and buffered["last_seq"] == n + 3
    refused = live.client.get("/intents", params={"origin": "radio"})
    assert refused.status_code == 422 and "unknown origin" in refused.json()["message"]


def test_what_the_buffer_no_longer_holds_is_said_to_be_missing(live_factory: Any) -> None:
    live = live_factory(scene_settings(intents=IntentSettings(buffer=2)))
    n = live.services.bus.first - 1
    for _ in range(4):
        say(live, "hello")
    answer = live.client.get("/intents", params={"after": 0}).json()
    assert answer["gap"] == {"first": n + 1, "last": n + 2, "restarted": False}
    assert [p["seq"] for p in answer["intents"]] == [n + 3, n + 4]
    # A number from before a restart of the service: all of this run's buffered intents follow.
    again = live.client.get("/intents", params={"after": 99}).json()
    assert again["gap"]["restarted"] and [p["seq"] for p in again["intents"]] == [n + 3, n + 4]


def test_the_websocket_streams_the_same_and_resumes_after_a_number(live: Live) -> None:
    n = live.services.bus.first - 1
    say(live, "hello")
    with connect(live.ws_url + "/intents/ws?after=0&intent=__intent_greet__&intent=__intent_bring_object__") as ws:
        hello = json.loads(ws.recv(timeout=30))
        assert hello["event"] == "hello" and hello["stream"] == live.services.bus.stream
        first = json.loads(ws.recv(timeout=30))
        assert (first["event"], first["seq"], first["intent"]["intent"]) == ("intent", n + 1, "__intent_greet__")
        say(live, "go to the kitchen")  # filtered out
        say(live, "bring me the cup")
        second = json.loads(ws.recv(timeout=30))
        assert (second["seq"], second["intent"]["intent"]) == (n + 3, "__intent_bring_object__")


def test_a_restarted_service_numbers_after_the_earlier_run(live_factory: Any) -> None:
    earlier = live_factory(scene_settings())
    say(earlier, "hello")
    last = earlier.client.get("/intents").json()["last_seq"]
    restarted = live_factory(scene_settings())  # a later start: numbered from a later clock
    for _ in range(3):
        say(restarted, "hello")
    answer = restarted.client.get("/intents", params={"after": last}).json()
    assert answer["gap"]["restarted"] and len(answer["intents"]) == 3


@pytest.mark.parametrize(("query", "says"), [
    ("after=abc", "after"), ("after=-1", "after"), ("origin=radio", "unknown origin"),
    ("after=" + "9" * 5000, "after"),  # past int()'s 4,300 digits: once a traceback and a torn socket
])
def test_a_bad_websocket_request_is_told_what_is_wrong(live: Live, query: str, says: str) -> None:
    with connect(f"{live.ws_url}/intents/ws?{query}") as ws:
        error = json.loads(ws.recv(timeout=30))
        assert error["status"] == 422 and error["code"] == "invalid_request" and says in error["message"]
        with pytest.raises(ConnectionClosed) as closed:
            ws.recv(timeout=30)
        assert closed.value.rcvd is not None and closed.value.rcvd.code == 1008
    assert live.services.bus.reader_count == 0


def test_a_last_event_id_that_is_no_number_is_a_clear_error(live: Live) -> None:
    # "\xb2" is latin-1 "2 superscript": a digit to str.isdigit, no int; 4,301 digits are past int()'s limit
    for bad in (b"abc", b"\xb2", b"9" * 4301, b"1" * 8000):
        answer = live.client.get("/intents/stream", headers={"Last-Event-ID": bad})
        assert answer.status_code == 422 and "Last-Event-ID" in answer.json()["message"], bad[:20]
        assert len(answer.json()["message"]) < 200  # the value is not echoed whole


def test_an_intent_published_by_another_process_is_numbered_on_the_stream(live_factory: Any) -> None:
    live = live_factory(scene_settings(token="pub-token"))
    auth = {"authorization": "Bearer pub-token"}
    n = live.services.bus.last_seq
    intent = {"intent": "__intent_greet__", "data": {"recipient": "person_alice"}, "source": "person_alice"}
    body = {"origin": "dialogue", "dialogue_id": "hall", "response": "Hello!", "intent": intent, "time": 1750000000.5}
    assert live.client.post("/intents", json=body).status_code == 401  # a write: the token
    published = live.client.post("/intents", headers=auth, json=body)
    assert published.status_code == 200, published.text
    assert published.json() == {"seq": n + 1, "stream": live.services.bus.stream}
    [pushed] = live.client.get("/intents", params={"after": n}).json()["intents"]
    assert pushed == {"seq": n + 1, "time": 1750000000.5, "origin": "dialogue", "dialogue_id": "hall",
                      "response": "Hello!", "intent": {**intent, "modality": "__modality_speech__",
                                                       "priority": 128, "confidence": 1.0}}
    bare = live.client.post("/intents", headers=auth, json={"intent": intent}).json()  # defaults: a dialogue's, now
    [pushed] = live.client.get("/intents", params={"after": n + 1}).json()["intents"]
    assert bare["seq"] == n + 2 and pushed["origin"] == "dialogue" and pushed["time"] > 1750000000.5
    for bad in ({**body, "origin": "radio"}, {**body, "time": -1}, {**body, "intent": {**intent, "modality": "x"}},
                {**body, "seq": 5}, {k: v for k, v in body.items() if k != "intent"}):
        refused = live.client.post("/intents", headers=auth, json=bad)
        assert refused.status_code == 422 and refused.json()["message"], bad
    assert live.services.bus.last_seq == n + 2  # nothing of them


def test_a_published_intent_is_a_catalogue_intent_whose_entities_the_kb_knows(live_factory: Any) -> None:
    """POST /intents once took anything: intents no hri_actions_msgs/Intent has, roles naming nothing."""
    live = live_factory(scene_settings(token="pub-token"))
    auth = {"authorization": "Bearer pub-token"}
    n = live.services.bus.last_seq

    def publish(intent: str, data: dict[str, str]) -> httpx.Response:
        body = {"intent": {"intent": intent, "data": data, "source": "person_alice"}}
        return live.client.post("/intents", headers=auth, json=body)

    refusals = [
        (("__intent_dance__", {}), "unknown intent '__intent_dance__'; expected one of"),
        (("__intent_greet__", {}), "GREET is missing required role(s) ['recipient']"),
        (("__intent_greet__", {"recipient": "person_alice", "colour": "red"}), "GREET has no role 'colour'"),
        (("__intent_greet__", {"recipient": "person_nobody"}),
         "recipient 'person_nobody' names nothing in the KB"),
        (("__intent_bring_object__", {"object": "dbr:Unicorn", "recipient": "person_alice"}),
         "object 'dbr:Unicorn' names nothing in the KB"),
        (("__intent_guide__", {"goal": "kitchen", "recipient": "no one"}), "recipient 'no one' is not a KB id"),
    ]
    for (intent, data), says in refusals:
        refused = publish(intent, data)
        assert (refused.status_code, refused.json()["code"]) == (422, "invalid_intent"), (intent, data)
        assert says in refused.json()["message"], refused.json()["message"]
    assert live.services.bus.last_seq == n  # nothing of them
    for intent, data in [("__intent_bring_object__", {"object": "cup_1", "recipient": "person_alice"}),
                         ("__intent_guide__", {"goal": "kitchen", "recipient": "person_alice"}),
                         ("__intent_say__", {"object": "free text, no entity", "recipient": "person_tom"})]:
        assert publish(intent, data).status_code == 200, (intent, data)
    assert live.services.bus.last_seq == n + 3


def test_a_published_intent_carries_json_values_where_no_entity_is_named(live_factory: Any) -> None:
    """A ROS caller's Intent has `data` values of any JSON type (`other_data` an object...): taken
    whole, and given back the same by the buffer, the stream and the WebSocket; a role that names an
    entity stays a KB id, and what no reader can take is refused saying where."""
    live = live_factory(scene_settings(token="pub-token"))
    auth = {"authorization": "Bearer pub-token"}
    n = live.services.bus.last_seq
    other = {"level": 2, "players": ["person_alice", "person_tom"], "timed": True, "rules": None, "pace": 0.5,
             "board": [[1, 2], [3, 4]]}
    intents = [{"intent": "__intent_start_activity__", "data": {"object": "memory_game", "other_data": other},
                "source": "person_alice"},
               {"intent": "__intent_say__", "data": {"object": {"text": "Hi!", "gesture": "wave"},
                                                     "recipient": "person_alice"}, "source": "__myself__"},
               {"intent": "__intent_stop_activity__", "data": {"other_data": 0}, "source": "person_alice"}]
    for intent in intents:
        published = live.client.post("/intents", headers=auth, json={"intent": intent})
        assert published.status_code == 200, published.text
    buffered = live.client.get("/intents", params={"after": n}).json()["intents"]
    assert [e["intent"]["data"] for e in buffered] == [i["data"] for i in intents]
    with live.client.stream("GET", "/intents/stream", params={"after": n}) as stream:
        events = sse(stream.iter_lines())
        streamed = [data for name, _, data in (next(events) for _ in range(4)) if name == "intent"]
    assert [e["intent"]["data"] for e in streamed] == [i["data"] for i in intents]
    with connect(f"{live.ws_url}/intents/ws?after={n}") as ws:
        frames = [json.loads(ws.recv(timeout=10)) for _ in range(4)]
    assert [f["intent"]["data"] for f in frames if f["event"] == "intent"] == [i["data"] for i in intents]

    def refused(data: Any, intent: str = "__intent_start_activity__") -> httpx.Response:
        return live.client.post("/intents", headers=auth, json={"intent": {"intent": intent, "data": data,
                                                                          "source": "person_alice"}})

    deep: Any = "x"
    for _ in range(40):
        deep = {"a": deep}
    cases = [
        (refused({"recipient": {"id": "person_alice"}}, "__intent_greet__"),
         "data.recipient of __intent_greet__ names an entity: a string (a KB id)"),
        (refused({"object": "game", "other_data": deep}), "data.other_data is nested more than 32 levels deep"),
        (refused({"object": "game", "other_data": None}), "data.other_data is null; leave a role with no value out"),
        (refused({"object": "game", "other_data": 10 ** 120}), "data.other_data has a number of 121 digits"),
    ]
    for answer, says in cases:
        assert (answer.status_code, answer.json()["code"]) == (422, "invalid_request"), answer.text
        assert says in answer.json()["message"] and len(answer.json()["message"]) < 400
    nan = live.client.post("/intents", headers={**auth, "content-type": "application/json"}, content=json.dumps(
        {"intent": {"intent": "__intent_start_activity__", "data": {"object": "game", "other_data": [float("nan")]},
                    "source": "person_alice"}}))
    assert nan.status_code == 422 and "data.other_data: nan is not a finite number" in nan.json()["message"]
    large = refused({"object": "game", "other_data": {"cells": list(range(20_000))}})
    assert (large.status_code, large.json()["code"]) == (413, "intent_too_large")
    assert live.services.bus.last_seq == n + len(intents)  # nothing of the refused ones


def test_a_published_intent_and_the_buffer_are_bounded_in_bytes(live_factory: Any) -> None:
    """600 intents of 900 KB once added 600 MB, and an anonymous GET /intents answered 540 MB."""
    bounds = IntentSettings(max_intent_bytes=8192, buffer_bytes=65_536)
    live = live_factory(scene_settings(token="pub-token", intents=bounds))
    auth = {"authorization": "Bearer pub-token"}

    def say(text: str, response: str = "") -> httpx.Response:
        intent = {"intent": "__intent_say__", "data": {"object": text}, "source": "person_alice"}
        return live.client.post("/intents", headers=auth, json={"intent": intent, "response": response})

    for text, response in (("x" * 900_000, ""), ("x" * 8192, ""), ("hi", "é" * 5000)):  # é: 2 bytes
        refused = say(text, response)
        assert (refused.status_code, refused.json()["code"]) == (413, "intent_too_large"), refused.text
        assert "the limit is 8192 bytes" in refused.json()["message"]
    first = live.services.bus.last_seq + 1
    for n in range(100):  # about 4 KB each: 400 KB in all, six times the buffer
        assert say(f"{n:03d} " + "y" * 4000).status_code == 200
    answer = live.client.get("/intents")  # anonymous: reads are open
    kept = answer.json()["intents"]
    assert 10 <= len(kept) <= 16 and len(answer.content) <= 65_536 + 4096
    assert kept[-1]["intent"]["data"]["object"].startswith("099 ")  # the newest, the oldest dropped
    assert answer.json()["gap"]["last"] == kept[0]["seq"] - 1  # what was dropped is said to be missing
    missed = live.client.get("/intents", params={"after": first - 1}).json()
    assert missed["gap"] == {"first": first, "last": kept[0]["seq"] - 1, "restarted": False}


def test_the_intent_bounds_have_defaults() -> None:
    bounds = IntentSettings()
    assert bounds.max_intent_bytes == 65_536 and bounds.buffer_bytes == 8 * 1024 * 1024
