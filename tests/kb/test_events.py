"""Subscriptions (kb-compat §3.6, K8, K9): ids, baseline, payloads, one-shot, and events caused by
inference, functional replacement, lifespan expiry and clear.
"""

from __future__ import annotations

import re
import threading
from collections.abc import Iterator
from typing import Any

import pytest

from kb import KB, KbError
from kb.events import event_id
from tests.conftest import VARIANTS, kb_variant
from tests.waiting import until


class Recorder:
    """A subscription callback that records every delivery (one list of rows per call)."""

    def __init__(self) -> None:
        self.calls: list[list[dict[str, Any]]] = []
        self._lock = threading.Lock()

    def __call__(self, rows: list[dict[str, Any]]) -> None:
        with self._lock:
            self.calls.append(rows)

    def take(self) -> list[list[dict[str, Any]]]:
        with self._lock:
            calls, self.calls = self.calls, []
        return calls


class FakeClock:
    def __init__(self) -> None:
        self.now = 1_000_000.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture(params=VARIANTS)
def kb(request: pytest.FixtureRequest) -> Iterator[KB]:
    """The in-process KB, and a RemoteKB reading a mirror of one from a SPARQL store: its
    subscriptions poll the store, and a write made through it returns once they saw it."""
    with kb_variant(request) as k:
        yield k


@pytest.fixture
def clock() -> FakeClock:
    return FakeClock()


@pytest.fixture
def timed_kb(clock: FakeClock) -> Iterator[KB]:
    with KB(clock=clock) as k:
        yield k


# --- ids -------------------------------------------------------------------------------------

ID = re.compile(r"evt_[0-9a-f]{32}")


def test_event_id_format_and_identity() -> None:
    base = event_id(["?a sees ?b", "?b rdf:type dbr:Cup"], False, ["default"])
    assert ID.fullmatch(base)
    assert event_id(["?b rdf:type dbr:Cup", "?a sees ?b"], False, ["default"]) == base  # sorted patterns
    assert event_id(["?a sees ?b", "?b rdf:type dbr:Cup"], True, ["default"]) != base
    assert event_id(["?a sees ?b", "?b rdf:type dbr:Cup"], False, ["bob"]) != base
    assert event_id(["?a sees ?b"], False, ["default"]) != base
    assert event_id(["?x"], False, ["a", "b"]) == event_id(["?x"], False, ["b", "a"])  # sorted models


def test_subscribe_returns_the_id_and_identical_subscriptions_share_it(kb: KB) -> None:
    first, second = Recorder(), Recorder()
    sid = kb.subscribe("?a sees ?b", first)
    assert ID.fullmatch(sid)
    assert kb.subscribe("?a sees ?b", second) == sid
    assert kb.subscribe(["?a sees ?b"], Recorder(), one_shot=True) != sid
    assert kb.subscribe("?a sees ?b", Recorder(), models=["all"]) != sid
    kb += "alfred sees cup"
    assert first.take() == [[{"a": "alfred", "b": "cup"}]]
    assert second.take() == [[{"a": "alfred", "b": "cup"}]]


def test_a_callback_subscribed_twice_to_the_same_patterns_is_called_once_per_trigger(kb: KB) -> None:
    # As knowledge_core's client: the same callback (an equal callable) subscribed again is not
    # added again; another callback of the same subscription is called too, once.
    rec, other = Recorder(), Recorder()
    sid = kb.subscribe("?a sees ?b", rec)
    assert kb.subscribe(["?a sees ?b"], rec) == sid
    kb.subscribe("?a sees ?b", other)
    kb += "alfred sees cup"
    assert rec.take() == [[{"a": "alfred", "b": "cup"}]]
    assert other.take() == [[{"a": "alfred", "b": "cup"}]]


# --- baseline and payloads -------------------------------------------------------------------


def test_baseline_does_not_fire_and_payload_is_only_new_rows(kb: KB) -> None:
    kb += ["alfred sees cup", "bob sees book"]
    rec = Recorder()
    kb.subscribe("?a sees ?b", rec)
    kb += "alfred sees cup"  # already true: no change at all
    kb += "carol likes cup"  # unrelated predicate
    assert rec.take() == []
    kb += ["alfred sees book", "alfred sees cup"]
    assert rec.take() == [[{"a": "alfred", "b": "book"}]]


def test_payload_keys_follow_find(kb: KB) -> None:
    anonymous, mixed = Recorder(), Recorder()
    kb.subscribe("* sees *", anonymous)
    kb.subscribe("?agent sees *", mixed)
    kb += ["alfred sees cup", "alfred sees book"]
    assert anonymous.take() == [[{"var1": "alfred", "var2": "book"}, {"var1": "alfred", "var2": "cup"}]]
    assert mixed.take() == [[{"agent": "alfred"}]]  # distinct after projection (K1)


