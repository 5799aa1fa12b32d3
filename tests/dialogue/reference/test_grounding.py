from dialogue.reference.grounding import Grounder, build_snapshot, readable_id
from kb import KB
from tests.dialogue.conftest import scene_kb


def test_snapshot_entities_have_readable_names_kinds_and_places(kitchen: KB) -> None:
    snap = build_snapshot(kitchen)
    cup = snap.entities["cup_1"]
    assert cup.kind == "thing" and cup.seen
    assert cup.name == "cup" and cup.class_names[0] == "cup"
    assert (cup.support, cup.zone) == ("table_1", "kitchen")
    assert not any(":" in name for e in snap.entities.values() for name in e.class_names)
    book = snap.entities["book_1"]
    assert book.name == "cookbook" and "book" in book.class_names
    assert "fruit" in snap.entities["apple_1"].class_names
    assert snap.entities["person_alice"].kind == "person"
    assert snap.entities["person_tom"].kind == "person" and not snap.entities["person_tom"].seen
    assert snap.entities["bedroom"].kind == "zone"
    assert snap.entities["myself"].kind == "robot"
    assert "dbr:Cup" not in snap.entities and "Human" not in snap.entities


def test_order_is_deterministic_visible_first() -> None:
    a, b = scene_kb("kitchen"), scene_kb("kitchen")
    ids = list(build_snapshot(a).entities)
    assert ids == list(build_snapshot(b).entities)
    first_unseen = next(i for i, e in enumerate(build_snapshot(a).entities.values()) if not e.seen)
    assert all(not e.seen for e in list(build_snapshot(a).entities.values())[first_unseen:])


def test_colour_property_is_read(cups: KB) -> None:
    snap = build_snapshot(cups)
    assert snap.entities["phone_a"].colour == "black"
    assert snap.entities["phone_b"].colour == "white"


def test_unlabelled_asserted_class_names_its_instances() -> None:
    kb = scene_kb(None, "gizmo_1 rdf:type FluxCapacitor", "myself sees gizmo_1")
    assert "flux capacitor" in build_snapshot(kb).entities["gizmo_1"].class_names


def test_grounder_caches_per_revision(kitchen: KB) -> None:
    grounder = Grounder()
    first = grounder.snapshot(kitchen)
    assert grounder.snapshot(kitchen) is first
    assert grounder.cached(kitchen.revision) is first
    kitchen.update(["pear_1 rdf:type dbr:Pear", "myself sees pear_1"])
    assert grounder.cached(kitchen.revision) is None
    second = grounder.snapshot(kitchen)
    assert second is not first and "pear_1" in second.entities


def test_readable_id() -> None:
    assert readable_id("dbr:Table_(furniture)") == "table"
    assert readable_id("ZoneOfInterest") == "zone of interest"
    assert readable_id("http://example.org/ns#BigBox") == "big box"


def test_incremental_snapshots_equal_full_rebuilds_after_random_changes() -> None:
    import random

    from dialogue.reference.grounding import Grounder, build_snapshot
    from kb import KB

    rng = random.Random(5)
    kb = KB()
    kb.update(["myself rdf:type Robot", "kitchen rdf:type ZoneOfInterest", 'kitchen rdfs:label "kitchen"',
               "hall rdf:type ZoneOfInterest", "table_1 rdf:type dbr:Table_(furniture)", "table_1 isIn kitchen",
               "person_ann rdf:type Human", 'person_ann rdfs:label "Ann"'])
    grounder = Grounder()
    grounder.snapshot(kb)
    things = [f"thing_{i}" for i in range(12)]
    facts = [
        lambda t: f"{t} rdf:type {rng.choice(['dbr:Cup', 'dbr:Book', 'dbr:Apple', 'Remote'])}",
        lambda t: f'{t} rdfs:label "{rng.choice(["red", "blue", "old"])} thing"',
        lambda t: f"{t} isOn table_1",
        lambda t: f"{t} isIn {rng.choice(['kitchen', 'hall'])}",
        lambda t: f"myself sees {t}",
        lambda t: f"{t} hasColor {rng.choice(['red', 'white'])}",
        lambda t: "dbr:Cup rdfs:label \"mug\"@en",
    ]
    for _ in range(60):
        statement = rng.choice(facts)(rng.choice(things))
        if rng.random() < 0.35:
            kb.remove([statement])
        else:
            kb.update([statement])
        incremental = grounder.snapshot(kb)
        assert incremental == build_snapshot(kb)
    grounder.close()
    kb.close()
