import gc
import threading
import time

from dialogue.reference.grounding import Grounder, Snapshot, build_snapshot, readable_id
from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.waiting import until


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
    kb.update(
        [
            "myself rdf:type Robot",
            "kitchen rdf:type ZoneOfInterest",
            'kitchen rdfs:label "kitchen"',
            "hall rdf:type ZoneOfInterest",
            "table_1 rdf:type dbr:Table_(furniture)",
            "table_1 isIn kitchen",
            "person_ann rdf:type Human",
            'person_ann rdfs:label "Ann"',
        ]
    )
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
        lambda t: 'dbr:Cup rdfs:label "mug"@en',
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


def test_a_thing_in_a_container_in_a_zone_shows_both() -> None:
    kb = scene_kb(None, "myself rdf:type Robot", "den rdf:type ZoneOfInterest", 'den rdfs:label "den"',
                  "crate_1 rdf:type Box", 'crate_1 rdfs:label "crate"', "crate_1 isIn den",
                  "yoyo_1 rdf:type Toy", "yoyo_1 isIn crate_1", "yoyo_1 isIn den")  # fmt: skip
    yoyo = build_snapshot(kb).entities["yoyo_1"]
    # the zone is the den (not "crate_1", first by its text); the crate is where in it
    assert yoyo.zone == "den" and ("in", "crate_1") in yoyo.relations
    assert {e.id for e in build_snapshot(kb).placed_at("crate_1")} == {"yoyo_1"}
    kb.close()


def test_incremental_snapshots_follow_containers_and_places_becoming_zones() -> None:
    import random

    rng = random.Random(11)
    kb = KB()
    kb.update(["myself rdf:type Robot", "attic rdf:type ZoneOfInterest", "chest_1 rdf:type Box",
               "chest_1 isIn attic", "myself sees chest_1"])  # fmt: skip
    grounder = Grounder()
    grounder.snapshot(kb)
    things = [f"thing_{i}" for i in range(8)]
    facts = [
        lambda t: f"{t} rdf:type {rng.choice(['dbr:Cup', 'Toy'])}",
        lambda t: f"{t} isIn {rng.choice(['attic', 'chest_1', 'thing_0', 'loft'])}",
        lambda t: f"myself sees {t}",
        lambda t: f"{rng.choice(['loft', 'chest_1'])} rdf:type ZoneOfInterest",
    ]
    for _ in range(80):
        statement = rng.choice(facts)(rng.choice(things))
        if rng.random() < 0.35:
            kb.remove([statement])
        else:
            kb.update([statement])
        assert grounder.snapshot(kb) == build_snapshot(kb)
    grounder.close()
    kb.close()


def test_a_following_grounder_takes_up_each_commit_without_a_turn(kitchen: KB) -> None:
    made: list[Snapshot] = []
    grounder = Grounder(then=made.append)
    grounder.follow(kitchen)  # the first snapshot is built by the worker
    until(lambda: grounder.cached(kitchen.revision) is not None)
    kitchen.update(["pear_1 rdf:type dbr:Pear", "myself sees pear_1"])
    until(lambda: grounder.cached(kitchen.revision) is not None)  # nobody asked for it
    snap = grounder.cached(kitchen.revision)
    assert snap is not None and "pear_1" in snap.entities and snap == build_snapshot(kitchen)
    assert snap.changed  # taken up from the commit, not rebuilt
    assert made[-1] is snap  # what comes with a snapshot (the engine's lexicon) made before it was shown
    grounder.close()
    before = kitchen.revision
    kitchen.update(["person_tom looksAt cup_1"])
    time.sleep(0.05)
    assert kitchen.revision > before
    assert grounder.cached(kitchen.revision) is None  # closed: no longer following


