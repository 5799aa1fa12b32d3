"""Read-only SPARQL (kb-compat §3.7): W3C JSON results plus "query", the §1.2 prefixes declared,
one model per call, updates refused, every error a KbError.
"""

from __future__ import annotations

import json
from collections.abc import Iterator

import pytest
from rdflib import Graph, URIRef

from kb import KB, KbError
from kb.index import TripleIndex
from kb.sparql import IndexStore, execute, to_json

ORO = "http://kb.openrobots.org#"


@pytest.fixture(scope="module")
def kb() -> Iterator[KB]:
    with KB() as k:
        k += ["alfred rdf:type Human", "alfred sees cup_1", "cup_1 rdf:type dbr:Cup", "alfred age 42"]
        k.add(["r2 rdf:type Robot", "r2 sees cup_1"], models=["bob"])
        yield k


def test_select_json_shape(kb: KB) -> None:
    query = "SELECT ?x ?a WHERE { ?x oro:sees oro:cup_1 . ?x oro:age ?a }"
    result = kb.sparql(query)
    assert result == {
        "head": {"vars": ["x", "a"]},
        "results": {
            "bindings": [
                {
                    "x": {"type": "uri", "value": ORO + "alfred"},
                    "a": {"type": "literal", "value": "42", "datatype": "http://www.w3.org/2001/XMLSchema#integer"},
                }
            ]
        },
        "query": query,
    }
    json.dumps(result)


def test_ask_json_shape(kb: KB) -> None:
    assert kb.sparql("ASK { oro:alfred oro:sees oro:cup_1 }") == {
        "head": {},
        "boolean": True,
        "query": "ASK { oro:alfred oro:sees oro:cup_1 }",
    }
    assert kb.sparql("ASK { oro:alfred oro:sees oro:nothing }")["boolean"] is False


@pytest.mark.parametrize(
    "query",
    [
        "SELECT ?x WHERE { ?x :sees :cup_1 }",
        "SELECT ?x WHERE { ?x oro:sees oro:cup_1 }",
        "SELECT ?x WHERE { ?x <http://kb.openrobots.org#sees> <http://kb.openrobots.org#cup_1> }",
        "SELECT ?x WHERE { ?x rdf:type foaf:Person . ?x oro:sees ?c . ?c a dbr:Cup }",
        "SELECT ?x WHERE { ?x rdf:type cyc:SolidTangibleThing . ?x :sees ?c }",
        "SELECT ?x WHERE { ?x a ?t . ?t rdfs:subClassOf* foaf:Agent . ?x oro:sees ?c }",
        "SELECT ?x WHERE { ?x oro:sees ?c . FILTER(?c = oro:cup_1) } LIMIT 5",
    ],
)
def test_prefixes_of_section_1_2_are_declared(kb: KB, query: str) -> None:
    result = kb.sparql(query)
    assert {b["x"]["value"] for b in result["results"]["bindings"]} == {ORO + "alfred"}


def test_sparql_sees_inferred_triples(kb: KB) -> None:
    result = kb.sparql("SELECT ?x WHERE { ?x a oro:Agent }")
    found = {b["x"]["value"] for b in result["results"]["bindings"]}
    assert {ORO + "alfred", ORO + "myself"} <= found


def test_sparql_takes_one_model(kb: KB) -> None:
    query = "SELECT ?x WHERE { ?x oro:sees oro:cup_1 }"
    bob = kb.sparql(query, model="bob")
    assert [b["x"]["value"] for b in bob["results"]["bindings"]] == [ORO + "r2"]
    assert kb.sparql(query, model=["bob"]) == bob
    with pytest.raises(KbError, match="nope"):
        kb.sparql(query, model="nope")
    with pytest.raises(KbError):
        kb.sparql(query, model=["default", "bob"])


def test_construct(kb: KB) -> None:
    result = kb.sparql("CONSTRUCT { ?x oro:sees oro:cup_1 } WHERE { ?x oro:sees oro:cup_1 }")
    assert result["query"].startswith("CONSTRUCT")
    graph = Graph().parse(data=json.dumps(result["graph"]), format="json-ld")
    assert set(graph) == {(URIRef(ORO + "alfred"), URIRef(ORO + "sees"), URIRef(ORO + "cup_1"))}


