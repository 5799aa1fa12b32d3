"""SPARQL text is written from checked terms only: nothing a term holds can end it early."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from rdflib import BNode, Literal, URIRef, Variable

from kb import KbError
from kb.sparqlstore import text as sparqltext
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.layout import skolem, unskolem


@pytest.mark.parametrize("iri", ["http://x/a b", "http://x/a>b", 'http://x/"', "http://x/{", "http://x/\\", "urn:a\nb"])
def test_iris_that_would_break_out_are_refused(iri: str) -> None:
    with pytest.raises(KbError, match="not a valid IRI"):
        sparqltext.term(URIRef(iri))


def test_variables_are_checked() -> None:
    assert sparqltext.term(Variable("o")) == "?o"
    with pytest.raises(KbError, match="not a valid variable"):
        sparqltext.term(Variable("o } DROP ALL"))


def test_blank_nodes_become_skolem_iris_and_come_back() -> None:
    node = BNode("n1 x")
    written = sparqltext.term(node)
    assert written.startswith("<urn:situated:/.well-known/genid/")
    assert unskolem(str(skolem(node))) == node


@pytest.fixture(scope="module")
def endpoint(oxigraph: object) -> Iterator[SparqlEndpoint]:
    with_store = SparqlEndpoint(oxigraph.store("literals"))  # type: ignore[attr-defined]
    yield with_store
    with_store.close()


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(value=st.text(), lang=st.sampled_from([None, "en", "fr-CA"]))
def test_any_literal_round_trips_through_the_store_and_injects_nothing(
        endpoint: SparqlEndpoint, value: str, lang: str | None) -> None:
    graph = URIRef("urn:test:literals")
    subject, predicate = URIRef("urn:test:s"), URIRef("urn:test:p")
    endpoint.update(f"DROP SILENT GRAPH {sparqltext.term(graph)} ;\n"
                    f"INSERT DATA {{ {sparqltext.graph_data(graph, [(subject, predicate, Literal(value, lang=lang))])} }}")
    rows = endpoint.select(f"SELECT ?s ?p ?o WHERE {{ GRAPH {sparqltext.term(graph)} {{ ?s ?p ?o }} }}")
    assert rows == [{"s": subject, "p": predicate, "o": Literal(value, lang=lang)}]
