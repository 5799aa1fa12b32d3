"""The writer's mirror of a KB in a SPARQL store: one update per commit, exact graphs, no half
writes when the store fails, a full rewrite after a failure, recovery from the store."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Iterator

import pytest
from rdflib import Literal, Variable

from kb import KB
from kb.errors import OutcomeUnknown, StoreUnavailable
from kb.sparqlstore import text as sparqltext
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.mirror import SparqlMirror
from kb.terms import Triple


class CountingEndpoint(SparqlEndpoint):
    """A real endpoint that counts updates and can be told to fail the next ones."""

    def __init__(self, spec: str) -> None:
        super().__init__(spec)
        self.updates = 0
        self.refuse = 0  # fail before sending
        self.lose_answer = 0  # send, then fail as if the answer was lost

    def update(self, update: str, timeout: float | None = None) -> None:
        if self.refuse:
            self.refuse -= 1
            raise StoreUnavailable("the SPARQL store at test cannot be reached: refused by the test")
        super().update(update, timeout)
        self.updates += 1
        if self.lose_answer:
            self.lose_answer -= 1
            raise OutcomeUnknown("the SPARQL store at test answered nothing: lost by the test")


@pytest.fixture
def mirrored(store: Callable[[], str]) -> Iterator[tuple[KB, CountingEndpoint, SparqlMirror]]:
    endpoint = CountingEndpoint(store())
    kb = KB()
    mirror = SparqlMirror(endpoint)
    mirror.attach(kb)
    yield kb, endpoint, mirror
    mirror.detach()
    kb.close()
    endpoint.close()


def graph(endpoint: SparqlEndpoint, name: object) -> set[Triple]:
    s, p, o = Variable("s"), Variable("p"), Variable("o")
    rows = endpoint.select(f"SELECT ?s ?p ?o WHERE {{ GRAPH {sparqltext.term(name)} "  # type: ignore[arg-type]
                           f"{{ {sparqltext.triple(s, p, o)} }} }}")
    return {(r["s"], r["p"], r["o"]) for r in rows}


def assert_same(kb: KB, endpoint: SparqlEndpoint, mirror: SparqlMirror) -> None:
    assert sorted(mirror.stored_models()) == sorted(kb.models())
    assert mirror.stored_revision() == kb.revision
    for name in kb.models():
        model = kb.writer.models.get(name)
        assert model is not None
        asserted, inferred = endpoint.layout.graphs(name)
        assert values(graph(endpoint, asserted)) == values(model.asserted)
        assert values(graph(endpoint, inferred)) == values(t for t in model.closure if t not in model.asserted)


def values(triples: Iterable[Triple]) -> set[tuple[object, ...]]:
    """Triples compared by value: the store writes typed literals in canonical form ("1.50" -> 1.5)."""
    return {tuple(term.toPython() if isinstance(term, Literal) else term for term in t) for t in triples}


def test_attach_writes_the_whole_kb(mirrored: tuple[KB, CountingEndpoint, SparqlMirror]) -> None:
    kb, endpoint, mirror = mirrored
    assert_same(kb, endpoint, mirror)


def test_every_commit_is_one_update_and_the_store_follows(
        mirrored: tuple[KB, CountingEndpoint, SparqlMirror]) -> None:
    kb, endpoint, mirror = mirrored
    steps: list[Callable[[], object]] = [
        lambda: kb.update(["myself sees cup_1", "cup_1 rdf:type dbr:Cup", "cup_1 isOn table_1",
                           'cup_1 rdfs:label "the \\"red\\" cup }>"']),
        lambda: kb.update(["cup_1 isOn shelf_1"]),  # functional: replaces table_1
        lambda: kb.remove(["myself sees ?x"]),
        lambda: kb.update(["person_bob sees cup_1"], models=["person_bob"]),  # a new model
        lambda: kb.update(["Mug rdfs:subClassOf dbr:Cup", "mug_2 rdf:type Mug"]),  # the TBox changes
        lambda: kb.apply(add=["myself sees mug_2"], remove=["cup_1 isOn shelf_1"]),
    ]
    for step in steps:
        before = endpoint.updates
        step()
        assert endpoint.updates == before + 1
        assert_same(kb, endpoint, mirror)
    kb.clear()
    assert_same(kb, endpoint, mirror)


def test_a_refused_update_leaves_nothing_half_written(
        mirrored: tuple[KB, CountingEndpoint, SparqlMirror]) -> None:
    kb, endpoint, mirror = mirrored
    kb += ["myself sees cup_1", "cup_1 rdf:type dbr:Cup"]
    revision = kb.revision
    endpoint.refuse = 1
    with pytest.raises(StoreUnavailable):
        kb.update(["myself sees apple_1", "cup_1 isOn table_1"], models=["person_new"])
    assert kb.revision == revision
    assert kb.models() == ["default"]
    assert not kb.exist(["cup_1 isOn table_1"])
    kb.update(["myself sees book_1"])  # the store is back: it is rewritten whole, then follows
    assert_same(kb, endpoint, mirror)
    assert kb["myself sees ?x"] == [{"x": "book_1"}, {"x": "cup_1"}]


def test_an_update_whose_answer_is_lost_is_undone_and_rewritten(
        mirrored: tuple[KB, CountingEndpoint, SparqlMirror]) -> None:
    kb, endpoint, mirror = mirrored
    endpoint.lose_answer = 1
    with pytest.raises(StoreUnavailable):
        kb.update(["myself sees cup_1"], lifespan=60)
    assert not kb.exist(["myself sees cup_1"]) and not kb.writer.expiries.items()
    assert mirror.stale and not mirror.status().in_sync
    deadline = time.monotonic() + 30
    while mirror.stale:  # the mirror reconciles in the background: the store applied it, so rewrite
        assert time.monotonic() < deadline, mirror.status()
        time.sleep(0.02)
    assert_same(kb, endpoint, mirror)
    kb.update(["myself sees apple_1"])
    assert not mirror.stale
    assert_same(kb, endpoint, mirror)


def test_a_new_writer_recovers_the_asserted_state_from_the_store(
        mirrored: tuple[KB, CountingEndpoint, SparqlMirror]) -> None:
    kb, endpoint, _ = mirrored
    kb += ["myself sees cup_1", "cup_1 rdf:type dbr:Cup"]
    kb.update(["person_bob sees cup_1"], models=["person_bob"])
    with KB() as again:
        again_mirror = SparqlMirror(endpoint)
        assert again_mirror.recover(again) == kb.revision
        for name in kb.models():
            assert again.size(name, inferred=False) == kb.size(name, inferred=False)
            assert again.size(name) == kb.size(name)
        assert again["?x sees cup_1"] == kb["?x sees cup_1"]
        assert again.classesof("cup_1") == kb.classesof("cup_1")
