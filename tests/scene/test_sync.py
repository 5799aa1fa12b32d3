"""A scene kept in the KB: one batch per change, nothing stale, bad input changes nothing."""

from __future__ import annotations

import math
import random
from importlib.resources import files

import pytest

from kb import KB, KbError
from scene.scene import Diff, Entity, Kind
from scene.svg import load_svg
from scene.sync import SceneSync, entity_from_json, scene_from_json, scene_to_json

SCENE_PREDICATES = ("sees", "isIn", "isOn", "engagementLevel")


@pytest.fixture
def kb() -> KB:
    with KB() as instance:
        yield instance


def scene_facts_in_kb(kb: KB) -> set[str]:
    facts = set()
    for predicate in SCENE_PREDICATES:
        facts |= {f"{r['s']} {predicate} {r['o']}" for r in kb.find(f"?s {predicate} ?o")}
    return facts


def spatial(facts: set[str]) -> set[str]:
    return {f for f in facts if f.split()[1] in SCENE_PREDICATES}


def test_demo_scene_answers_what_the_robot_sees(kb: KB) -> None:
    sync = SceneSync(kb)
    sync.replace(load_svg((files("ontologies") / "demo.svg").read_bytes()))
    seen = {r["o"] for r in kb["myself sees ?o"]}
    assert {"table", "cup", "apple", "sofa", "person_alice"} <= seen
    assert kb["cup isOn ?s"] == [{"s": "table"}]
    assert kb.details("cup")["attributes"][0]["values"][0]["label"]["default"] == "cup"


def test_each_change_is_one_batch_and_leaves_nothing_stale(kb: KB) -> None:
    sync = SceneSync(kb)
    table = Entity("table_1", Kind.FURNITURE, "dbr:Table_(furniture)", x=2.0, width=1.2, depth=0.8)
    cup = Entity("cup_1", Kind.OBJECT, "dbr:Cup", x=2.0, y=0.1)
    sync.replace([table, cup])
    revision = kb.revision
    diff = sync.put(Entity("cup_1", Kind.OBJECT, "dbr:Cup", x=-1.0, y=0.0))  # off the table, behind
    assert kb.revision == revision + 1
    assert {"cup_1 isOn table_1", "myself sees cup_1"} <= diff.removed
    assert kb["cup_1 isOn ?x"] == [] and kb["myself sees cup_1"] == []
    assert kb["table_1 placeOf ?x"] == []  # the inferred inverse is gone too
    sync.remove("cup_1")
    assert kb["cup_1 ?p ?o"] == []


@pytest.mark.parametrize("seed", range(4))
def test_kb_scene_facts_equal_recomputation_after_random_changes(kb: KB, seed: int) -> None:
    rng = random.Random(seed)
    sync = SceneSync(kb)
    kinds = {Kind.OBJECT: "dbr:Cup", Kind.FURNITURE: "dbr:Table_(furniture)", Kind.PERSON: "Human",
             Kind.ZONE: "ZoneOfInterest"}
    for step in range(60):
        ids = [e.id for e in sync.scene if e.id != "myself"]
        if ids and rng.random() < 0.25:
            sync.remove(rng.choice(ids))
        else:
            entity_id = rng.choice(ids) if ids and rng.random() < 0.6 else f"thing_{step}"
            current = sync.scene.get(entity_id)
            kind = current.kind if current else rng.choice(list(kinds))
            sync.put(Entity(entity_id, kind, kinds[kind], x=rng.uniform(-1, 5), y=rng.uniform(-3, 3),
                            heading=rng.uniform(-math.pi, math.pi), width=rng.uniform(0.1, 2.0)))
        assert scene_facts_in_kb(kb) == spatial(sync.scene.facts())


def test_unknown_class_and_clashing_id_are_refused_and_change_nothing(kb: KB) -> None:
    sync = SceneSync(kb)
    sync.replace([Entity("cup_1", Kind.OBJECT, "dbr:Cup", x=1.0)])
    before, revision = sync.scene.facts(), kb.revision
    with pytest.raises(KbError, match="unknown class 'dbr:Spaceship'"):
        sync.put(Entity("ship_1", Kind.OBJECT, "dbr:Spaceship", x=1.0))
    kb += "remote_1 rdf:type Remote"
    with pytest.raises(KbError, match="already has facts about 'remote_1'"):
        sync.put(Entity("remote_1", Kind.OBJECT, "Remote", x=1.0))
    with pytest.raises(KbError, match="several entities named cup_2"):
        sync.replace([Entity("cup_2", Kind.OBJECT, "dbr:Cup"), Entity("cup_2", Kind.OBJECT, "dbr:Cup")])
    with pytest.raises(KbError, match="robot"):
        sync.put(Entity("myself", Kind.ROBOT))
    assert sync.scene.facts() == before and kb.revision == revision + 1  # only the += above


def test_resync_after_clear(kb: KB) -> None:
    sync = SceneSync(kb)
    sync.replace([Entity("cup_1", Kind.OBJECT, "dbr:Cup", x=1.0)])
    kb.clear()
    assert kb["myself sees ?o"] == []
    sync.resync()
    assert kb["myself sees ?o"] == [{"o": "cup_1"}]


def test_engagement_level_is_stored_and_replaced(kb: KB) -> None:
    sync = SceneSync(kb)
    alice = Entity("person_alice", Kind.PERSON, "Human", x=1.0, y=0.0, heading=math.pi)
    sync.replace([alice])
    engaged_at = None
    for tick in range(1, 140):
        _, transitions = sync.tick()
        if any(t.after.name == "ENGAGED" for t in transitions):
            engaged_at = tick
    assert engaged_at is not None
    assert kb["person_alice engagementLevel ?l"] == [{"l": "engaged"}]
    sync.put(Entity("person_alice", Kind.PERSON, "Human", x=1.0, y=0.0, heading=0.0))  # turns away
    for _ in range(140):
        sync.tick()
    assert kb["person_alice engagementLevel ?l"] == [{"l": "disengaged"}]
    sync.remove("person_alice")
    assert kb["person_alice engagementLevel ?l"] == []


def test_json_round_trip_and_errors(kb: KB) -> None:
    sync = SceneSync(kb)
    sync.replace(scene_from_json({"entities": [
        {"id": "cup_1", "kind": "object", "class": "dbr:Cup", "label": "red cup", "x": 1.0, "y": 0.2}]}))
    data = scene_to_json(sync)
    assert {e["id"] for e in data["entities"]} == {"myself", "cup_1"}
    assert scene_from_json(data)[0].label == "red cup"
    with pytest.raises(KbError, match="unknown fields"):
        entity_from_json({"id": "x", "colour": "red"})
    with pytest.raises(KbError, match="missing field"):
        entity_from_json({"kind": "object"})
    with pytest.raises(KbError, match="malformed JSON"):
        scene_from_json("{")


def test_a_scene_never_put_in_the_kb_brings_nothing_back_after_a_clear(kb: KB) -> None:
    # `--scene none`: the robot's facts were never asserted; a clear must not invent them.
    sync = SceneSync(kb)
    kb.clear(keep_defaults=False)
    assert sync.resync() == Diff()
    assert kb["?s ?p ?o"] == []
