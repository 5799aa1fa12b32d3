"""The SPARQL 1.1 Protocol endpoint, including rdflib's SPARQLStore as a client."""

from __future__ import annotations

import csv
import io
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import httpx
from pydantic import SecretStr
from rdflib import Graph, URIRef
from rdflib.plugins.stores.sparqlstore import SPARQLStore

from api.settings import Limits, Settings
from tests.api.conftest import SCENE, Live
from tests.reliability.server import ServerProcess

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


# --- anonymous /sparql on a fresh service (issue 26, item 1) -------------------------------------

FIRST_QUERIES = [SELECT, ASK, CONSTRUCT, "DESCRIBE <http://x.org/a>",
                 "SELECT ?x WHERE { VALUES ?x { 1 2 3 } OPTIONAL { ?x ?y ?z } } ORDER BY DESC(?x)",
                 "SELECT ?x (SAMPLE(?y) AS ?z) WHERE { ?x ?p ?y } GROUP BY ?x HAVING (COUNT(?y) > 1)",
                 "SELECT (COUNT(*) AS ?n) WHERE { ?s ?p ?o FILTER(REGEX(STR(?s), 'cup')) }"]


def test_concurrent_first_queries_of_a_fresh_service_leave_sparql_answering(tmp_path: Path) -> None:
    # The parses take turns: on a busy machine 40 of them queue past the default 5 s budget, and a
    # 503 query_timeout would say so (a right answer, but not what this test is about).
    server = ServerProcess(["--scene", "none"], tmp_path / "server.log", env={"SITUATED_LIMITS__QUERY_TIMEOUT": "300"})
    try:
        server.wait_ready(timeout=120)
        start = threading.Barrier(40)

        def first(n: int) -> int:
            with httpx.Client(timeout=120) as client:
                start.wait()
                return client.get(server.url + "/sparql", params={"query": FIRST_QUERIES[n % len(FIRST_QUERIES)]},
                                  headers={"accept": "application/sparql-results+json, text/turtle"}).status_code

        with ThreadPoolExecutor(40) as pool:
            statuses = list(pool.map(first, range(40)))
        assert statuses == [200] * 40, statuses
        with httpx.Client(timeout=60) as client:
            for query in FIRST_QUERIES:
                later = client.get(server.url + "/sparql", params={"query": query},
                                   headers={"accept": "application/sparql-results+json, text/turtle"})
                assert later.status_code == 200, later.text
            assert client.get(server.url + "/health").json()["status"] == "ok"
    finally:
        server.kill()


def test_a_concat_chain_and_a_long_parse_are_refused_clearly(live_factory) -> None:  # type: ignore[no-untyped-def]
    # The chain is refused by the size of what it builds, whatever the time budget (a generous one
    # here: on a loaded machine its first doublings alone may take a second).
    roomy = live_factory(Settings(scene=SCENE, limits=Limits(query_timeout=120.0)))
    # 512 characters doubled 13 times: 4 MiB (30 times, the attack: 512 GiB)
    binds = " ".join(f"BIND(CONCAT(?v{i}, ?v{i}) AS ?v{i + 1})" for i in range(13))
    chain = f'SELECT (STRLEN(?v13) AS ?n) WHERE {{ BIND("{"x" * 512}" AS ?v0) {binds} }}'
    refused = roomy.client.get("/sparql", params={"query": chain})
    assert (refused.status_code, refused.json()["code"]) == (413, "query_too_large"), refused.text
    assert "CONCAT builds a string" in refused.json()["message"]
    live = live_factory(Settings(scene=SCENE, limits=Limits(query_timeout=1.0)))
    values = "SELECT ?x WHERE { VALUES ?x { " + "1 " * 40_000 + "} }"
    slow = live.client.post("/sparql", content=values, headers={"content-type": "application/sparql-query"})
    assert (slow.status_code, slow.json()["code"]) == (503, "query_timeout"), slow.text
    huge = "SELECT ?x WHERE { VALUES ?x { " + "<x> " * 30_000 + "} }"
    too_large = live.client.post("/sparql", content=huge, headers={"content-type": "application/sparql-query"})
    assert (too_large.status_code, too_large.json()["code"]) == (413, "query_too_large"), too_large.text
    assert live.client.get("/sparql", params={"query": ASK}).json()["boolean"] is True


def test_expression_errors_are_unbound_and_an_aggregate_error_a_400(live: Live) -> None:
    xsd = "PREFIX xsd: <http://www.w3.org/2001/XMLSchema#> "
    huge = live.client.get("/sparql", params={"query": xsd + 'SELECT (CEIL("1E999999"^^xsd:decimal) AS ?x) '
                                                          '(ROUND(xsd:double("NaN")) AS ?y) WHERE {}'})
    assert huge.status_code == 200, huge.text
    assert huge.json()["results"]["bindings"] == [{}]
    summed = live.client.get("/sparql", params={
        "query": xsd + 'SELECT (SUM(?x) AS ?s) WHERE { VALUES ?x { "P1D"^^xsd:dayTimeDuration 1 } }'})
    assert (summed.status_code, summed.json()["code"]) == (400, "kb_error"), summed.text
    assert "the query could not be evaluated" in summed.json()["message"]
