"""The SPARQL 1.1 Protocol endpoint, including rdflib's SPARQLStore as a client."""

from __future__ import annotations

import csv
import io

from pydantic import SecretStr
from rdflib import Graph, URIRef
from rdflib.plugins.stores.sparqlstore import SPARQLStore

from api.settings import Settings
from tests.api.conftest import SCENE, Live

ORO = "http://kb.openrobots.org#"
SELECT = f"PREFIX o: <{ORO}> SELECT ?x WHERE {{ o:myself o:sees ?x . ?x o:isOn o:table_1 }} ORDER BY ?x"
ASK = f"PREFIX o: <{ORO}> ASK {{ o:cup_1 o:isOn o:table_1 }}"
CONSTRUCT = f"PREFIX o: <{ORO}> CONSTRUCT {{ ?x o:isOn o:table_1 }} WHERE {{ ?x o:isOn o:table_1 }}"


def test_get_and_post_select_in_every_result_format(live: Live) -> None:
    client = live.client
    as_json = client.get("/sparql", params={"query": SELECT},
                         headers={"accept": "application/sparql-results+json"})
    assert as_json.headers["content-type"].startswith("application/sparql-results+json")
    values = [b["x"]["value"] for b in as_json.json()["results"]["bindings"]]
    assert values == [ORO + "book_1", ORO + "cup_1"]
    form = client.post("/sparql", data={"query": SELECT}, headers={"accept": "text/csv"})
    assert form.headers["content-type"].startswith("text/csv")
    assert list(csv.reader(io.StringIO(form.text)))[1:] == [[ORO + "book_1"], [ORO + "cup_1"]]
    direct = client.post("/sparql", content=SELECT, headers={"content-type": "application/sparql-query",
                                                             "accept": "text/tab-separated-values"})
    assert direct.text.splitlines()[0] == "?x"
    xml = client.get("/sparql", params={"query": SELECT},
                     headers={"accept": "application/sparql-results+xml"})
    assert "<sparql" in xml.text and "book_1" in xml.text


def test_ask_and_construct(live: Live) -> None:
    client = live.client
    predeclared = client.get("/sparql", params={"query": "ASK { :cup_1 oro:isOn :table_1 . :cup_1 a dbr:Cup }"})
    assert predeclared.json()["boolean"] is True
    assert client.get("/sparql", params={"query": ASK}).json()["boolean"] is True
    assert client.get("/sparql", params={"query": ASK}, headers={"accept": "text/csv"}).status_code == 406
    turtle = client.get("/sparql", params={"query": CONSTRUCT}, headers={"accept": "text/turtle"})
    assert turtle.headers["content-type"].startswith("text/turtle")
    graph = Graph().parse(data=turtle.text, format="turtle")
    assert (URIRef(ORO + "cup_1"), URIRef(ORO + "isOn"), URIRef(ORO + "table_1")) in graph


def test_bad_queries_and_updates_are_refused(live: Live) -> None:
    client = live.client
    assert client.get("/sparql", params={"query": "SELEKT nothing"}).json()["code"] == "invalid_sparql"
    assert client.get("/sparql").json()["code"] == "missing_query"
    update = f"PREFIX o: <{ORO}> INSERT DATA {{ o:cup_1 o:isOn o:shelf_1 }}"
    refused = client.post("/sparql", data={"update": update})
    assert (refused.status_code, refused.json()["code"]) == (403, "sparql_update_disabled")
    assert client.get("/sparql", params={"query": SELECT, "default-graph-uri": "x"}).status_code == 400


def test_rdflib_sparqlstore_queries_the_service(live: Live) -> None:
    store = SPARQLStore(query_endpoint=live.url + "/sparql")
    graph = Graph(store=store)
    rows = sorted(str(row[0]) for row in graph.query(SELECT) if isinstance(row, tuple))
    assert rows == [ORO + "book_1", ORO + "cup_1"]
    assert graph.query(ASK).askAnswer is True
    constructed = graph.query(CONSTRUCT).graph
    assert constructed is not None and len(constructed) == 2
    assert (URIRef(ORO + "book_1"), URIRef(ORO + "isOn"), URIRef(ORO + "table_1")) in graph


def test_update_when_enabled_goes_through_the_kb(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(Settings(scene=SCENE, sparql_update=True, token=SecretStr("s3cret")))
    insert = f'PREFIX o: <{ORO}> INSERT DATA {{ o:cup_1 o:isOn o:shelf_1 . o:cup_1 o:note "hi" }}'
    assert live.client.post("/sparql", data={"update": insert}).status_code == 401
    auth = {"authorization": "Bearer s3cret"}
    assert live.client.post("/sparql", data={"update": insert}, headers=auth).status_code == 204
    kb = live.services.kb
    assert kb.find(["cup_1 isOn ?s"]) == [{"s": "shelf_1"}, {"s": "table_1"}]
    assert kb.find(["shelf_1 placeOf ?x"]) == [{"x": "cup_1"}]  # reasoned like any KB write
    delete = 'DELETE DATA { :cup_1 oro:note "hi" }'  # the KB's predeclared prefixes
    assert live.client.post("/sparql", content=delete, headers={
        **auth, "content-type": "application/sparql-update"}).status_code == 204
    assert kb.find(["cup_1 note ?n"]) == []
    delete_where = f"PREFIX o: <{ORO}> DELETE WHERE {{ ?x o:isOn ?y }}"
    refused = live.client.post("/sparql", content=delete_where, headers={
        **auth, "content-type": "application/sparql-update"})
    assert refused.json()["code"] == "unsupported_update"
    assert kb.find(["cup_1 isOn shelf_1"]) == ["cup_1 isOn shelf_1"]
