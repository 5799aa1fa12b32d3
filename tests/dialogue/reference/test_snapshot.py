"""What the snapshot says of one entity: whether it can be picked up and carried."""

import pytest

from dialogue.reference.grounding import build_snapshot
from dialogue.reference.snapshot import fixed
from tests.dialogue.conftest import scene_kb


@pytest.mark.parametrize(
    ("facts", "is_fixed"),
    [
        (["x rdf:type Artifact", "x isMovable false"], True),  # the KB says so
        (["x rdf:type dbr:Couch"], True),  # furniture, the KB saying nothing
        (["x rdf:type dbr:Couch", "x isMovable true"], False),  # furniture the KB says is movable
        (["x rdf:type dbr:Cup"], False),
        (["x rdf:type Artifact", "x isMovable true"], False),
    ],
)
def test_a_thing_is_fixed_when_the_kb_says_it_cannot_move_or_it_is_furniture(
    facts: list[str], is_fixed: bool
) -> None:
    kb = scene_kb(None, "myself rdf:type Robot", *facts, "myself sees x")
    entity = build_snapshot(kb).get("x")
    assert entity is not None and fixed(entity) is is_fixed
    kb.close()


def test_movable_follows_the_kb() -> None:
    kb = scene_kb(None, "myself rdf:type Robot", "x rdf:type Artifact", "myself sees x")
    entity = build_snapshot(kb).get("x")
    assert entity is not None and entity.movable is None
    kb.update(["x isMovable false"])
    entity = build_snapshot(kb).get("x")
    assert entity is not None and entity.movable is False
    kb.close()


def test_the_robots_name_is_its_scene_label_not_the_ontologys_myself() -> None:
    named = build_snapshot(scene_kb(None, "myself rdf:type Robot", 'myself rdfs:label "Pip"'))
    assert named.robot_name("robot") == "Pip"
    # the ontology alone labels it "myself"@en, its id: no name of its own
    assert build_snapshot(scene_kb(None, "myself rdf:type Robot")).robot_name("robot") == "robot"
