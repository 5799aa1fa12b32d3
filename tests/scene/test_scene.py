"""Scene → facts: the simulator's sees/isIn/isOn rules, policies, and incremental upkeep."""

from __future__ import annotations

import math
import random

import pytest

from scene.scene import ROBOT_ID, Entity, Kind, Scene, SceneConfig


def scene_with(*entities: Entity, config: SceneConfig | None = None) -> Scene:
    scene = Scene(config)
    for entity in entities:
        scene.put(entity)
    return scene


TABLE = Entity("table_1", Kind.FURNITURE, "dbr:Table_(furniture)", x=2.0, y=0.0, width=1.2, depth=0.8)
KITCHEN = Entity("kitchen", Kind.ZONE, "ZoneOfInterest", x=2.0, y=0.0, width=4.0, depth=4.0)
LIVING = Entity("living_room", Kind.ZONE, "ZoneOfInterest", x=6.0, y=0.0, width=4.0, depth=4.0)


def test_types_labels_and_robot() -> None:
    scene = scene_with(Entity("cup_1", Kind.OBJECT, "dbr:Cup", label="red cup", x=1.0))
    facts = scene.facts()
    assert {"myself rdf:type Robot", "cup_1 rdf:type dbr:Cup", 'cup_1 rdfs:label "red cup"'} <= facts


@pytest.mark.parametrize(
    ("x", "y", "seen"),
    [(3.4, 0.0, True), (3.7, 0.0, False), (1.0, 1.55, True), (1.0, 2.2, False), (-0.5, 0.0, False)],
)
def test_robot_sees_within_sector_and_range(x: float, y: float, seen: bool) -> None:
    scene = scene_with(Entity("cup_1", Kind.OBJECT, "dbr:Cup", x=x, y=y))
    assert ("myself sees cup_1" in scene.facts()) is seen


def test_field_of_view_is_configurable_and_used() -> None:
    cup = Entity("cup_1", Kind.OBJECT, "dbr:Cup", x=1.0, y=2.2)
    assert "myself sees cup_1" not in scene_with(cup).facts()
    assert "myself sees cup_1" in scene_with(cup, config=SceneConfig(fov_degrees=150)).facts()
    far = Entity("cup_2", Kind.OBJECT, "dbr:Cup", x=5.0)
    assert "myself sees cup_2" in scene_with(far, config=SceneConfig(range_m=6)).facts()


def test_people_see_what_they_face_and_the_robot() -> None:
    alice = Entity("person_alice", Kind.PERSON, "Human", x=2.0, y=0.0, heading=math.pi)
    facts = scene_with(alice, TABLE).facts()
    assert "person_alice sees myself" in facts and "myself sees person_alice" in facts
    assert "person_alice sees table_1" in facts  # the table overlaps her position
    turned = Entity("person_alice", Kind.PERSON, "Human", x=3.0, y=0.0, heading=0.0)
    assert "person_alice sees myself" not in scene_with(turned).facts()


def test_is_on_follows_stacking_and_zones_give_is_in() -> None:
    cup = Entity("cup_1", Kind.OBJECT, "dbr:Cup", x=2.0, y=0.1)
    facts = scene_with(KITCHEN, TABLE, cup).facts()
    assert {"cup_1 isOn table_1", "cup_1 isIn kitchen", "table_1 isIn kitchen"} <= facts
    assert "table_1 isOn cup_1" not in facts
    # Placed before the table, the cup is under it (equal z: later is above).
    assert "table_1 isOn cup_1" in scene_with(KITCHEN, cup, TABLE).facts()


def test_stacked_supports_all_by_default_top_as_option() -> None:
    box = Entity("box_1", Kind.OBJECT, "Box", x=2.0, y=0.0, width=0.4, depth=0.4)
    book = Entity("book_1", Kind.OBJECT, "dbr:Book", x=2.0, y=0.0)
    facts = scene_with(TABLE, box, book).facts()
    assert {"book_1 isOn box_1", "book_1 isOn table_1", "box_1 isOn table_1"} <= facts
    top = scene_with(TABLE, box, book, config=SceneConfig(supports="top")).facts()
    assert "book_1 isOn box_1" in top and "book_1 isOn table_1" not in top


def test_item_straddling_two_zones() -> None:
    sofa = Entity("sofa_1", Kind.FURNITURE, "dbr:Couch", x=4.1, y=0.0, width=1.0, depth=0.5)
    both = scene_with(KITCHEN, LIVING, sofa).facts()
    assert {"sofa_1 isIn kitchen", "sofa_1 isIn living_room"} <= both
    largest = scene_with(KITCHEN, LIVING, sofa, config=SceneConfig(zones="largest")).facts()
    assert "sofa_1 isIn living_room" in largest and "sofa_1 isIn kitchen" not in largest


def test_agents_policy() -> None:
    alice = Entity("person_alice", Kind.PERSON, "Human", x=2.0, y=0.0)
    default = scene_with(KITCHEN, TABLE, alice).facts()
    assert "person_alice isIn kitchen" not in default  # as upstream (S7)
    assert "person_alice isOn table_1" in default  # agents are above furniture
    assert "person_alice isIn kitchen" in scene_with(
        KITCHEN, alice, config=SceneConfig(agents_in_zones=True)).facts()


def test_removing_an_observer_retracts_what_it_saw() -> None:
    scene = scene_with(Entity("person_alice", Kind.PERSON, "Human", x=1.0, heading=0.0), TABLE)
    assert "person_alice sees table_1" in scene.facts()
    diff = scene.remove("person_alice")
    assert "person_alice sees table_1" in diff.removed and "myself sees person_alice" in diff.removed
    assert not any("person_alice" in f for f in scene.facts())


def test_the_robot_stays() -> None:
    scene = Scene()
    with pytest.raises(ValueError, match="cannot be removed"):
        scene.remove(ROBOT_ID)


def scratch(scene: Scene) -> set[str]:
    fresh = Scene(scene.config)
    for entity in scene:
        if entity.id != ROBOT_ID:
            fresh.put(entity)
    return fresh.facts()


@pytest.mark.parametrize("seed", range(8))
def test_incremental_facts_equal_recomputation_after_random_changes(seed: int) -> None:
    rng = random.Random(seed)
    config = rng.choice([SceneConfig(), SceneConfig(supports="top", zones="largest", agents_in_zones=True)])
    scene = Scene(config)
    kinds = [Kind.OBJECT, Kind.FURNITURE, Kind.PERSON, Kind.ZONE]
    facts = scene.facts()
    for step in range(120):
        ids = [e.id for e in scene if e.id != ROBOT_ID]
        if ids and rng.random() < 0.25:
            diff = scene.remove(rng.choice(ids))
        else:
            entity_id = rng.choice(ids) if ids and rng.random() < 0.6 else f"e{step}"
            current = scene.get(entity_id)
            kind = current.kind if current else rng.choice(kinds)
            diff = scene.put(Entity(entity_id, kind, x=rng.uniform(-1, 5), y=rng.uniform(-3, 3),
                                    heading=rng.uniform(-math.pi, math.pi), width=rng.uniform(0.1, 2.0)))
        facts = (facts - diff.removed) | diff.added
        assert facts == scene.facts() == scratch(scene)
