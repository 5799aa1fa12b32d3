from collections.abc import Sequence

from dialogue.reference import clarify
from dialogue.reference.grounding import Entity, Snapshot, build_snapshot
from kb import KB
from tests.dialogue.conftest import english, scene_kb


def question(snapshot: Snapshot, candidates: Sequence[Entity], noun: str | None = None) -> str:
    """The clarifying question, in English."""
    return clarify.question(english(), snapshot, candidates, noun)


def test_labels_distinguish(cups: KB) -> None:
    snap = build_snapshot(cups)
    q = question(snap, [snap.entities["cup_red"], snap.entities["cup_blue"]])
    assert q == "Which cup do you mean: the red cup or the blue cup?"


def test_colour_distinguishes(cups: KB) -> None:
    snap = build_snapshot(cups)
    q = question(snap, [snap.entities["phone_a"], snap.entities["phone_b"]])
    assert q == "Which phone do you mean: the black one or the white one?"


def test_support_distinguishes() -> None:
    snap = build_snapshot(
        scene_kb("kitchen", "cup_2 rdf:type dbr:Cup", "cup_2 isOn shelf_1", "myself sees cup_2")
    )
    q = question(snap, [snap.entities["cup_1"], snap.entities["cup_2"]])
    assert q == "Which cup do you mean: the one on the table or the one on the shelf?"


def test_ids_when_nothing_distinguishes() -> None:
    snap = build_snapshot(
        scene_kb("kitchen", "cup_2 rdf:type dbr:Cup", "cup_2 isOn table_1", "myself sees cup_2")
    )
    q = question(snap, [snap.entities["cup_1"], snap.entities["cup_2"]])
    assert "(cup_1)" in q and "(cup_2)" in q and q.endswith("?")
