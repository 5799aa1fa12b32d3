"""A store that stalls or loses the answer to an update (issue 19, items 12 and 13).

The stall is real: an Oxigraph process of the test's own, paused with SIGSTOP. A lost answer is
a real update that a transport in front of the real store holds back and delivers later, as a
store that resumes delivers an update the writer gave up on. Either way, a write the writer
refused must not end up in the store, store and writer must agree again without waiting for
another write, and a stalled store must not hold the writer's KB for longer than one timeout.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator

import httpx
import pytest

from bench.oxigraph import OxigraphServer, oxigraph_command
from kb import KB
from kb.errors import OutcomeUnknown, StoreUnavailable
from kb.sparqlstore import text as sparqltext
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.mirror import SparqlMirror
from kb.terms import parse_ground
from tests.kb.sparqlstore.test_mirror import assert_same
from tests.waiting import until

WAIT = 30.0  # generous: the machine is shared


@pytest.fixture
def stallable() -> Iterator[OxigraphServer]:
    """An Oxigraph server of this test's own: pausing it stalls no other test."""
    if oxigraph_command() is None:
        pytest.skip("the `oxigraph` command is not installed (pip install oxigraph; it is in the test extra)")
    with OxigraphServer(in_memory=True) as server:
        yield server


class HoldingTransport(httpx.BaseTransport):
    """The real transport, except that it can hold the next update back (the caller sees a read
    timeout, as when the store stalls) and deliver it to the store later."""

    def __init__(self) -> None:
        self.inner = httpx.HTTPTransport()
        self.hold_next_update = False
        self.held: list[httpx.Request] = []
        self.updates = 0

    def handle_request(self, request: httpx.Request) -> httpx.Response:
        if request.url.path.endswith("/update"):
            self.updates += 1
            if self.hold_next_update:
                self.hold_next_update = False
                request.read()
                self.held.append(request)
                raise httpx.ReadTimeout("held back by the test", request=request)
        return self.inner.handle_request(request)

    def deliver(self) -> None:
        """The store receives what was held back, late."""
        while self.held:
            response = self.inner.handle_request(self.held.pop(0))
            response.read()
            assert response.status_code < 300, response.text

    def close(self) -> None:
        self.inner.close()


def wait_in_sync(mirror: SparqlMirror, why: Callable[[], str], timeout: float = WAIT) -> None:
    deadline = time.monotonic() + timeout
    while mirror.stale:
        assert time.monotonic() < deadline, f"the writer did not reconcile the store: {why()}"
        time.sleep(0.05)


def holds(endpoint: SparqlEndpoint, statement: str) -> bool:
    """Whether the store holds a statement in the default model's asserted graph."""
    graph = sparqltext.term(endpoint.layout.asserted("default"))
    return endpoint.ask(f"ASK {{ GRAPH {graph} {{ {sparqltext.triple(*parse_ground(statement))} }} }}")


@pytest.fixture
def held(store: Callable[[], str]) -> Iterator[tuple[KB, SparqlEndpoint, SparqlMirror, HoldingTransport]]:
    transport = HoldingTransport()
    http = httpx.Client(transport=transport, timeout=5.0)
    endpoint = SparqlEndpoint(store(), http=http)
    kb = KB()
    mirror = SparqlMirror(endpoint)
    mirror.attach(kb)
    yield kb, endpoint, mirror, transport
    mirror.detach()
    kb.close()
    endpoint.close()
    http.close()


def test_a_refused_update_delivered_late_does_not_change_the_store(
        held: tuple[KB, SparqlEndpoint, SparqlMirror, HoldingTransport]) -> None:
    kb, endpoint, mirror, transport = held
    kb += ["myself sees cup_1"]
    transport.hold_next_update = True
    with pytest.raises(StoreUnavailable):
        kb.update(["myself sees apple_1"])
    assert not kb.exist(["myself sees apple_1"])
    until(lambda: kb.update(["myself sees book_1"]) or True, WAIT, ignoring=(StoreUnavailable,))
    transport.deliver()  # the store resumes and gets the update the writer gave up on
    assert not holds(endpoint, "myself sees apple_1"), "a refused write reached the store"
    assert_same(kb, endpoint, mirror)
    kb.update(["myself sees pen_1"])
    assert_same(kb, endpoint, mirror)


def test_a_refused_update_applied_late_is_undone_in_the_store_without_another_write(
        held: tuple[KB, SparqlEndpoint, SparqlMirror, HoldingTransport]) -> None:
    kb, endpoint, mirror, transport = held
    kb += ["myself sees cup_1"]
    transport.hold_next_update = True
    with pytest.raises(StoreUnavailable):
        kb.update(["myself sees apple_1"])
    transport.deliver()  # applied after the writer gave up, before it could reconcile
    wait_in_sync(mirror, lambda: f"the store holds the refused write: {holds(endpoint, 'myself sees apple_1')}")
    assert not holds(endpoint, "myself sees apple_1")
    assert_same(kb, endpoint, mirror)
    kb.update(["myself sees pen_1"])
    assert_same(kb, endpoint, mirror)