def test_one_call_per_mutation_with_all_new_rows(kb: KB) -> None:
    rec = Recorder()
    kb.subscribe("?x isIn kitchen", rec)
    kb += ["x1 isIn kitchen", "x2 isIn kitchen", "x3 isIn kitchen", "x3 isIn garden"]
    calls = rec.take()
    assert len(calls) == 1
    assert sorted(r["x"] for r in calls[0]) == ["x1", "x2", "x3"]


def test_reappearing_rows_fire_again(kb: KB) -> None:
    kb += "alfred sees cup"
    rec = Recorder()
    kb.subscribe("alfred sees ?x", rec)
    kb -= "alfred sees cup"
    assert rec.take() == []
    kb += "alfred sees cup"
    assert rec.take() == [[{"x": "cup"}]]


def test_conjunction_fires_when_every_pattern_holds(kb: KB) -> None:
    rec = Recorder()
    kb.subscribe(["?h sees ?o", "?o rdf:type dbr:Cup", "?h rdf:type Human"], rec)
    kb += "person_x sees cup_1"
    kb += "cup_1 rdf:type dbr:Cup"
    assert rec.take() == []
    kb += "person_x rdf:type Human"
    assert rec.take() == [[{"h": "person_x", "o": "cup_1"}]]


def test_ground_subscription_fires_once_when_it_becomes_true(kb: KB) -> None:
    rec = Recorder()
    kb.subscribe("alfred sees cup", rec)
    kb += "alfred sees cup"
    kb += "alfred sees book"
    assert len(rec.take()) == 1


# --- inferred rows ---------------------------------------------------------------------------


def test_inferred_rows_fire(kb: KB) -> None:
    agents, places = Recorder(), Recorder()
    kb.subscribe("?x rdf:type Agent", agents)
    kb.subscribe("?place placeOf ?thing", places)
    kb += "r1 rdf:type Robot"
    kb += "cup isIn kitchen"  # isIn ⊑ isAt, isAt inverse placeOf
    assert agents.take() == [[{"x": "r1"}]]
    assert places.take() == [[{"place": "kitchen", "thing": "cup"}]]
    kb += "r1 rdf:type foaf:Agent"  # r1 was already an Agent: no new row
    assert agents.take() == []


def test_a_row_with_two_supports_fires_once(kb: KB) -> None:
    rec = Recorder()
    kb.subscribe("?x rdf:type EmbodiedAgent", rec)
    kb += ["r2 rdf:type Robot", "r2 rdf:type EmbodiedAgent"]
    assert rec.take() == [[{"x": "r2"}]]


# --- one-shot (K8) ---------------------------------------------------------------------------


def test_one_shot_fires_exactly_once_on_the_first_evaluation_with_new_rows(kb: KB) -> None:
    rec = Recorder()
    sid = kb.subscribe("?x isIn kitchen", rec, one_shot=True)
    kb += "cup isIn bedroom"  # evaluated (same predicate), no new row: must stay subscribed
    kb += "cup2 rdf:type dbr:Cup"
    assert rec.take() == []
    kb += "cup isIn kitchen"
    kb += "pen isIn kitchen"
    kb -= "cup isIn kitchen"
    kb += "cup isIn kitchen"
    assert rec.take() == [[{"x": "cup"}]]
    assert kb.unsubscribe(sid) is False  # already gone


# --- functional replacement and expiry (K9) --------------------------------------------------


def test_functional_replacement_fires_once_per_new_value(kb: KB) -> None:
    kb += "cup hasColor red"
    rec = Recorder()
    kb.subscribe("cup hasColor ?c", rec)
    kb += "cup hasColor blue"
    assert rec.take() == [[{"c": "blue"}]]
    assert kb["cup hasColor ?c"] == [{"c": "blue"}]
    kb += "cup hasColor red"  # red disappeared with the replacement, so it is new again
    assert rec.take() == [[{"c": "red"}]]


def test_expiry_is_seen_by_subscriptions(timed_kb: KB, clock: FakeClock) -> None:
    rec = Recorder()
    timed_kb.subscribe("?x isOn table", rec)
    timed_kb.add("lamp isOn table", lifespan=2)
    assert rec.take() == [[{"x": "lamp"}]]
    clock.now += 3
    timed_kb.expire()
    until(lambda: timed_kb["?x isOn table"] == [])
    assert rec.take() == []  # a row disappearing fires nothing
    timed_kb.add("lamp isOn table", lifespan=2)
    assert rec.take() == [[{"x": "lamp"}]]  # ... but its return does, because expiry re-evaluated