def test_a_long_spell_of_perception_is_taken_up_as_it_comes() -> None:
    kb = scene_kb("kitchen")
    grounder = Grounder()
    builds: list[int] = []
    grounder.follow(kb, built=lambda: builds.append(kb.revision))
    # The first snapshot is a full build, of whatever revision the worker finds when it starts: on
    # loaded cores it once started after the whole spell, and the only snapshot was that build.
    until(lambda: grounder.cached(kb.revision) is not None)
    zones = ["kitchen", "bedroom", "living_room"]
    for n in range(600):  # a minute of perception at 10 Hz, and nobody speaks
        kb.apply(add=[f"cup_1 isIn {zones[n % 3]}", f"person_tom looksAt thing_{n % 7}"],
                 remove=[f"cup_1 isIn {zones[(n - 1) % 3]}", f"person_tom looksAt thing_{(n - 1) % 7}"])
    until(lambda: grounder.cached(kb.revision) is not None)
    snap = grounder.cached(kb.revision)
    assert snap is not None and snap.changed  # followed commit by commit,
    assert len(builds) == 1  # never rebuilt
    assert snap == build_snapshot(kb) and snap.entities["cup_1"].zone == "living_room"
    grounder.close()
    kb.close()


def test_a_following_grounder_says_when_it_built_everything_and_only_then(kitchen: KB) -> None:
    builds: list[int] = []
    grounder = Grounder()
    grounder.follow(kitchen, built=lambda: builds.append(kitchen.revision))
    until(lambda: grounder.cached(kitchen.revision) is not None)
    assert builds == [kitchen.revision]  # the first snapshot
    kitchen.update(["pear_1 rdf:type dbr:Pear", "myself sees pear_1"])
    until(lambda: grounder.cached(kitchen.revision) is not None)
    kitchen.update(['dbr:Pear rdfs:subClassOf dbr:Apple'])  # a TBox change: everything again
    until(lambda: grounder.cached(kitchen.revision) is not None)
    assert len(builds) == 2 and builds[-1] == kitchen.revision
    grounder.close()


def test_a_full_build_is_settled_before_the_collector_runs_again(kitchen: KB) -> None:
    """The service settles (freezes) what a full build made: done while the collector is still
    paused, no collection pass walks it first."""
    collecting: list[bool] = []
    grounder = Grounder()
    assert gc.isenabled()
    grounder.follow(kitchen, built=lambda: collecting.append(gc.isenabled()))
    until(lambda: grounder.cached(kitchen.revision) is not None)
    assert collecting == [False]  # called during the build's pause,
    assert gc.isenabled()  # which ended with it
    grounder.close()


def test_a_snapshot_taken_while_a_commit_is_told_holds_that_commit(kitchen: KB) -> None:
    """The KB moves its revision on before it tells its listeners: a snapshot asked for in between
    (the grounding's worker, a turn) must not be stamped with that revision without its changes,
    or it passes for current until the next commit."""
    grounder = Grounder()
    grounder.follow(kitchen)
    until(lambda: grounder.cached(kitchen.revision))
    taken: list[Snapshot] = []

    def telling(_commit: object) -> None:  # told before the grounder: its changes not queued yet
        asker = threading.Thread(target=lambda: taken.append(grounder.snapshot(kitchen)), daemon=True)
        asker.start()
        asker.join(1)  # a snapshot that does not wait for the commit is taken here

    unwatch = kitchen.on_commit(telling, durable=True)
    kitchen.update(['cup_1 rdfs:label "blue mug"'])
    unwatch()
    until(lambda: taken)
    assert "blue mug" in grounder.snapshot(kitchen).entities["cup_1"].labels
    assert all("blue mug" in snap.entities["cup_1"].labels for snap in taken if snap.revision == kitchen.revision)
    grounder.close()


def test_closing_while_a_commit_is_told_deadlocks_nothing(kitchen: KB) -> None:
    """The KB tells its listeners of a commit under its lock, and the grounder takes its own lock
    then; closing (or watching) must not hold the grounder's lock while it waits for the KB's."""
    telling, closing = threading.Event(), threading.Event()

    def slow_listener(_commit: object) -> None:  # registered first: told before the grounder
        telling.set()
        closing.wait(5)
        time.sleep(0.2)  # the close is now waiting for the KB's lock, which this commit holds

    kitchen.on_commit(slow_listener)
    grounder = Grounder()
    grounder.follow(kitchen)
    until(lambda: grounder.cached(kitchen.revision))
    writer = threading.Thread(target=kitchen.update, args=(["cup_1 isOn shelf_1"],), daemon=True)
    writer.start()
    assert telling.wait(10)
    closer = threading.Thread(target=grounder.close, daemon=True)
    closer.start()
    closing.set()
    writer.join(30)
    closer.join(30)
    assert not writer.is_alive() and not closer.is_alive(), "the commit and the close wait for each other"