def test_while_the_outcome_is_unknown_writes_are_refused_without_touching_the_store(
        stallable: OxigraphServer) -> None:
    transport = HoldingTransport()
    http = httpx.Client(transport=transport)
    endpoint = SparqlEndpoint(stallable.store("doubt"), timeout=1.0, http=http)
    kb = KB()
    mirror = SparqlMirror(endpoint)
    mirror.attach(kb)
    try:
        kb += ["myself sees cup_1"]
        stallable.pause()
        try:
            with pytest.raises(StoreUnavailable):
                kb.update(["myself sees apple_1"])
            sent = transport.updates
            revision = kb.revision
            for n in range(3):
                with pytest.raises(StoreUnavailable):
                    kb.update([f"myself sees pear_{n}"])
            assert transport.updates == sent, "a write was sent to a store whose state is unknown"
            assert kb.revision == revision
            assert kb["myself sees ?x"] == [{"x": "cup_1"}]
            assert mirror.status().refused >= 4
        finally:
            stallable.resume()
        until(lambda: kb.update(["myself sees book_1"]) or True, WAIT, ignoring=(StoreUnavailable,))
        assert_same(kb, endpoint, mirror)
    finally:
        mirror.detach()
        kb.close()
        endpoint.close()
        http.close()


def test_a_write_refused_during_a_stall_is_not_in_the_store_after_it_resumes(
        stallable: OxigraphServer) -> None:
    """The red team's case: the store paused, a write answered 503, the store resumed."""
    url = stallable.store("stall")
    endpoint = SparqlEndpoint(url, timeout=1.0)
    probe = SparqlEndpoint(url, timeout=10.0)
    kb = KB()
    mirror = SparqlMirror(endpoint)
    mirror.attach(kb)
    try:
        kb += ["myself sees cup_1"]
        stallable.pause()
        try:
            with pytest.raises(StoreUnavailable):
                kb.update(["myself sees apple_1"])
        finally:
            stallable.resume()
        assert not kb.exist(["myself sees apple_1"])
        wait_in_sync(mirror, lambda: f"the store holds the refused write: {holds(probe, 'myself sees apple_1')}, "
                                     f"revision {mirror.stored_revision()} (the writer's: {kb.revision})")
        time.sleep(0.5)  # whatever the resumed store still had queued is processed by now
        assert not holds(probe, "myself sees apple_1")
        assert_same(kb, probe, mirror)
        until(lambda: kb.update(["myself sees book_1"]) or True, WAIT, ignoring=(StoreUnavailable,))
        assert_same(kb, probe, mirror)
    finally:
        mirror.detach()
        kb.close()
        endpoint.close()
        probe.close()


def test_reads_do_not_wait_on_a_stalled_store_beyond_one_timeout(stallable: OxigraphServer) -> None:
    """The first write into a stall holds the KB for at most the store timeout; once the writer
    knows the store is stalled, writes are refused at once and reads never wait."""
    endpoint = SparqlEndpoint(stallable.store("reads"), timeout=1.0)
    kb = KB()
    mirror = SparqlMirror(endpoint)
    mirror.attach(kb)
    try:
        kb += ["myself sees cup_1"]
        stallable.pause()
        try:
            started = time.monotonic()
            with pytest.raises(StoreUnavailable):
                kb.update(["myself sees apple_1"])
            assert time.monotonic() - started < 15, "the store timeout was not applied"
            stop = threading.Event()
            refused: list[int] = []

            def keep_writing() -> None:
                while not stop.is_set():
                    try:
                        kb.update(["myself sees pear_1"])
                    except StoreUnavailable:
                        refused.append(1)
                    time.sleep(0.01)

            writer = threading.Thread(target=keep_writing)
            writer.start()
            try:
                started = time.monotonic()
                for _ in range(20):
                    assert kb["myself sees ?x"] == [{"x": "cup_1"}]
                    time.sleep(0.02)
                # 20 reads while writes keep coming: each write into the stall would hold the
                # lock a full timeout (1 s), so 20 reads would take well over 10 s
                assert time.monotonic() - started < 10
            finally:
                stop.set()
                writer.join(WAIT)
            assert refused
        finally:
            stallable.resume()
    finally:
        mirror.detach()
        kb.close()
        endpoint.close()


def test_an_unanswered_update_is_told_apart_from_a_refused_one(stallable: OxigraphServer) -> None:
    """Only an update that was sent and got no answer may still be applied: that one is
    ``OutcomeUnknown``; a store that cannot be reached, or answers a query late, is not."""
    endpoint = SparqlEndpoint(stallable.store("kinds"), timeout=0.5)
    nowhere = SparqlEndpoint("sparql+http://127.0.0.1:9", timeout=0.5)
    try:
        with pytest.raises(StoreUnavailable) as refused:
            nowhere.update("INSERT DATA { <urn:a> <urn:b> <urn:c> }")
        assert not isinstance(refused.value, OutcomeUnknown)
        with pytest.raises(StoreUnavailable) as bad:
            endpoint.update("INSERT DATA { this is not SPARQL }")
        assert not isinstance(bad.value, OutcomeUnknown)  # the store's own refusal of all of it
        stallable.pause()
        try:
            with pytest.raises(OutcomeUnknown, match=r"did not answer within 0\.5 s"):
                endpoint.update("INSERT DATA { <urn:a> <urn:b> <urn:c> }")
            with pytest.raises(StoreUnavailable) as late:
                endpoint.ask("ASK { ?s ?p ?o }")
            assert not isinstance(late.value, OutcomeUnknown)
        finally:
            stallable.resume()
    finally:
        endpoint.close()
        nowhere.close()
