"""Service processes on one Oxigraph store: the writer (reasoner, scene, mirror) and readers
(answer from the store, forward writes and the scene to the writer). Writes through either are
read through both; dialogues started on one continue on the other; the intent stream is one for
the deployment, and what a person tells any process is learnt into the shared KB."""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from tests.api.test_intents import sse
from tests.reliability.server import ServerProcess

TOKEN = "scale-out-token"
AUTH = {"authorization": f"Bearer {TOKEN}"}


@pytest.fixture(scope="module")
def trio(oxigraph: object, tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[httpx.Client, ...]]:
    """The writer and two readers."""
    store = oxigraph.store("scaleout")  # type: ignore[attr-defined]
    logs = tmp_path_factory.mktemp("scaleout")
    env = {"SITUATED_STORE": store, "SITUATED_TOKEN": TOKEN}
    writer = ServerProcess(["--scene", "demo"], logs / "writer.log", env=env)
    readers: list[ServerProcess] = []
    try:
        writer.wait_ready()
        for n in range(2):
            readers.append(ServerProcess([], logs / f"reader{n}.log", env={**env, "SITUATED_WRITER_URL": writer.url}))
        for reader in readers:
            reader.wait_ready()
        clients = [httpx.Client(base_url=p.url, timeout=20) for p in (writer, *readers)]
        try:
            yield tuple(clients)
        finally:
            for client in clients:
                client.close()
    finally:
        for reader in readers:
            reader.stop()
        writer.stop()


@pytest.fixture(scope="module")
def pair(trio: tuple[httpx.Client, ...]) -> tuple[httpx.Client, httpx.Client]:
    return trio[0], trio[1]


def query(client: httpx.Client, *patterns: str) -> list[dict[str, object]]:
    response = client.post("/kb/query", json={"patterns": list(patterns)})
    assert response.status_code == 200, response.text
    rows: list[dict[str, object]] = response.json()
    return rows


def test_roles_are_reported(pair: tuple[httpx.Client, httpx.Client]) -> None:
    writer, reader = pair
    assert writer.get("/health").json()["kb"]["role"] == "writer"
    health = reader.get("/health").json()
    assert health["status"] == "ok" and health["kb"]["role"] == "reader"
    assert health["kb"]["revision"] == writer.get("/health").json()["kb"]["revision"]


def test_a_write_through_either_is_read_through_both(pair: tuple[httpx.Client, httpx.Client]) -> None:
    writer, reader = pair
    done = writer.post("/kb/revise", headers=AUTH, json={"statements": ["myself sees mug_w", "mug_w rdf:type dbr:Mug"],
                                                         "method": "add"})
    assert done.status_code == 200
    assert reader.get("/health").json()["kb"]["revision"] == done.json()["revision"]
    assert query(reader, "myself sees mug_w") == ["myself sees mug_w"]
    done = reader.post("/kb/revise", headers=AUTH, json={"statements": ["mug_r rdf:type dbr:Mug", "mug_r isOn table"],
                                                         "method": "add"})
    assert done.status_code == 200, done.text
    for client in (writer, reader):
        assert {"x": "mug_r"} in query(client, "?x isOn table")
        assert client.get("/kb/details/mug_r").json()["type"] == "instance"
    # the reasoner runs in the writer; its inferences are read through the reader too
    assert reader.get("/kb/classesof/table").json() == writer.get("/kb/classesof/table").json()
    assert query(reader, "?s ?p mug_r") == query(writer, "?s ?p mug_r")
    assert query(reader, "mug_r rdf:type ?c") == query(writer, "mug_r rdf:type ?c")
    # a retraction through the reader reports what the writer removed
    gone = reader.post("/kb/revise", headers=AUTH, json={"statements": ["?m rdf:type dbr:Mug"], "method": "retract"})
    assert gone.status_code == 200, gone.text
    assert gone.json()["removed"] == 2
    assert query(writer, "?m rdf:type dbr:Mug") == []


def test_the_writers_refusals_come_back_through_the_reader(pair: tuple[httpx.Client, httpx.Client]) -> None:
    writer, reader = pair
    unauthorised = reader.post("/kb/revise", json={"statements": ["a b c"], "method": "add"})
    assert unauthorised.status_code == 401
    bad = reader.post("/kb/revise", headers=AUTH, json={"statements": ["only two"], "method": "add"})
    assert bad.status_code == 400 and bad.json()["code"] == "kb_error"
    assert bad.json()["message"] == writer.post("/kb/revise", headers=AUTH, json={
        "statements": ["only two"], "method": "add"}).json()["message"]


