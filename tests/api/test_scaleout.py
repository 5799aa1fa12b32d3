"""Two service processes on one Oxigraph store: the writer (reasoner, scene, mirror) and a reader
(answers from the store, forwards writes and the scene to the writer). Writes through either are
read through both; dialogues started on one continue on the other."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

from tests.reliability.server import ServerProcess

TOKEN = "scale-out-token"
AUTH = {"authorization": f"Bearer {TOKEN}"}


@pytest.fixture(scope="module")
def pair(oxigraph: object, tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[httpx.Client, httpx.Client]]:
    store = oxigraph.store("scaleout")  # type: ignore[attr-defined]
    logs = tmp_path_factory.mktemp("scaleout")
    env = {"SITUATED_STORE": store, "SITUATED_TOKEN": TOKEN}
    writer = ServerProcess(["--scene", "demo"], logs / "writer.log", env=env)
    reader: ServerProcess | None = None
    try:
        writer.wait_ready()
        reader = ServerProcess([], logs / "reader.log", env={**env, "SITUATED_WRITER_URL": writer.url})
        reader.wait_ready()
        with httpx.Client(base_url=writer.url, timeout=20) as w, httpx.Client(base_url=reader.url, timeout=20) as r:
            yield w, r
    finally:
        if reader is not None:
            reader.stop()
        writer.stop()


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
    assert reader.delete(f"/dialogues/{dialogue}", headers=AUTH).status_code == 204
    assert writer.post(f"/dialogues/{dialogue}/interactions", headers=AUTH, json=turn).status_code == 404


def test_a_reader_needs_a_writer(oxigraph: object, tmp_path: Path) -> None:
    gone = ServerProcess([], tmp_path / "reader.log", env={
        "SITUATED_STORE": oxigraph.store("scaleout"),  # type: ignore[attr-defined]
        "SITUATED_WRITER_URL": "http://127.0.0.1:9", "SITUATED_TOKEN": TOKEN})
    try:
        gone.wait_ready()
        refused = httpx.post(gone.url + "/kb/revise", headers=AUTH, json={"statements": ["a b c"], "method": "add"})
        assert refused.status_code == 503 and refused.json()["code"] == "writer_unavailable"
        assert "nothing was written" in refused.json()["message"]
        assert httpx.get(gone.url + "/scene").status_code == 503
    finally:
        gone.stop()