@pytest.mark.parametrize(
    "query",
    [
        "INSERT DATA { oro:a oro:b oro:c }",
        "DELETE WHERE { ?s ?p ?o }",
        "DROP ALL",
        "CLEAR DEFAULT",
        "LOAD <file:///etc/passwd>",
    ],
)
def test_updates_are_refused(kb: KB, query: str) -> None:
    before = kb.size()
    with pytest.raises(KbError):
        kb.sparql(query)
    assert kb.size() == before


@pytest.mark.parametrize(
    "query",
    ["", "   ", "SELEC ?x WHERE { ?x ?p ?o }", "SELECT ?x WHERE { ?x zz:p ?o }", "SELECT ?x WHERE { ?x ?p "],
)
def test_errors_are_kb_errors(kb: KB, query: str) -> None:
    with pytest.raises(KbError):
        kb.sparql(query)


def test_serialize_formats(kb: KB) -> None:
    kind, data = kb.sparql_serialize("SELECT ?x WHERE { ?x oro:sees oro:cup_1 }", "csv")
    assert kind == "SELECT"
    assert data.decode().split() == ["x", ORO + "alfred"]
    kind, data = kb.sparql_serialize("SELECT ?x WHERE { ?x oro:sees oro:cup_1 }", "json")
    assert json.loads(data)["results"]["bindings"][0]["x"]["value"] == ORO + "alfred"
    kind, data = kb.sparql_serialize("CONSTRUCT { ?x oro:sees ?y } WHERE { ?x oro:sees ?y }", "nt")
    assert kind == "CONSTRUCT"
    assert f"<{ORO}alfred> <{ORO}sees> <{ORO}cup_1> ." in data.decode()


def test_index_store_is_read_only() -> None:
    index = TripleIndex()
    index.add(URIRef(ORO + "a"), URIRef(ORO + "p"), URIRef(ORO + "b"))
    graph = Graph(store=IndexStore(index))
    assert len(graph) == 1
    with pytest.raises(KbError, match="read-only"):
        graph.add((URIRef(ORO + "x"), URIRef(ORO + "p"), URIRef(ORO + "y")))
    with pytest.raises(KbError, match="read-only"):
        graph.remove((URIRef(ORO + "a"), URIRef(ORO + "p"), URIRef(ORO + "b")))
    assert len(index) == 1


def test_execute_and_to_json_on_an_index() -> None:
    index = TripleIndex()
    index.add(URIRef(ORO + "a"), URIRef(ORO + "p"), URIRef(ORO + "b"))
    query = "SELECT ?s WHERE { ?s oro:p oro:b }"
    data = to_json(execute(index, query), query)
    assert data["results"]["bindings"] == [{"s": {"type": "uri", "value": ORO + "a"}}]
    assert data["query"] == query


def test_sparql_update_is_one_batch_with_the_net_effect_of_its_operations() -> None:
    import pytest

    from kb import KB
    from kb.errors import InvalidSparql, UnsupportedUpdate

    with KB() as kb:
        kb += "cup_1 isOn table_1"
        revision = kb.revision
        kb.sparql_update("INSERT DATA { :cup_1 :isOn :shelf_1 . :cup_2 :isOn :shelf_1 } ; "
                         "DELETE DATA { :cup_1 :isOn :table_1 . :cup_2 :isOn :shelf_1 }")
        assert kb.revision == revision + 1
        assert kb["?c isOn ?s"] == [{"c": "cup_1", "s": "shelf_1"}]
        with pytest.raises(UnsupportedUpdate, match="DeleteWhere"):
            kb.sparql_update("INSERT DATA { :a :b :c } ; DELETE WHERE { ?x :isOn ?y }")
        with pytest.raises(InvalidSparql):
            kb.sparql_update("INSERT NONSENSE")
        assert kb["a b ?c"] == [] and kb.revision == revision + 1