def test_the_scene_is_the_writers_and_reached_through_the_reader(pair: tuple[httpx.Client, httpx.Client]) -> None:
    writer, reader = pair
    moved = reader.put("/scene/entities/box_9", headers=AUTH,
                       json={"kind": "object", "class": "dbr:Book", "label": "box", "x": 1.0, "y": 0.0})
    assert moved.status_code == 200, moved.text
    assert "myself sees box_9" in moved.json()["added"]
    assert {e["id"] for e in reader.get("/scene").json()["entities"]} == \
        {e["id"] for e in writer.get("/scene").json()["entities"]}
    assert query(reader, "myself sees box_9") == ["myself sees box_9"]
    assert reader.delete("/scene/entities/box_9", headers=AUTH).status_code == 200
    assert query(reader, "myself sees box_9") == []


def test_events_on_the_reader_see_writes_made_on_the_writer(pair: tuple[httpx.Client, httpx.Client]) -> None:
    writer, reader = pair
    with reader.stream("GET", "/kb/events", params={"pattern": "?x isOn shelf"}, timeout=20) as events:
        assert events.status_code == 200
        lines = events.iter_lines()
        # The write comes after the subscription is registered (its "subscribed" event), not after
        # a pause that a busy machine may outlast.
        assert next(line for line in lines if line.startswith("event:")) == "event: subscribed"
        writer.post("/kb/revise", headers=AUTH, json={"statements": ["vase_1 isOn shelf"], "method": "add"})
        payloads = (json.loads(line[len("data:"):]) for line in lines if line.startswith("data:"))
        rows = next(p for p in payloads if isinstance(p, list))  # after the "subscribed" event
        assert {"x": "vase_1"} in rows


def test_a_dialogue_continues_across_processes(pair: tuple[httpx.Client, httpx.Client]) -> None:
    writer, reader = pair
    # two cups in view: "the cup" needs a clarification, asked by one process, answered through the other
    writer.post("/kb/revise", headers=AUTH, json={"method": "add", "statements": [
        "myself sees cup_red", "cup_red rdf:type dbr:Cup", 'cup_red rdfs:label "red cup"',
        "myself sees cup_blue", "cup_blue rdf:type dbr:Cup", 'cup_blue rdfs:label "blue cup"']})
    dialogue = writer.post("/dialogues", headers=AUTH, json={}).json()["dialogue_id"]
    turn = {"user_id": "person_alice", "input": "pick up the cup"}
    asked = reader.post(f"/dialogues/{dialogue}/interactions", headers=AUTH, json=turn)
    assert asked.status_code == 200, asked.text
    assert asked.json()["response"].endswith("?") and asked.json()["intents"] == []
    answered = writer.post(f"/dialogues/{dialogue}/interactions", headers=AUTH,
                           json={"user_id": "person_alice", "input": "the red one"}).json()
    assert [i["data"].get("object") for i in answered["intents"]] == ["cup_red"]
    assert reader.delete(f"/dialogues/{dialogue}", headers=AUTH).status_code == 200
    assert writer.post(f"/dialogues/{dialogue}/interactions", headers=AUTH, json=turn).status_code == 404


def test_a_reader_needs_a_writer(oxigraph: object, tmp_path: Path) -> None:
    gone = ServerProcess([], tmp_path / "reader.log", env={
        "SITUATED_STORE": oxigraph.store("scaleout"),  # type: ignore[attr-defined]
        "SITUATED_WRITER_URL": "http://127.0.0.1:9", "SITUATED_TOKEN": TOKEN,
        "SITUATED_INTENTS__WEBHOOK_RETRIES": "1", "SITUATED_INTENTS__WEBHOOK_BACKOFF": "0.05"})
    try:
        gone.wait_ready()
        refused = httpx.post(gone.url + "/kb/revise", headers=AUTH, json={"statements": ["a b c"], "method": "add"})
        assert refused.status_code == 503 and refused.json()["code"] == "writer_unavailable"
        assert "nothing was written" in refused.json()["message"]
        assert httpx.get(gone.url + "/scene").status_code == 503
        assert httpx.get(gone.url + "/intents/stream").status_code == 503
        url = "ws" + gone.url[len("http"):]
        with connect(f"{url}/intents/ws") as ws:
            assert json.loads(ws.recv(timeout=30))["code"] == "writer_unavailable"
            with pytest.raises(ConnectionClosed) as closed:
                ws.recv(timeout=30)
            assert closed.value.rcvd is not None and closed.value.rcvd.code == 1013
        # A turn is answered; its intent cannot reach the writer's stream, and /health says so.
        with httpx.Client(base_url=gone.url, timeout=20) as client:
            assert say(client, "default", "hello")["intents"][0]["intent"] == "__intent_greet__"
            health = wait_for(lambda: (h := client.get("/health", headers=AUTH).json())["intents"]["relay"]
                              ["given_up"] and h)
        relay = health["components"]["intent_relay"]
        assert health["status"] == "degraded" and not relay["ok"] and relay["code"] == "intent_relay_failing"
        assert "writer" in relay["reason"] and "1 given up" in relay["reason"]
    finally:
        gone.stop()