def test_expiry_of_a_supporting_fact_updates_inferred_rows(timed_kb: KB, clock: FakeClock) -> None:
    rec = Recorder()
    timed_kb.subscribe("?place placeOf ?thing", rec)
    timed_kb.add("cup isIn kitchen", lifespan=1)
    assert rec.take() == [[{"place": "kitchen", "thing": "cup"}]]
    clock.now += 2
    timed_kb.expire()
    until(lambda: timed_kb["?place placeOf cup"] == [])
    timed_kb.add("cup isIn kitchen")
    assert rec.take() == [[{"place": "kitchen", "thing": "cup"}]]


# --- models, unsubscribe, clear ---------------------------------------------------------------


def test_subscriptions_honour_models(kb: KB) -> None:
    kb.add("bob_thing likes x", models=["bob"])
    only_bob, everywhere, default = Recorder(), Recorder(), Recorder()
    kb.subscribe("?a likes ?b", only_bob, models=["bob"])
    kb.subscribe("?a likes ?b", everywhere, models=["all"])
    kb.subscribe("?a likes ?b", default)
    kb += "alice likes tea"
    kb.add("bob likes coffee", models=["bob"])
    kb.add("carol likes cake", models=["carol"])
    assert only_bob.take() == [[{"a": "bob", "b": "coffee"}]]
    assert default.take() == [[{"a": "alice", "b": "tea"}]]
    assert everywhere.take() == [
        [{"a": "alice", "b": "tea"}],
        [{"a": "bob", "b": "coffee"}],
        [{"a": "carol", "b": "cake"}],
    ]


def test_unsubscribe(kb: KB) -> None:
    rec = Recorder()
    sid = kb.subscribe("?a sees ?b", rec)
    assert kb.unsubscribe(sid) is True
    assert kb.unsubscribe(sid) is False
    kb += "alfred sees cup"
    assert rec.take() == []


def test_subscriptions_survive_clear_and_fire_again(kb: KB) -> None:
    kb += "alfred sees cup"
    rec = Recorder()
    kb.subscribe("?a sees ?b", rec)
    kb.clear()
    assert rec.take() == []
    kb += "alfred sees cup"
    assert rec.take() == [[{"a": "alfred", "b": "cup"}]]


def test_callbacks_run_after_the_lock_is_released(kb: KB) -> None:
    seen: list[bool] = []
    found: list[Any] = []

    def callback(rows: list[dict[str, Any]]) -> None:
        acquired: list[bool] = []

        def probe() -> None:
            got = kb.lock.acquire(timeout=10.0)
            acquired.append(got)
            if got:
                kb.lock.release()

        thread = threading.Thread(target=probe)
        thread.start()
        thread.join()
        seen.append(acquired == [True])
        found.append(kb["?a sees ?b"])  # callbacks may read the KB

    kb.subscribe("?a sees ?b", callback)
    kb += "alfred sees cup"
    assert seen == [True]
    assert found == [[{"a": "alfred", "b": "cup"}]]


def test_bad_subscriptions_are_kb_errors(kb: KB) -> None:
    with pytest.raises(KbError):
        kb.subscribe([], Recorder())
    with pytest.raises(KbError, match="expected 3 terms"):
        kb.subscribe("?a sees", Recorder())


def test_variable_predicate_subscription(kb: KB) -> None:
    rec = Recorder()
    kb.subscribe("alfred ?p cup", rec)
    kb += "alfred sees cup"
    kb += "alfred likes cup"
    assert rec.take() == [[{"p": "sees"}], [{"p": "likes"}]]


def test_tbox_change_fires_for_newly_inferred_rows(kb: KB) -> None:
    kb += "tom rdf:type Cat"
    rec = Recorder()
    kb.subscribe("?x rdf:type Animal", rec)
    kb += "Cat rdfs:subClassOf Animal"
    assert rec.take() == [[{"x": "tom"}]]


def test_a_failing_callback_does_not_cost_other_subscribers_their_rows(kb: KB) -> None:
    def broken(rows: list[dict[str, Any]]) -> None:
        raise RuntimeError("subscriber bug")

    rec = Recorder()
    kb.subscribe("?x sees ?y", broken)
    kb.subscribe(["?x sees ?y", "?x sees ?y"], rec)  # another id, same rows
    kb += "a1 sees b1"  # the write committed: a subscriber's bug must not surface as a write error
    assert kb.is_asserted("a1 sees b1")
    assert rec.take() == [[{"x": "a1", "y": "b1"}]]  # K9: exactly once per new row, for every subscriber
    kb += "a2 sees b2"
    assert rec.take() == [[{"x": "a2", "y": "b2"}]]


def test_one_write_to_several_models_fires_once_for_all(kb: KB) -> None:
    rec = Recorder()
    kb.subscribe("?a sees ?b", rec, models=["all"])
    kb.add("alfred sees cup", models=["m1", "m2", "default"])
    assert rec.take() == [[{"a": "alfred", "b": "cup"}]]
