"""The store URL of a scaled-out KB, and what the SPARQL client reports when the store fails."""

from __future__ import annotations

import pytest

from kb import KbError
from kb.errors import StoreUnavailable
from kb.sparqlstore.endpoint import SparqlEndpoint, StoreSpec
from kb.sparqlstore.layout import Layout


def test_oxigraph_layout_by_default() -> None:
    spec = StoreSpec.parse("sparql+http://127.0.0.1:7878")
    assert (spec.query_url, spec.update_url) == ("http://127.0.0.1:7878/query", "http://127.0.0.1:7878/update")
    assert spec.layout == Layout("situated")


def test_other_engines_name_their_endpoints() -> None:
    fuseki = StoreSpec.parse("sparql+http://h:3030/ds/?dataset=site_2")
    assert (fuseki.query_url, fuseki.update_url) == ("http://h:3030/ds/query", "http://h:3030/ds/update")
    assert fuseki.layout.dataset == "site_2"
    graphdb = StoreSpec.parse("sparql+https://h/repositories/r?update=/repositories/r/statements&query=/repositories/r")
    assert (graphdb.query_url, graphdb.update_url) == ("https://h/repositories/r", "https://h/repositories/r/statements")


@pytest.mark.parametrize(("spec", "message"), [
    ("http://h:1", "must look like sparql"),
    ("sparql+http://", "must look like sparql"),
    ("sparql+http://h:1?graph=x", "unknown option"),
    ("sparql+http://h:1?dataset=a/b", "dataset name"),
])
def test_bad_store_urls_say_what_is_wrong(spec: str, message: str) -> None:
    with pytest.raises(KbError, match=message):
        StoreSpec.parse(spec)


def test_an_unreachable_store_is_a_clear_error() -> None:
    endpoint = SparqlEndpoint("sparql+http://127.0.0.1:9", timeout=2)
    with pytest.raises(StoreUnavailable, match="cannot be reached"):
        endpoint.ask("ASK {}")
    with pytest.raises(StoreUnavailable, match=r"127\.0\.0\.1:9/update"):
        endpoint.update("INSERT DATA {}")
    endpoint.close()


def test_a_store_error_names_status_and_reason(oxigraph: object) -> None:
    endpoint = SparqlEndpoint(oxigraph.store())  # type: ignore[attr-defined]
    with pytest.raises(StoreUnavailable, match="answered 400"):
        endpoint.select("SELECT nonsense")
    endpoint.close()