# --- one intent stream for the deployment --------------------------------------------------------


def say(client: httpx.Client, dialogue: str, text: str, user: str = "person_alice") -> dict[str, Any]:
    answer = client.post(f"/dialogues/{dialogue}/interactions", headers=AUTH, json={"user_id": user, "input": text})
    assert answer.status_code == 200, answer.text
    body: dict[str, Any] = answer.json()
    return body


def wait_for(find: Callable[[], Any], timeout: float = 30.0) -> Any:
    """What `find` returns once it is truthy (generous: a busy machine)."""
    deadline = time.monotonic() + timeout
    while not (found := find()):
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.05)
    return found


def buffered(client: httpx.Client, **params: Any) -> dict[str, Any]:
    answer = client.get("/intents", params=params)
    assert answer.status_code == 200, answer.text
    body: dict[str, Any] = answer.json()
    return body


def test_a_turn_answered_by_a_reader_is_on_every_processs_stream_with_one_numbering(
        trio: tuple[httpx.Client, ...]) -> None:
    writer, reader, other = trio
    dialogue = writer.post("/dialogues", headers=AUTH, json={}).json()["dialogue_id"]
    mine = {"dialogue_id": dialogue}
    with reader.stream("GET", "/intents/stream", params=mine, timeout=60) as on_reader, \
            writer.stream("GET", "/intents/stream", params=mine, timeout=60) as on_writer:
        assert on_reader.status_code == 200 and on_reader.headers["content-type"].startswith("text/event-stream")
        from_reader, from_writer = sse(on_reader.iter_lines()), sse(on_writer.iter_lines())
        hello = [next(from_reader), next(from_writer)]
        assert [h[0] for h in hello] == ["hello", "hello"]
        assert hello[0][2]["stream"] == hello[1][2]["stream"]  # one bus: the writer's
        start = hello[0][2]["last_seq"]
        greeted = say(reader, dialogue, "hello")  # answered by the reader...
        moved = say(other, dialogue, "go to the kitchen")  # ...then by the other reader
        said = [next(from_reader)[2], next(from_reader)[2]]
        assert said == [next(from_writer)[2], next(from_writer)[2]]  # the same events, the same numbers
        assert [p["intent"] for p in said] == [greeted["intents"][0], moved["intents"][0]]
        assert [(p["origin"], p["dialogue_id"], p["response"]) for p in said] == [
            ("dialogue", dialogue, greeted["response"]), ("dialogue", dialogue, moved["response"])]
        assert start < said[0]["seq"] < said[1]["seq"]
    # Replay after a reconnect, through any process: the buffer, SSE's Last-Event-ID, the WebSocket.
    for client in trio:
        assert buffered(client, after=start, **mine)["intents"] == said
        with client.stream("GET", "/intents/stream", params=mine, headers={"Last-Event-ID": str(said[0]["seq"])},
                           timeout=60) as again:
            events = sse(again.iter_lines())
            assert next(events)[2]["gap"] is None
            assert next(events)[2] == said[1]
    url = "ws" + str(other.base_url)[len("http"):].rstrip("/")
    with connect(f"{url}/intents/ws?after={start}&dialogue_id={dialogue}") as ws:
        assert json.loads(ws.recv(timeout=30))["stream"] == hello[0][2]["stream"]
        assert [json.loads(ws.recv(timeout=30)) for _ in said] == [{"event": "intent", **p} for p in said]
        third = say(writer, dialogue, "hello")  # live, after the replay
        assert json.loads(ws.recv(timeout=30))["intent"] == third["intents"][0]
    # A client that goes ends what a reader followed for it on the writer.
    wait_for(lambda: writer.get("/health", headers=AUTH).json()["intents"]["readers"] == 0)


