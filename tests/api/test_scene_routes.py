"""The scene routes end to end: the demo scene by default, replace, move, remove, bad input."""

from __future__ import annotations

import math
from collections.abc import Callable
from importlib.resources import files
from pathlib import Path

from api.settings import Settings
from tests.api.conftest import Live


def test_demo_scene_is_loaded_by_default(live_factory: Callable[..., Live]) -> None:
    live = live_factory(Settings())
    seen = live.client.post("/kb/query", json={"patterns": ["myself sees ?o"]}).json()
    assert {"table", "cup", "apple", "person_alice"} <= {row["o"] for row in seen}
    reply = live.client.post("/dialogues/default/interactions",
                             json={"user_id": "person_alice", "input": "what do you see?"}).json()
    assert "cup" in reply["response"] and "apple" in reply["response"]
    scene = live.client.get("/scene").json()
    alice = next(e for e in scene["entities"] if e["id"] == "person_alice")
    assert alice["kind"] == "person" and alice["engagement"] in ("unknown", "disengaged", "engaging", "engaged")
    assert scene["config"]["fov_degrees"] == 120.0


def test_put_move_and_delete_entities_answer_with_the_diff(live_factory: Callable[..., Live]) -> None:
    client = live_factory(Settings(scene=None)).client
    table = {"kind": "furniture", "class": "dbr:Table_(furniture)", "x": 2.0, "y": 0.0, "width": 1.2, "depth": 0.8}
    assert "myself sees table_1" in client.put("/scene/entities/table_1", json=table).json()["added"]
    added = client.put("/scene/entities/cup_1", json={"class": "dbr:Cup", "label": "red cup", "x": 2.0, "y": 0.1}).json()["added"]
    assert {"cup_1 isOn table_1", 'cup_1 rdfs:label "red cup"', "myself sees cup_1"} <= set(added)
    moved = client.put("/scene/entities/cup_1", json={"class": "dbr:Cup", "x": -1.0, "y": 0.0}).json()
    assert {"cup_1 isOn table_1", "myself sees cup_1", 'cup_1 rdfs:label "red cup"'} <= set(moved["removed"])
    assert client.post("/kb/query", json={"patterns": ["cup_1 isOn ?t"]}).json() == []
    person = {"kind": "person", "x": 1.0, "y": 0.0, "heading": math.pi}
    assert "person_bob sees myself" in client.put("/scene/entities/person_bob", json=person).json()["added"]
    gone = client.delete("/scene/entities/person_bob").json()
    assert {"person_bob sees myself", "person_bob rdf:type Human"} <= set(gone["removed"])
    missing = client.delete("/scene/entities/person_bob")
    assert missing.status_code == 404 and missing.json()["code"] == "not_found"


def test_replace_with_svg_and_json(live_factory: Callable[..., Live]) -> None:
    client = live_factory(Settings(scene=None)).client
    svg = (files("ontologies") / "demo.svg").read_bytes()
    diff = client.put("/scene", content=svg, headers={"Content-Type": "image/svg+xml"}).json()
    assert "cup isOn table" in diff["added"]
    json_scene = {"entities": [{"id": "box_1", "kind": "object", "class": "Box", "x": 1.0, "y": 0.0}]}
    diff = client.put("/scene", json=json_scene).json()
    assert "cup isOn table" in diff["removed"] and "myself sees box_1" in diff["added"]
    assert [e["id"] for e in client.get("/scene").json()["entities"]] == ["myself", "box_1"]


def test_bad_scenes_are_clear_errors_and_change_nothing(live_factory: Callable[..., Live]) -> None:
    client = live_factory(Settings(scene=None)).client
    client.put("/scene/entities/cup_1", json={"class": "dbr:Cup", "x": 1.0, "y": 0.0})
    before = client.get("/scene").json()
    bad_svg = client.put("/scene", content=b"<svg><g>", headers={"Content-Type": "image/svg+xml"})
    assert bad_svg.status_code == 400 and "malformed SVG" in bad_svg.json()["message"]
    unknown = client.put("/scene/entities/ship_1", json={"class": "dbr:Spaceship", "x": 1.0, "y": 0.0})
    assert unknown.status_code == 400 and "dbr:Spaceship" in unknown.json()["message"]
    client.post("/kb/revise", json={"statements": ["remote_1 rdf:type Remote"], "method": "add"})
    clash = client.put("/scene/entities/remote_1", json={"class": "Remote", "x": 1.0, "y": 0.0})
    assert clash.status_code == 400 and "remote_1" in clash.json()["message"]
    wrong_type = client.put("/scene", content=b"x", headers={"Content-Type": "text/plain"})
    assert wrong_type.status_code == 415
    assert client.put("/scene/entities/x", json={"x": "far"}).status_code == 422
    assert client.get("/scene").json() == before


def test_clear_keeps_the_scene_facts(live_factory: Callable[..., Live]) -> None:
    client = live_factory(Settings()).client
    client.post("/kb/clear", json={})
    assert {"cup", "table"} <= {r["o"] for r in client.post("/kb/query", json={"patterns": ["myself sees ?o"]}).json()}


def test_scene_survives_a_restart_with_a_data_dir(live_factory: Callable[..., Live], tmp_path: Path) -> None:
    settings = Settings(data_dir=tmp_path, scene="demo")
    first = live_factory(settings)
    first.client.put("/scene/entities/cup", json={"class": "dbr:Cup", "x": 1.0, "y": -1.0})
    first.app.state.services.stop()  # as at shutdown (the fixture stops it again, harmlessly)
    second = live_factory(settings)
    rows = second.client.post("/kb/query", json={"patterns": ["cup isOn ?s"]}).json()
    assert rows == []  # moved off the table before the restart, and nothing stale came back
    cup = next(e for e in second.client.get("/scene").json()["entities"] if e["id"] == "cup")
    assert (cup["x"], cup["y"]) == (1.0, -1.0)
