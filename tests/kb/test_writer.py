"""The write path (kb-compat §3.5, K9, K16): functional-property replacement, all-or-nothing batches,
revisions and commit listeners, active concepts, and concurrent readers and writers.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest

from kb import KB, KbError
from kb.writer import Commit


class FakeClock:
    def __init__(self) -> None:
        self.now = 10_000.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def kb() -> Iterator[KB]:
    with KB() as k:
        yield k


# --- functional replacement ------------------------------------------------------------------


@pytest.mark.parametrize(
    ("prop", "old", "new"),
    [
        ("hasColor", "red", "blue"),
        ("hasPosture", "sitting", "standing"),
        ("hasInLeftHand", "cup_1", "book_1"),
        ("hasInRightHand", "cup_1", "book_1"),
        ("hasShape", "boxShape", "sphereShape"),
        ("hasSize", "small", "large"),
        ("isLocated", "here", "there"),
        ("isVisible", "true", "false"),
        ("isPerceived", "false", "true"),
        ("isMoving", "true", "false"),
        ("isHolder", "false", "true"),
        ("isReachable", "true", "false"),
        ("hasCharacteristicDimension", "10", "12"),
        ("preferredName", '"Bob"', '"Bobby"'),
    ],
)
def test_functional_property_value_is_replaced(kb: KB, prop: str, old: str, new: str) -> None:
    subject = "thing_x"
    kb += f"{subject} {prop} {old}"
    kb += f"{subject} {prop} {new}"
    values = [r["v"] for r in kb[f"{subject} {prop} ?v"]]
    assert len(values) == 1
    assert kb.is_asserted(f"{subject} {prop} {new}")
    assert not kb.is_asserted(f"{subject} {prop} {old}")


def test_non_functional_properties_accumulate(kb: KB) -> None:
    kb += "alfred sees cup"
    kb += "alfred sees book"
    assert kb["alfred sees ?x"] == [{"x": "book"}, {"x": "cup"}]


def test_replacement_is_per_subject(kb: KB) -> None:
    kb += ["cup hasColor red", "mug hasColor red"]
    kb += "cup hasColor blue"
    assert kb["?x hasColor red"] == [{"x": "mug"}]
    assert kb["?x hasColor blue"] == [{"x": "cup"}]


def test_within_one_batch_the_last_value_wins(kb: KB) -> None:
    kb += ["cup hasColor red", "cup hasColor green", "cup hasColor blue"]
    assert kb["cup hasColor ?c"] == [{"c": "blue"}]
    assert not kb.is_asserted("cup hasColor red")


def test_replacement_also_drops_the_derived_facts(kb: KB) -> None:
    kb += "cup hasColor red"
    assert kb["cup mainColorOfObject ?c"] == [{"c": "red"}]  # equivalent property
    kb += "cup hasColor blue"
    assert kb["cup mainColorOfObject ?c"] == [{"c": "blue"}]
    assert kb["cup hasFeature ?c"] == [{"c": "blue"}]  # super-property


def test_declared_functional_property_in_the_default_model(kb: KB) -> None:
    kb += "hasMood rdf:type owl:FunctionalProperty"
    kb += "alfred hasMood happy"
    kb += "alfred hasMood sad"
    assert kb["alfred hasMood ?m"] == [{"m": "sad"}]
    kb.add("bob hasMood calm", models=["bob"])
    kb.add("bob hasMood angry", models=["bob"])  # the default model's functional set applies
    assert kb.find("bob hasMood ?m", models=["bob"]) == [{"m": "angry"}]


def test_inferred_functional_property(kb: KB) -> None:
    kb += ["MoodProperty rdfs:subClassOf owl:FunctionalProperty", "hasFeeling rdf:type MoodProperty"]
    assert kb.exist(["hasFeeling rdf:type owl:FunctionalProperty"])
    kb += "alfred hasFeeling joy"
    kb += "alfred hasFeeling calm"
    assert kb["alfred hasFeeling ?f"] == [{"f": "calm"}]


def test_remove_does_not_replace(kb: KB) -> None:
    kb += "cup hasColor red"
    kb -= "cup hasColor blue"
    assert kb["cup hasColor ?c"] == [{"c": "red"}]


# --- batches ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "bad",
    ["bad", "x foo:p y", "x p ?y", 'x p "open', '"lit" p y', "x p *", "x p y z"],
)
def test_a_bad_statement_writes_nothing(kb: KB, bad: str) -> None:
    before = (kb.revision, kb.size(inferred=False), kb.size())
    with pytest.raises(KbError):
        kb.add(["good1 sees cup", "good2 hasColor red", bad, "good3 sees cup"])
    with pytest.raises(KbError):
        kb.add(["good1 sees cup", bad], models=["fresh_model"])
    with pytest.raises(KbError):
        kb -= ["good1 sees cup", bad] if "?" not in bad and "*" not in bad else ["good1 sees cup", "bad"]
    assert (kb.revision, kb.size(inferred=False), kb.size()) == before
    assert kb["?x sees cup"] == []
    assert "fresh_model" not in kb.models()


def test_revision_moves_once_per_commit(kb: KB) -> None:
    start = kb.revision
    kb += ["a1 sees b", "a2 sees b", "a3 sees b"]
    assert kb.revision == start + 1
    kb += "a1 sees b"  # nothing changes
    kb -= "nobody sees b"
    assert kb.revision == start + 1
    kb -= ["a1 sees b", "a2 sees b"]
    assert kb.revision == start + 2


def test_commit_listener_sees_each_commit(kb: KB) -> None:
    commits: list[Commit] = []
    kb.on_commit(commits.append)
    kb += "alfred sees cup"
    kb.add("alfred sees cup", models=["bob"])
    assert [c.revision for c in commits] == [kb.revision - 1, kb.revision]
    first = commits[0]
    assert [d.model for d in first.deltas] == ["default"]
    assert len(first.deltas[0].asserted_added) == 1
    assert len(first.deltas[0].added) > 1  # the fact and what it implies
    assert [d.model for d in commits[1].deltas] == ["bob"]


def test_write_to_several_models_is_one_commit(kb: KB) -> None:
    start = kb.revision
    kb.add("alfred sees cup", models=["m1", "m2"])
    assert kb.revision == start + 1
    assert kb.find("alfred sees ?x", models=["m1"]) == [{"x": "cup"}]
    assert kb.find("alfred sees ?x", models=["m2"]) == [{"x": "cup"}]
    assert kb.find("alfred sees ?x") == []


# --- active concepts -------------------------------------------------------------------------


def test_active_concepts_are_published_and_expire_after_5_seconds() -> None:
    clock = FakeClock()
    with KB(clock=clock) as k:
        published: list[list[str]] = []
        k.on_active_concept(published.append)
        k += "cup_1 rdf:type ActiveConcept"
        k += "book_1 rdf:type ActiveConcept"
        assert published == [["cup_1"], ["book_1", "cup_1"]]
        clock.now += 4.9
        k.expire()
        assert k["?c rdf:type ActiveConcept"] == [{"c": "book_1"}, {"c": "cup_1"}]
        clock.now += 0.2
        k.expire()
        assert k["?c rdf:type ActiveConcept"] == []
        assert published[-1] == []


# --- concurrency -----------------------------------------------------------------------------


def test_readers_never_see_half_a_batch(kb: KB) -> None:
    batch = [f"box_{i} isIn storeroom" for i in range(10)]
    stop = threading.Event()
    errors: list[BaseException] = []
    seen: set[int] = set()

    def writer() -> None:
        try:
            for _ in range(60):
                kb.update(batch)
                kb.remove(batch)
        except BaseException as exc:  # noqa: BLE001 - reported to the main thread
            errors.append(exc)
        finally:
            stop.set()

    def reader() -> None:
        try:
            while not stop.is_set():
                asserted = len(kb["?b isIn storeroom"])
                inferred = len(kb["storeroom placeOf ?b"])  # derived in the same batch
                seen.update((asserted, inferred))
                with kb.lock:  # several answers from one state
                    assert len(kb["?b isIn storeroom"]) == len(kb["?b isAt storeroom"])
        except BaseException as exc:  # noqa: BLE001 - reported to the main thread
            errors.append(exc)

    def other_writer() -> None:
        try:
            i = 0
            while not stop.is_set():
                kb.add(f"other_{i % 5} sees thing_{i % 7}", models=["default", "bob"])
                kb.remove(f"other_{(i + 2) % 5} sees thing_{(i + 3) % 7}")
                i += 1
        except BaseException as exc:  # noqa: BLE001 - reported to the main thread
            errors.append(exc)

    threads = [threading.Thread(target=writer), threading.Thread(target=other_writer)]
    threads += [threading.Thread(target=reader) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=30)
    assert not errors, errors
    assert seen <= {0, 10}
    assert kb["?b isIn storeroom"] == []


def test_concurrent_subscribers_get_every_row_once(kb: KB) -> None:
    got: list[Any] = []
    lock = threading.Lock()

    def record(rows: list[dict[str, Any]]) -> None:
        with lock:
            got.extend(r["x"] for r in rows)

    kb.subscribe("?x isIn hall", record)

    def add(start: int) -> None:
        for i in range(start, start + 25):
            kb.update(f"item_{i} isIn hall")

    threads = [threading.Thread(target=add, args=(n * 25,)) for n in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=30)
    assert sorted(got) == sorted(f"item_{i}" for i in range(100))