def test_the_writers_initiative_is_on_a_readers_stream(trio: tuple[httpx.Client, ...]) -> None:
    writer, reader, _ = trio
    start = buffered(reader)["last_seq"]
    url = "ws" + str(reader.base_url)[len("http"):].rstrip("/")
    with connect(f"{url}/intents/ws?origin=initiative&after={start}") as ws:
        assert json.loads(ws.recv(timeout=30))["event"] == "hello"
        done = reader.post("/kb/revise", headers=AUTH, json={"method": "add", "statements": [
            "person_quinn rdf:type Human", 'person_quinn rdfs:label "Quinn"', "person_quinn engagementLevel engaged"]})
        assert done.status_code == 200, done.text
        reached: list[tuple[str, str]] = []
        while len(reached) < 2:  # the demo scene's people may engage meanwhile: Quinn's only
            event = json.loads(ws.recv(timeout=30))
            if event["intent"]["data"].get("recipient") == "person_quinn":
                reached.append((event["intent"]["intent"], event["response"]))
    assert reached == [("__intent_engage_with__", ""), ("__intent_greet__", "Hello Quinn!")]
    initiative = buffered(writer, origin="initiative", after=start)["intents"]
    assert buffered(reader, origin="initiative", after=start)["intents"] == initiative


def test_a_bad_request_to_a_readers_stream_is_the_writers_answer(pair: tuple[httpx.Client, httpx.Client]) -> None:
    writer, reader = pair
    url = "ws" + str(reader.base_url)[len("http"):].rstrip("/")
    with connect(f"{url}/intents/ws?origin=radio") as ws:
        error = json.loads(ws.recv(timeout=30))
        assert error["code"] == "invalid_request" and "unknown origin" in error["message"]
        with pytest.raises(ConnectionClosed) as closed:
            ws.recv(timeout=30)
        assert closed.value.rcvd is not None and (closed.value.rcvd.code, closed.value.rcvd.reason) == (
            1008, "invalid_request")
    assert reader.get("/intents", params={"origin": "radio"}).json() == writer.get(
        "/intents", params={"origin": "radio"}).json()
    assert reader.post("/intents", json={"intent": {}}).status_code == 401  # publishing is a write


# --- what a person tells any process --------------------------------------------------------------


def test_what_a_person_tells_a_reader_is_learnt_into_the_shared_kb(trio: tuple[httpx.Client, ...]) -> None:
    writer, reader, other = trio
    writer.post("/kb/revise", headers=AUTH, json={"method": "add", "statements": [
        "person_zoe rdf:type Human", "myself sees person_zoe",
        "umbrella_1 rdf:type Artifact", 'umbrella_1 rdfs:label "umbrella"', "myself sees umbrella_1"]})
    dialogues = [c.post("/dialogues", headers=AUTH, json={}).json()["dialogue_id"] for c in trio]
    assert say(reader, dialogues[1], "Hi, I'm Zoe", "person_zoe")["response"] == "Hello! Nice to meet you, Zoe."
    assert say(reader, dialogues[1], "the umbrella is mine", "person_zoe")["response"] == "OK, the umbrella is yours."
    # Learnt into the writer's KB: the belief in Zoe's model, the robot's adoption with its record.
    for client in trio:
        assert query(client, 'person_zoe rdfs:label "Zoe"') == ['person_zoe rdfs:label "Zoe"']
        assert client.post("/kb/query", json={"patterns": ["umbrella_1 belongsTo ?p"],
                                              "models": ["person_zoe"]}).json() == [{"p": "person_zoe"}]
        assert query(client, "?r toldBy person_zoe", "?r rdf:subject umbrella_1") != []
    # Answered by the writer and by the other reader.
    assert say(writer, dialogues[0], "whose umbrella is this?", "person_zoe")["response"] == "The umbrella is yours."
    assert say(other, dialogues[2], "what's my name?", "person_zoe")["response"] == "Your name is Zoe."
    memories = [c.get("/people/person_zoe/memory").json() for c in trio]
    assert memories[0] == memories[1] == memories[2]
    memory = memories[0]
    assert memory["last_spoke"] is not None and 'said "the umbrella is mine"' in memory["summary"]
    assert {(t["subject"], t["predicate"], t["object"], t["by"]) for t in memory["told"]} == {
        ("person_zoe", "rdfs:label", "Zoe", "person_zoe"), ("umbrella_1", "belongsTo", "person_zoe", "person_zoe")}
