"""Lifespans (kb-compat §3.5): expiry bookkeeping, refresh on re-add, permanence on re-add
without a lifespan, and expiry behaving exactly like a retract (re-reasoning and events, K9).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rdflib import URIRef

from kb import KB, KbError
from kb.lifespan import Expiries
from tests.waiting import until

ORO = "http://kb.openrobots.org#"
T1 = (URIRef(ORO + "a"), URIRef(ORO + "p"), URIRef(ORO + "b"))
T2 = (URIRef(ORO + "c"), URIRef(ORO + "p"), URIRef(ORO + "d"))


class FakeClock:
    def __init__(self) -> None:
        self.now = 5_000.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def clock() -> FakeClock:
    return FakeClock()


@pytest.fixture
def kb(clock: FakeClock) -> Iterator[KB]:
    with KB(clock=clock) as k:
        yield k


# --- Expiries --------------------------------------------------------------------------------


def test_expiries_pop_in_time_order() -> None:
    exp = Expiries()
    exp.set("default", T1, 10.0)
    exp.set("bob", T2, 5.0)
    assert len(exp) == 2
    assert exp.next_due() == 5.0
    assert exp.expires_at("default", T1) == 10.0
    assert exp.expires_at("bob", T1) is None
    assert exp.pop_due(4.9) == []
    assert exp.pop_due(5.0) == [("bob", T2)]
    assert exp.pop_due(20.0) == [("default", T1)]
    assert len(exp) == 0
    assert exp.next_due() is None


def test_refresh_replaces_the_old_expiry() -> None:
    exp = Expiries()
    exp.set("default", T1, 10.0)
    exp.set("default", T1, 30.0)
    assert len(exp) == 1
    assert exp.next_due() == 30.0
    assert exp.pop_due(15.0) == []  # the stale heap entry at 10 is ignored
    assert exp.pop_due(30.0) == [("default", T1)]


def test_discard_and_clear() -> None:
    exp = Expiries()
    exp.set("default", T1, 10.0)
    exp.set("default", T2, 12.0)
    exp.discard("default", T1)
    exp.discard("default", T1)
    assert exp.next_due() == 12.0
    assert exp.items() == [("default", T2, 12.0)]
    exp.clear()
    assert len(exp) == 0
    assert exp.pop_due(100.0) == []


# --- through the KB --------------------------------------------------------------------------


def present(kb: KB, stmt: str) -> bool:
    return kb.is_asserted(stmt)


def test_statement_expires_after_its_lifespan(kb: KB, clock: FakeClock) -> None:
    kb.add("cup isOn table", lifespan=10)
    kb += "book isOn table"
    clock.now += 9.9
    kb.expire()
    assert kb["?x isOn table"] == [{"x": "book"}, {"x": "cup"}]
    clock.now += 0.2
    kb.expire()
    assert kb["?x isOn table"] == [{"x": "book"}]


def test_expiry_re_reasons(kb: KB, clock: FakeClock) -> None:
    kb.add("cup isIn kitchen", lifespan=1)
    assert kb["kitchen placeOf ?x"] == [{"x": "cup"}]
    assert kb["cup isAt ?p"] == [{"p": "kitchen"}]
    clock.now += 2
    kb.expire()
    assert kb["kitchen placeOf ?x"] == []
    assert kb["cup isAt ?p"] == []
    assert kb.size(inferred=False) == KB(clock=clock).size(inferred=False)


def test_reads_collect_due_statements(kb: KB, clock: FakeClock) -> None:
    kb.add("cup isOn table", lifespan=1)
    clock.now += 1.5
    assert kb["cup isOn ?t"] == []  # no explicit expire() needed
    assert not kb.exist(["cup isOn table"])


def test_re_adding_with_a_lifespan_refreshes(kb: KB, clock: FakeClock) -> None:
    kb.add("cup isOn table", lifespan=10)
    clock.now += 8
    kb.add("cup isOn table", lifespan=10)
    clock.now += 8  # 16 s after the first add, 8 after the refresh
    kb.expire()
    assert present(kb, "cup isOn table")
    clock.now += 3
    kb.expire()
    assert not present(kb, "cup isOn table")


def test_re_adding_without_a_lifespan_makes_it_permanent(kb: KB, clock: FakeClock) -> None:
    kb.add("cup isOn table", lifespan=5)
    kb += "cup isOn table"
    clock.now += 1000
    kb.expire()
    assert present(kb, "cup isOn table")


def test_lifespan_per_model(kb: KB, clock: FakeClock) -> None:
    kb.add("cup isOn table", lifespan=5, models=["bob"])
    kb += "cup isOn table"
    clock.now += 6
    kb.expire()
    assert kb.find("cup isOn ?t", models=["bob"]) == []
    assert kb.find("cup isOn ?t") == [{"t": "table"}]


def test_retracting_clears_the_lifespan(kb: KB, clock: FakeClock) -> None:
    kb.add("cup isOn table", lifespan=5)
    kb -= "cup isOn table"
    kb += "cup isOn table"
    clock.now += 10
    kb.expire()
    assert present(kb, "cup isOn table")


def test_revise_passes_the_lifespan(kb: KB, clock: FakeClock) -> None:
    kb.revise(["cup isOn table"], {"method": "add", "lifespan": 2})
    clock.now += 3
    kb.expire()
    assert not present(kb, "cup isOn table")


def test_expiry_fires_events_like_a_retract(kb: KB, clock: FakeClock) -> None:
    calls: list[list[dict[str, Any]]] = []
    kb.subscribe("?x isOn table", calls.append)
    kb.add("cup isOn table", lifespan=1)
    clock.now += 2
    kb.expire()
    until(lambda: kb["?x isOn table"] == [])
    kb.add("cup isOn table", lifespan=1)
    assert calls == [[{"x": "cup"}], [{"x": "cup"}]]


def test_background_expiry(clock: FakeClock) -> None:
    with KB(clock=clock) as k:
        k.add("cup isOn table", lifespan=0.5)
        clock.now += 1
        # The expiry thread collects it without any call on the KB.
        until(lambda: not k.is_asserted("cup isOn table"), timeout=30.0)


@pytest.mark.parametrize("bad", [-1, "5", True, None, [1], float("nan")])
def test_invalid_lifespan_is_refused(kb: KB, bad: Any) -> None:
    with pytest.raises(KbError, match="lifespan"):
        kb.add("cup isOn table", lifespan=bad)
    assert not present(kb, "cup isOn table")


def test_clear_forgets_lifespans(kb: KB, clock: FakeClock) -> None:
    kb.add("cup isOn table", lifespan=5)
    kb.clear()
    kb += "cup isOn table"
    clock.now += 10
    kb.expire()
    assert present(kb, "cup isOn table")


def test_expiry_thread_survives_a_failing_listener(clock: FakeClock) -> None:
    def listener(concepts: list[str]) -> None:
        if not concepts:
            raise RuntimeError("listener bug")

    with KB(clock=clock) as k:
        k.on_active_concept(listener)
        k += "cup rdf:type ActiveConcept"
        clock.now += 6
        # The expiry thread retracts the activation and the listener fails in that thread...
        until(lambda: not k.is_asserted("cup rdf:type ActiveConcept"))
        # ... and later lifespans must still be collected in the background.
        k.add("x sees y", lifespan=1)
        clock.now += 2
        until(lambda: not k.is_asserted("x sees y"), timeout=30.0)


def test_replaced_value_takes_its_expiry_with_it(kb: KB, clock: FakeClock) -> None:
    kb.add("cup hasColor red", lifespan=5)
    kb += "cup hasColor blue"  # functional replacement retracts red and its lifespan
    kb += "cup hasColor red"  # red again, now permanent
    clock.now += 10
    kb.expire()
    assert kb["cup hasColor ?c"] == [{"c": "red"}]


# --- hypothesis: lifespans against a model of expiry times -------------------------------------

lifespan_ops = st.lists(
    st.one_of(
        st.tuples(
            st.just("add"),
            st.sampled_from(["s1", "s2"]),
            st.sampled_from(["likes", "hasColor"]),
            st.sampled_from(["o1", "o2"]),
            st.sampled_from([0, 0.5, 1, 2.5, 4]),
        ),
        st.tuples(st.just("remove"), st.sampled_from(["s1", "s2"]), st.sampled_from(["likes", "hasColor"]),
                  st.sampled_from(["o1", "o2"]), st.just(0)),
        st.tuples(st.just("wait"), st.just(""), st.just(""), st.just(""), st.sampled_from([0.5, 1, 2, 3])),
    ),
    max_size=20,
)


@settings(max_examples=60, deadline=None)
@given(lifespan_ops)
def test_random_lifespans_match_a_model(ops: list[tuple[str, str, str, str, float]]) -> None:
    clock = FakeClock()
    expires: dict[tuple[str, str, str], float | None] = {}  # None: permanent
    with KB(ontology=False, clock=clock) as kb:
        kb += "hasColor rdf:type owl:FunctionalProperty"
        for op, s, p, o, value in ops:
            if op == "add":
                kb.add(f"{s} {p} {o}", lifespan=value)
                if p == "hasColor":
                    for t in [t for t in expires if t[0] == s and t[1] == p and t[2] != o]:
                        del expires[t]
                expires[(s, p, o)] = clock.now + value if value else None
            elif op == "remove":
                kb.remove(f"{s} {p} {o}")
                expires.pop((s, p, o), None)
            else:
                clock.now += value
                kb.expire()
                for t, at in list(expires.items()):
                    if at is not None and at <= clock.now:
                        del expires[t]
            found = {(r["s"], r["p"], r["o"]) for r in kb["?s ?p ?o"] if r["p"] in ("likes", "hasColor")}
            assert found == set(expires)
