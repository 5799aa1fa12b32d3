"""The write path (kb-compat §3.5, K9, K16): functional-property replacement, all-or-nothing batches,
revisions and commit listeners, active concepts, and concurrent readers and writers.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

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
    assert (kb.revision, kb.size(inferred=False), kb.size()) == before
    assert kb["?x sees cup"] == []
    assert "fresh_model" not in kb.models()


@pytest.mark.parametrize("bad", ["bad", "x foo:p y", 'x p "open', '"lit" p y', "x p y z", "?x zz:p ?y"])
def test_a_bad_statement_retracts_nothing(kb: KB, bad: str) -> None:
    kb += ["good1 sees cup", "good2 sees cup"]
    revision = kb.revision
    with pytest.raises(KbError):
        kb.remove(["good1 sees cup", bad])
    with pytest.raises(KbError):
        kb.remove(["?x sees cup", bad])
    assert kb.revision == revision
    assert kb["?x sees cup"] == [{"x": "good1"}, {"x": "good2"}]


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


def test_an_active_concept_listener_can_be_removed() -> None:
    with KB() as k:
        published: list[list[str]] = []
        stop = k.on_active_concept(published.append)
        k += "cup_1 rdf:type ActiveConcept"
        stop()
        k += "book_1 rdf:type ActiveConcept"
        assert published == [["cup_1"]]


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


# --- hypothesis: the write path against a plain model of the asserted facts --------------------

_SUBJECTS = ["s1", "s2", "s3"]
_OBJECTS = ["o1", "o2", "o3"]
statements = st.tuples(
    st.sampled_from(_SUBJECTS), st.sampled_from(["likes", "hasColor"]), st.sampled_from(_OBJECTS)
)
operations = st.lists(
    st.tuples(st.sampled_from(["add", "remove", "retract_pattern"]), st.lists(statements, min_size=1, max_size=4)),
    min_size=1,
    max_size=12,
)


def _apply(model: set[tuple[str, str, str]], op: str, batch: list[tuple[str, str, str]]) -> None:
    if op == "add":
        for s, p, o in batch:
            if p == "hasColor":
                model -= {t for t in model if t[0] == s and t[1] == p}
            model.add((s, p, o))
    elif op == "remove":
        model -= set(batch)
    else:
        s, p, _ = batch[0]
        model -= {t for t in model if t[0] == s and t[1] == p}


@settings(max_examples=80, deadline=None)
@given(operations)
def test_random_batches_match_a_model_and_fire_exactly_the_new_rows(
    ops: list[tuple[str, list[tuple[str, str, str]]]],
) -> None:
    with KB(ontology=False) as kb:
        kb += "hasColor rdf:type owl:FunctionalProperty"
        fired: list[list[dict[str, Any]]] = []
        kb.subscribe("?s ?p ?o", fired.append)
        model: set[tuple[str, str, str]] = set()
        for op, batch in ops:
            before = set(model)
            texts = [" ".join(t) for t in batch]
            if op == "add":
                kb.add(texts)
            elif op == "remove":
                kb.remove(texts)
            else:
                kb.remove(f"{batch[0][0]} {batch[0][1]} ?o")
            _apply(model, op, batch)
            rows = {(r["s"], r["p"], r["o"]) for r in kb["?s ?p ?o"] if r["p"] in ("likes", "hasColor")}
            assert rows == model
            new = {t for t in model - before}
            got = [(r["s"], r["p"], r["o"]) for call in fired for r in call if r["p"] in ("likes", "hasColor")]
            fired.clear()
            assert sorted(got) == sorted(new)  # exactly once per new row (K9)
            for s in _SUBJECTS:
                assert len(kb[f"{s} hasColor ?c"]) <= 1


def test_a_batch_with_a_lifespan_expires_as_a_whole_under_concurrent_reads() -> None:
    batch = [f"crate_{i} isIn hangar" for i in range(10)]
    errors: list[BaseException] = []
    seen: set[int] = set()
    stop = threading.Event()

    with KB() as kb:

        def reader() -> None:
            try:
                while not stop.is_set():
                    seen.add(len(kb["?c isIn hangar"]))
            except BaseException as exc:  # noqa: BLE001 - reported to the main thread
                errors.append(exc)

        readers = [threading.Thread(target=reader) for _ in range(2)]
        for t in readers:
            t.start()
        try:
            for _ in range(15):
                kb.add(batch, lifespan=0.01)  # expired by reads and by the expiry thread
                deadline = time.monotonic() + 30.0
                while kb["?c isIn hangar"] and time.monotonic() < deadline:
                    time.sleep(0.002)
        finally:
            stop.set()
            for t in readers:
                t.join(timeout=10)
        assert not errors, errors
        assert seen <= {0, 10}
        assert 0 in seen
        assert kb["?c isIn hangar"] == []


multi_model_ops = st.lists(
    st.tuples(
        st.sampled_from(["add", "remove"]),
        st.sampled_from([["default"], ["bob"], ["default", "bob"]]),
        st.lists(st.tuples(st.sampled_from(_SUBJECTS), st.just("likes"), st.sampled_from(_OBJECTS)),
                 min_size=1, max_size=3),
    ),
    min_size=1,
    max_size=10,
)


@settings(max_examples=40, deadline=None)
@given(multi_model_ops)
def test_all_models_subscription_fires_for_rows_new_to_the_union(
    ops: list[tuple[str, list[str], list[tuple[str, str, str]]]],
) -> None:
    with KB(ontology=False) as kb:
        kb.add("seed likes seed", models=["bob"])
        fired: list[list[dict[str, Any]]] = []
        kb.subscribe("?s likes ?o", fired.append, models=["all"])
        models: dict[str, set[tuple[str, str]]] = {"default": set(), "bob": {("seed", "seed")}}
        for op, targets, batch in ops:
            union_before = models["default"] | models["bob"]
            texts = [" ".join(t) for t in batch]
            if op == "add":
                kb.add(texts, models=targets)
            else:
                kb.remove(texts, models=targets)
            for name in targets:
                pairs = {(s, o) for s, _, o in batch}
                models[name] = models[name] | pairs if op == "add" else models[name] - pairs
            union = models["default"] | models["bob"]
            assert {(r["s"], r["o"]) for r in kb.find("?s likes ?o", models=["all"])} == union
            assert len(kb.find("?s likes ?o", models=["all"])) == len(union)  # distinct (K1)
            got = [(r["s"], r["o"]) for call in fired for r in call]
            fired.clear()
            assert sorted(got) == sorted(union - union_before)


def test_a_listener_that_refuses_a_commit_undoes_it_and_earlier_listeners_see_the_undoing() -> None:
    with KB() as kb:
        kb += ["myself sees cup_1"]
        seen: list[Commit] = []
        kb.on_commit(seen.append)

        def refuse(commit: Commit) -> None:
            raise KbError("refused by the test")

        unregister = kb.on_commit(refuse)
        revision = kb.revision
        with pytest.raises(KbError, match="refused"):
            kb.apply(add=["myself sees apple_1"], remove=["myself sees cup_1"], models=["default", "person_x"],
                     lifespan=30)
        assert kb["myself sees ?x"] == [{"x": "cup_1"}]
        assert kb.models() == ["default"] and not kb.writer.expiries.items()
        # the first listener took revision+1, then got revision+2 putting everything back
        assert [c.revision for c in seen] == [revision + 1, revision + 2] and kb.revision == revision + 2
        undone = {d.model: d for d in seen[1].deltas}
        assert undone["default"].asserted_added and undone["default"].asserted_removed
        unregister()
        kb += ["myself sees apple_1"]
        assert kb["myself sees ?x"] == [{"x": "apple_1"}, {"x": "cup_1"}]


def test_a_refused_batch_of_several_models_changes_none_of_them() -> None:
    """A person's belief and the robot's adoption of it are one batch (dialogue.memory): refused,
    neither stays, and the model the batch would have created does not exist."""
    with KB() as kb:
        kb += ["mug_1 isOn table_1"]
        kb.add("mug_1 isOn shelf_1", models=["person_ann"])
        unregister = kb.on_commit(_refuse, durable=True)  # the journal on a full disk does this
        revision = kb.revision
        with pytest.raises(KbError, match="refused"):
            kb.apply_models({"person_bob": {"add": ["mug_1 belongsTo person_bob"]},
                             "person_ann": {"remove": ["mug_1 isOn shelf_1"]},
                             "default": {"add": ["mug_1 belongsTo person_bob"], "remove": ["mug_1 isOn table_1"]}})
        assert kb.revision == revision and kb.models() == ["default", "person_ann"]
        assert kb["mug_1 isOn ?o"] == [{"o": "table_1"}] and kb["mug_1 belongsTo ?o"] == []
        assert kb.find("mug_1 isOn ?o", models=["person_ann"]) == [{"o": "shelf_1"}]
        unregister()


def _refuse(commit: Commit) -> None:
    raise KbError("refused by the test")


def test_a_durable_listener_refusing_reaches_no_observer_and_consumes_no_revision() -> None:
    with KB() as kb:
        kb += ["myself sees cup_1"]
        seen: list[Commit] = []
        kb.on_commit(seen.append)  # an observer, registered first
        unregister = kb.on_commit(_refuse, durable=True)  # but a durable listener is called before it
        revision = kb.revision
        with pytest.raises(KbError, match="refused"):
            kb += ["myself sees apple_1"]
        assert seen == [] and kb.revision == revision
        assert kb["myself sees ?x"] == [{"x": "cup_1"}]
        unregister()
        kb += ["myself sees apple_1"]
        assert [c.revision for c in seen] == [revision + 1]


def test_a_refused_clear_changes_nothing() -> None:
    with KB() as kb:
        kb += ["myself sees cup_1"]
        kb.update(["alice sees book_1"], models=["alice"], lifespan=600)
        before = (kb.export("nt"), kb.export("nt", model="alice"), kb.models(), kb.writer.expiries.items(),
                  kb.revision, kb.size())
        seen: list[Commit] = []
        kb.on_commit(seen.append)
        unregister = kb.on_commit(_refuse, durable=True)
        for keep_defaults in (True, False):
            with pytest.raises(KbError, match="refused"):
                kb.clear(keep_defaults)
            assert (kb.export("nt"), kb.export("nt", model="alice"), kb.models(), kb.writer.expiries.items(),
                    kb.revision, kb.size()) == before
            assert kb["myself sees ?x"] == [{"x": "cup_1"}] and kb["table_1 placeOf ?x"] == []
        assert seen == []
        unregister()
        kb.clear()
        assert kb["myself sees ?x"] == [] and kb.models() == ["default"] and kb.revision == before[4] + 1


def test_a_clear_refused_after_the_journal_took_it_is_undone_in_the_journal_too(tmp_path: Any) -> None:
    from kb.journal import Journal

    with KB() as kb:
        journal = Journal(tmp_path)
        journal.recover(kb)
        kb += ["myself sees cup_1"]
        kb -= ["rdfs:label rdfs:label ?l"]
        kb.update(["alice sees book_1"], models=["alice"])
        expected = _nt(kb), _nt(kb, "alice"), kb.models()
        kb.on_commit(_refuse, durable=True)  # after the journal: the journal has taken the clear
        with pytest.raises(KbError, match="refused"):
            kb.clear(keep_defaults=False)
        assert (_nt(kb), _nt(kb, "alice"), kb.models()) == expected
        journal.close()
    with KB() as again:
        Journal(tmp_path).recover(again)
        assert (_nt(again), _nt(again, "alice"), again.models()) == expected


def _nt(kb: KB, model: str | None = None) -> set[bytes]:
    return set(kb.export("nt", model=model).splitlines())  # the order of export is not fixed


def test_the_expiry_reaper_survives_refusals_reports_them_and_retries() -> None:
    from kb.errors import StorageFull

    refusing = [True]

    def gate(commit: Commit) -> None:
        if refusing[0]:
            raise StorageFull("the disk of the data directory is full (test)")

    with KB() as kb:
        kb.update(["p sees q"], lifespan=0.2)
        kb.on_commit(gate, durable=True)
        deadline = time.monotonic() + 20
        while kb.writer.expiry_status.get().ok and time.monotonic() < deadline:
            time.sleep(0.02)
        status = kb.writer.expiry_status.get()
        assert status.code == "storage_full" and "full" in status.reason and status.retry_in
        assert kb["p sees ?x"] == [{"x": "q"}]  # not retracted, still due
        refusing[0] = False
        while (kb["p sees ?x"] or not kb.writer.expiry_status.get().ok) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert kb["p sees ?x"] == [] and kb.writer.expiry_status.get().ok
