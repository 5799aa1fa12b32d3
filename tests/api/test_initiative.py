"""Engagement in the scene -> the robot engages with the person and greets them, on the stream."""

from __future__ import annotations

import math
from typing import Any

from api.settings import MemorySettings, Settings
from scene.settings import SceneSettings
from tests.api.conftest import Live

FACING = {"kind": "person", "x": 1.0, "y": 0.0, "heading": math.pi}  # in front of the robot, facing it
AWAY = {"kind": "person", "x": 1.0, "y": 0.0, "heading": 0.0}  # turned away


def scene_service(live_factory: Any, **memory: Any) -> Live:
    # No background ticks: the test drives the engagement state machine tick by tick.
    settings = Settings(scene="none", scene_settings=SceneSettings(engagement_hz=0),
                        memory=MemorySettings(**memory))
    live: Live = live_factory(settings)
    return live


def put(live: Live, person: str, body: dict[str, Any]) -> None:
    response = live.client.put(f"/scene/entities/{person}", json=body)
    assert response.status_code == 200, response.text


def tick(live: Live, times: int) -> None:
    for _ in range(times):
        live.services.world.tick()


def pushed(live: Live) -> list[tuple[str, str, str]]:
    live.services.initiative.join()  # every engagement so far reached out to
    intents = live.client.get("/intents", params={"origin": "initiative"}).json()["intents"]
    return [(p["intent"]["intent"], p["intent"]["data"]["recipient"], p["response"]) for p in intents]


def test_a_person_engaging_in_the_scene_is_engaged_with_and_greeted(live_factory: Any) -> None:
    live = scene_service(live_factory)
    put(live, "person_bob", {**FACING, "label": "Bob"})
    put(live, "person_anon", {**AWAY, "y": 1.0})
    tick(live, 40)  # 50 samples before a first level (hri_engagement's timings)...
    assert pushed(live) == []
    tick(live, 20)  # ...then disengaged, engaging and engaged, one a tick: for Bob only
    assert live.client.post("/kb/query", json={"patterns": ["person_bob engagementLevel ?l"]}).json() == [
        {"l": "engaged"}]
    assert pushed(live) == [("__intent_engage_with__", "person_bob", ""),
                            ("__intent_greet__", "person_bob", "Hello Bob!")]
    stream = live.client.get("/intents", params={"after": 0}).json()["intents"]
    assert {(p["origin"], p["dialogue_id"], p["intent"]["source"]) for p in stream} == {
        ("initiative", None, "__myself__")}


def test_a_person_who_comes_back_is_greeted_again_only_after_the_interval(live_factory: Any) -> None:
    live = scene_service(live_factory, greet_interval=3600)
    put(live, "person_x", FACING)  # never met: no name
    tick(live, 120)
    assert pushed(live) == [("__intent_engage_with__", "person_x", ""), ("__intent_greet__", "person_x", "Hello!")]
    assert live.client.delete("/scene/entities/person_x").status_code == 200  # leaves...
    tick(live, 5)
    put(live, "person_x", FACING)  # ...and comes back within the interval
    tick(live, 120)
    assert [i for i, _, _ in pushed(live)] == ["__intent_engage_with__", "__intent_greet__",
                                               "__intent_engage_with__"]


def test_engagement_facts_from_any_producer_count_and_greeting_can_be_off(live_factory: Any) -> None:
    live = scene_service(live_factory, greet=False)
    revise = live.client.post("/kb/revise", json={"statements": ["person_eve rdf:type Human",
                                                                  "person_eve engagementLevel engaged"],
                                                   "method": "update"})
    assert revise.status_code == 200, revise.text
    assert pushed(live) == [("__intent_engage_with__", "person_eve", "")]


def test_greeted_again_after_the_interval(live_factory: Any) -> None:
    live = scene_service(live_factory, greet_interval=0)
    for level in ("engaged", "disengaging", "engaged"):
        live.client.post("/kb/revise", json={"statements": [f"person_bob engagementLevel {level}"],
                                             "method": "update"})
    assert [i for i, _, _ in pushed(live)] == ["__intent_engage_with__", "__intent_greet__"] * 2
