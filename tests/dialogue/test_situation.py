from dialogue.reference.grounding import build_snapshot
from dialogue.situation import MAX_CHARS, MAX_LINES, describe
from kb import KB
from tests.dialogue.conftest import scene_kb


def test_description_is_natural_with_ids_in_brackets(kitchen: KB) -> None:
    text = describe(build_snapshot(kitchen), "person_alice").text
    assert text.splitlines()[0] == "Alice [person_alice] is speaking to you."
    lines = text.splitlines()
    # What the robot sees is listed under its zone, the zone said once for all of it.
    seen = lines[lines.index("You see in the kitchen [kitchen]:") + 1:]
    assert "- the cookbook [book_1], a book, on the shelf [shelf_1]" in seen
    assert "- a cup [cup_1], on the table [table_1]" in seen
    assert text.count("[kitchen]") == 2  # the zone's list, and the places
    assert "You know Tom [person_tom], not here now." in text
    assert "dbr:" not in text and "rdf:type" not in text


def test_description_mentions_unseen_known_things() -> None:
    kb = scene_kb(
        "kitchen", "remote_1 rdf:type Remote", 'remote_1 rdfs:label "TV remote"', "remote_1 isIn living_room"
    )
    text = describe(build_snapshot(kb), "person_alice").text
    lines = text.splitlines()
    unseen = lines[lines.index("You know, not seen now:") + 1:]
    assert "- the TV remote [remote_1], a remote, in the living room [living_room]" in unseen


def test_description_says_whose_things_are() -> None:
    kb = scene_kb("kitchen", "cup_1 belongsTo person_tom")
    text = describe(build_snapshot(kb), "person_alice").text
    assert "- a cup [cup_1], on the table [table_1], belongs to Tom [person_tom]" in text.splitlines()


def test_description_is_bounded_and_deterministic() -> None:
    facts = []
    for i in range(150):
        facts += [f"obj_{i:03d} rdf:type dbr:Cup", f"obj_{i:03d} isOn table_1", f"myself sees obj_{i:03d}"]
    kb = scene_kb("kitchen", *facts)
    first = describe(build_snapshot(kb), "person_alice")
    assert len(first.lines) <= MAX_LINES and len(first.text) <= MAX_CHARS + 60
    assert first.truncated > 100
    assert "more things are not listed" in first.text
    assert first == describe(build_snapshot(kb), "person_alice")


def test_unknown_speaker_is_still_named_by_id(kitchen: KB) -> None:
    text = describe(build_snapshot(kitchen), "anonymous_speaker").text
    assert "[anonymous_speaker]" in text.splitlines()[0]


def test_people_engaged_with_the_robot_are_named() -> None:
    kb = scene_kb("kitchen", "person_tom engagementLevel engaged", "person_alice engagementLevel disengaged")
    snapshot = build_snapshot(kb)
    assert snapshot.get("person_tom").engagement == "engaged"  # type: ignore[union-attr]
    text = describe(snapshot, "person_alice").text
    assert "Engaged with you now: Tom [person_tom]." in text
    assert "Alice [person_alice]." not in text.split("Engaged with you now:")[1]


def test_things_seen_in_several_zones_are_listed_under_each() -> None:
    kb = scene_kb("kitchen", "lamp_1 rdf:type Lamp", "lamp_1 isIn living_room", "myself sees lamp_1",
                  "ball_1 rdf:type Ball", "myself sees ball_1")
    lines = describe(build_snapshot(kb), "person_alice").text.splitlines()
    assert lines[lines.index("You see in the living room [living_room]:") + 1] == "- a lamp [lamp_1]"
    assert lines[lines.index("You see:") + 1] == "- a ball [ball_1]"  # where, the KB does not say
