"""RemoteKB, the read replica over a SPARQL store (issue 9): what the conformance tables of
test_kb / test_describe / test_events (run against it too) do not show. The same answers as the
writer's KB (several models, lookup by CURIE fragments, SPARQL passthrough), reads that see the
writer at once, max_rows, blank nodes, hostile literals, the number of requests each read costs,
an unreachable or closed store. Writes: test_writetarget.py; polling: test_remoteevents.py."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager
from pathlib import Path
from typing import Any

import pytest
from rdflib import Graph

from kb import KbError
from kb.errors import StoreUnavailable, TooManyRows
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.remote import RemoteKB
from tests.conftest import Replica

Replicas = Callable[..., AbstractContextManager[Replica]]

WORLD = [
    "myself sees cup_abcd", "myself sees book_1", "cup_abcd rdf:type dbr:Cup", "book_1 rdf:type dbr:Book",
    'book_1 rdfs:label "the red book"', "person_x rdf:type Human", "person_x sees sofa", "person_x sees cup_abcd",
    "alfred rdf:type Human", "alfred age 42", 'nono rdfs:label "alfred"',
    'sentence rdfs:label "alfred is a charming person"', 'j1 rdfs:label "Johnny"@en', 'j1 rdfs:label "Jean"@fr',
    "robby rdf:type Robot", 'robby hasName "Zebulon"', "cup_abcd isOn table_1", "a1 leftOf a2", "a2 leftOf a3",
    "Mug rdfs:subClassOf dbr:Cup", "mug_1 rdf:type Mug", "<http://example.org/x#y> likes dbr:Table_(furniture)",
]
BOB = ["r2 rdf:type Robot", "r2 sees cup_abcd", "r2 sees ball_9", 'ball_9 rdfs:label "ball"']


@pytest.fixture(scope="module")
def pair(replicas: Replicas) -> Iterator[Replica]:
    with replicas() as replica:
        replica.writer.update(WORLD)
        replica.writer.update(BOB, models=["bob"])
        yield replica


# --- the same answers as the writer's KB ------------------------------------------------------

CALLS: dict[str, Callable[[Any], Any]] = {
    "find": lambda k: k["myself sees ?o"],
    "find join": lambda k: k[["?h sees ?o", "?o rdf:type dbr:Cup", "?h rdf:type Human"]],
    "find inferred": lambda k: k["a3 rightOf ?x"],
    "find vars": lambda k: k.find(["?a sees ?o"], vars=["?a"]),
    "find anonymous": lambda k: k["* sees *"],
    "find all models": lambda k: k.find("?x sees cup_abcd", models=["all"]),
    "find bob": lambda k: k.find("?x rdf:type Agent", models=["bob"]),
    "ground": lambda k: k["person_x rdf:type Agent"],
    "exist": lambda k: (k.exist("r2 sees ?x"), k.exist("r2 sees ?x", ["bob"])),
    "details instance": lambda k: k.details("cup_abcd", origin=True),
    "details class": lambda k: k.details("dbr:Cup", origin=True),
    "details Human": lambda k: k.details("Human"),
    "details predicate": lambda k: k.details("sees", origin=True),
    "details datatype": lambda k: k.details("age"),
    "details rdf:type": lambda k: k.details("rdf:type"),
    "details literal": lambda k: k.details("42"),
    "details unknown": lambda k: k.details("nobody_at_all"),
    "details full IRI": lambda k: k.details("<http://example.org/x#y>"),
    "details bob": lambda k: k.details("r2", models=["bob"]),
    "lookup": lambda k: k.lookup("alfred"),
    "lookup case": lambda k: k.lookup("ALFRED"),
    "lookup label": lambda k: k.lookup("cup"),
    "lookup literal": lambda k: k.lookup("Zebulon"),
    "lookup number": lambda k: k.lookup("42"),
    "lookup curie dbr:C": lambda k: k.lookup("dbr:C"),
    "lookup curie r:Cu": lambda k: k.lookup("r:Cu"),
    "lookup curie DBR:cup": lambda k: k.lookup("DBR:cup"),
    "lookup curie dbr:": lambda k: k.lookup("dbr:"),
    "lookup parenthesis": lambda k: k.lookup("(furniture)"),
    "lookup full IRI": lambda k: k.lookup("example.org/x#"),
    "lookup all models": lambda k: k.lookup("ball", models=["all"]),
    "lookup short": lambda k: k.lookup("ag"),
    "about": lambda k: k.about("cup_abcd"),
    "about predicate": lambda k: k.about("leftOf"),
    "about words": lambda k: k.about("charming person"),
    "about all models": lambda k: k.about("cup_abcd", models=["all"]),
    "label": lambda k: [k.label("j1", lang) for lang in (None, "fr", "de")],
    "label class": lambda k: k.label("dbr:Cup", "fr"),
    "classesof": lambda k: (k.classesof("mug_1"), k.classesof("mug_1", True)),
    "classesof all models": lambda k: k.classesof("r2", models=["all"]),
    "contains": lambda k: ("alfred" in k, "nobody_at_all" in k, "myself sees *" in k),
    "models": lambda k: k.models(),
    "size": lambda k: (k.size(), k.size(inferred=False), k.size("bob")),
    "is_asserted": lambda k: (k.is_asserted("mug_1 rdf:type Mug"), k.is_asserted("mug_1 rdf:type dbr:Cup")),
    "revision": lambda k: k.revision,
    "sparql select": lambda k: k.sparql("SELECT ?x WHERE { ?x oro:sees :cup_abcd } ORDER BY ?x"),
    "sparql ask": lambda k: k.sparql("ASK { oro:myself :sees oro:book_1 }"),
    # JSON-LD lists a graph's triples in no particular order: compare the graphs.
    "sparql construct": lambda k: _graph(k.sparql("CONSTRUCT { ?x oro:sees ?y } WHERE { ?x oro:sees ?y }")),
    "sparql own prefix": lambda k: k.sparql("PREFIX oro: <http://example.org/x#> SELECT ?o WHERE { oro:y ?p ?o }"),
    "sparql model": lambda k: k.sparql("SELECT ?x WHERE { ?x a oro:Agent } ORDER BY ?x", "bob"),
    "sparql csv": lambda k: k.sparql_serialize("SELECT ?x ?a WHERE { ?x oro:age ?a }", "csv"),
    "sparql turtle": lambda k: k.sparql_serialize("CONSTRUCT WHERE { ?x oro:leftOf ?y }", "turtle"),
}


def _graph(answer: dict[str, Any]) -> list[str]:
    """A JSON-LD answer in a canonical order."""
    nodes = [{key: sorted(value, key=json.dumps) if isinstance(value, list) else value
              for key, value in node.items()} for node in answer["graph"]]
    return sorted(json.dumps(node, sort_keys=True) for node in nodes)


@pytest.mark.parametrize("call", list(CALLS.values()), ids=list(CALLS))
def test_same_answers_as_the_writer(pair: Replica, call: Callable[[Any], Any]) -> None:
    assert call(pair.reader) == call(pair.writer)


def test_export_and_save_hold_the_writer_triples(pair: Replica, tmp_path: Path) -> None:
    for inferred in (False, True):
        mine, theirs = Graph(), Graph()
        mine.parse(data=pair.reader.export("nt", inferred=inferred), format="nt")
        theirs.parse(data=pair.writer.export("nt", inferred=inferred), format="nt")
        assert len(mine) == len(theirs) == pair.writer.size(inferred=inferred)
        assert {t for t in mine if not _has_bnode(t)} == {t for t in theirs if not _has_bnode(t)}
    files = pair.reader.save(tmp_path, models=["all"])
    assert sorted(Path(f).name for f in files) == ["kb-bob.rdf", "kb-default.rdf"]
    saved = Graph().parse(tmp_path / "kb-bob.rdf", format="xml")
    assert len(saved) == pair.writer.size("bob", inferred=False)


def _has_bnode(triple: Any) -> bool:
    return any(type(t).__name__ == "BNode" for t in triple)


def test_unknown_models_and_one_model_calls(pair: Replica) -> None:
    for kb in (pair.reader, pair.writer):
        with pytest.raises(KbError, match="unknown model 'ghost'; known models: default, bob"):
            kb.find("?x sees ?y", models=["ghost"])
        with pytest.raises(KbError, match="exactly one model"):
            kb.details("r2", models=["all"])


def test_reads_see_the_writer_at_once_and_the_revision_follows(replicas: Replicas) -> None:
    with replicas() as replica:
        writer, reader = replica.writer, replica.reader
        assert reader.revision == writer.revision
        for i in range(5):
            writer.add(f"myself sees thing_{i}")  # straight to the writer, not through the reader
            assert reader.find("myself sees ?x") == writer.find("myself sees ?x")
            assert reader.revision == writer.revision
        writer.remove("myself sees ?x")
        assert reader["myself sees ?x"] == []
        writer.clear()
        assert reader.revision == writer.revision and reader.models() == ["default"]


def test_models_come_default_first_then_by_name(replicas: Replicas) -> None:
    with replicas() as replica:
        for name in ("zed", "alice"):
            replica.writer.add("x sees y", models=[name])
        assert replica.writer.models() == ["default", "zed", "alice"]  # creation order
        assert replica.reader.models() == ["default", "alice", "zed"]  # the store keeps none


# --- max_rows, blank nodes -------------------------------------------------------------------

GHOSTS = """@prefix : <http://kb.openrobots.org#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
[] :sees :ghostcup ; rdfs:label "ghost" . [] :sees :ghostcup . :ghostcup :isIn [ rdfs:label "ghostroom" ] .
:p1 :sees :ghostcup . :p2 :sees :ghostcup .
"""


def test_max_rows_counts_the_rows_kb_counts(replicas: Replicas) -> None:
    with replicas() as replica:
        replica.writer.load_data(GHOSTS)  # two blank-node rows for ?x: dropped, not counted
        for kb in (replica.reader, replica.writer):
            assert kb.find("?x sees ghostcup", max_rows=2) == [{"x": "p1"}, {"x": "p2"}]
            with pytest.raises(TooManyRows):
                kb.find("?x sees ghostcup", max_rows=1)
        replica.writer.add("p3 sees ghostcup", models=["bob"])
        with pytest.raises(TooManyRows):  # the union over models counts
            replica.reader.find("?x sees ghostcup", models=["all"], max_rows=2)


def test_blank_nodes_never_leak_and_come_back_from_sparql(replicas: Replicas) -> None:
    with replicas() as replica:
        replica.writer.load_data(GHOSTS)
        reader, writer = replica.reader, replica.writer
        assert reader.lookup("ghost") == writer.lookup("ghost") == [["ghostcup", "instance"]]
        assert reader.about("ghostcup") == writer.about("ghostcup")
        assert reader.details("ghostcup") == writer.details("ghostcup")
        assert reader["ghostcup isIn ?r"] == []
        query = "SELECT ?x WHERE { ?x oro:sees oro:ghostcup }"
        found = reader.sparql(query)["results"]["bindings"]
        assert sorted(b["x"]["type"] for b in found) == ["bnode", "bnode", "uri", "uri"]
        # The same blank node ids; not the same order (ORDER BY sorts blank nodes first, but the
        # store holds them as skolem IRIs).
        assert sorted(found, key=json.dumps) == sorted(writer.sparql(query)["results"]["bindings"], key=json.dumps)


# --- hostile text ----------------------------------------------------------------------------

HOSTILE = [
    '"a \\"quoted\\" word"',
    '"back\\\\slash"',
    '"""two\nlines"""',
    '"} ; DROP ALL ; INSERT DATA { <urn:x> <urn:y> <urn:z> } #"',
    '"> <urn:evil> . #"',
    '"\\\\\\" } >"',
    '"tab\tand\rreturn"',
    '"it\'s"@en-GB',
]


@pytest.mark.parametrize("literal", HOSTILE)
def test_hostile_literals_round_trip_and_inject_nothing(pair: Replica, literal: str) -> None:
    reader, writer = pair.reader, pair.writer
    reader += f"note_1 says {literal}"
    size = writer.size()
    found = reader[f"?x says {literal}"]
    assert found == writer[f"?x says {literal}"] == [{"x": "note_1"}]
    value = reader["note_1 says ?v"]
    assert value == writer["note_1 says ?v"] and len(value) == 1
    text = value[0]["v"]
    assert reader.lookup(text) == writer.lookup(text)
    assert reader.about(text) == writer.about(text)
    assert reader.details(literal) == writer.details(literal)
    assert reader.exist(f"note_1 says {literal}")
    reader -= f"note_1 says {literal}"
    assert reader["note_1 says ?v"] == []
    assert reader.size() == writer.size() == size - 1  # nothing else changed, nothing added
    assert not reader.sparql("ASK { <urn:x> ?p ?o }")["boolean"]


def test_sparql_is_checked_like_in_process(pair: Replica) -> None:
    for query, message in [
        ("DELETE WHERE { ?s ?p ?o }", "only read-only queries"),
        ("SELECT * FROM <urn:situated:other> WHERE { ?s ?p ?o }", "FROM and FROM NAMED"),
        ("SELECT * WHERE { GRAPH ?g { ?s ?p ?o } }", "GRAPH is not supported"),
        ("SELECT * WHERE { SERVICE <http://example.org/sparql> { ?s ?p ?o } }", "SERVICE"),
        ("SELECT ?x WHERE { ?x nope:p ?y }", "invalid SPARQL"),
    ]:
        with pytest.raises(KbError, match=message):
            pair.reader.sparql(query)


# --- the store ------------------------------------------------------------------------------


class CountingEndpoint(SparqlEndpoint):
    def __init__(self, spec: str) -> None:
        super().__init__(spec)
        self.requests = 0

    def _send(self, method: str, url: str, **kwargs: Any) -> Any:
        self.requests += 1
        return super()._send(method, url, **kwargs)


@pytest.mark.parametrize(
    ("call", "requests"),
    [
        (lambda k: k["myself sees ?o"], 1),
        (lambda k: k.find(["?h sees ?o", "?o rdf:type dbr:Cup", "?h rdf:type Human"], max_rows=10), 1),
        (lambda k: k.exist("myself sees cup_abcd"), 1),
        (lambda k: k["myself sees cup_abcd"], 1),
        (lambda k: k.find("?x sees ?y", models=["bob"]), 2),  # the model list, then the query
        (lambda k: k.find("?x sees ?y", models=["all"]), 3),
        (lambda k: k.details("cup_abcd"), 1),
        (lambda k: k.details("dbr:Cup", origin=True), 1),
        (lambda k: k.about("cup_abcd", models=["all"]), 2),
        (lambda k: k.label("j1", "fr"), 1),
        (lambda k: k.classesof("cup_abcd"), 1),
        (lambda k: k.lookup("alfred"), 2),
        (lambda k: k.lookup("no such thing anywhere"), 1),
        (lambda k: k.sparql("SELECT * WHERE { ?s oro:sees ?o }"), 1),
    ],
)
def test_requests_per_call(pair: Replica, call: Callable[[Any], Any], requests: int) -> None:
    endpoint = CountingEndpoint(pair.store)
    with RemoteKB(endpoint) as reader:
        call(reader)
    endpoint.close()
    assert endpoint.requests == requests


def test_an_unreachable_store_is_a_kb_error() -> None:
    with RemoteKB("sparql+http://127.0.0.1:9?dataset=x") as reader:
        with pytest.raises(StoreUnavailable, match="cannot be reached"):
            reader["myself sees ?x"]
        with pytest.raises(StoreUnavailable):
            reader.models()


def test_a_closed_replica_says_so(pair: Replica) -> None:
    reader = RemoteKB(pair.store)
    assert reader["myself sees ?o"] == pair.writer["myself sees ?o"]
    reader.close()
    with pytest.raises(StoreUnavailable, match="closed"):
        reader["myself sees ?o"]


def test_the_summary_is_the_writers(pair: Replica) -> None:
    assert pair.reader.summary() == pair.writer.summary()
