"""SPARQL 1.1 Protocol semantics over the KB: result formats by query form and Accept, and the
INSERT DATA / DELETE DATA subset of SPARQL Update, applied through the KB's write path.

Everything here is blocking (rdflib parsing and evaluation): call it off the event loop.
"""

from __future__ import annotations

from api.errors import ApiError
from api.negotiation import negotiate
from api.settings import Limits
from kb.errors import InvalidSparql, UnsupportedUpdate
from kb.protocol import KnowledgeBase

RESULTS = {
    "application/sparql-results+json": "json",
    "application/sparql-results+xml": "xml",
    "application/json": "json",
    "text/csv": "csv",
    "text/tab-separated-values": "tsv",
}
BOOLEAN_RESULTS = {k: v for k, v in RESULTS.items() if v in ("json", "xml")}
GRAPHS = {
    "text/turtle": "turtle",
    "application/n-triples": "nt",
    "application/ld+json": "json-ld",
    "application/rdf+xml": "xml",
}
# By result type, as the KB reports it.
_FORMS = {"SELECT": RESULTS, "ASK": BOOLEAN_RESULTS, "CONSTRUCT": GRAPHS, "DESCRIBE": GRAPHS}


def answer(kb: KnowledgeBase, query: str, accept: str | None, model: str | None,
           limits: Limits) -> tuple[str, bytes]:
    """Run a read-only query within the service's time budget and row cap; returns (media type,
    body) in the format the client accepts. The query is parsed once, by the KB, within the
    budget: the format follows from the result's type (an Accept that no format of it meets is a
    406)."""

    def media_of(form: str) -> str:
        return negotiate(accept, list(_FORMS[form]))

    try:
        form, body = kb.sparql_serialize(query, lambda form: _FORMS[form][media_of(form)], model,
                                         timeout=limits.query_timeout, max_rows=limits.max_rows)
    except InvalidSparql as exc:
        raise ApiError(400, "invalid_sparql", f"{exc} (SPARQL Update goes in an 'update' parameter)") from exc
    return media_of(form), body


def apply_update(kb: KnowledgeBase, update: str, model: str | None) -> None:
    """Apply INSERT DATA / DELETE DATA as one KB batch; anything else is refused unchanged."""
    try:
        kb.sparql_update(update, [model] if model else None)
    except UnsupportedUpdate as exc:
        raise ApiError(400, "unsupported_update", str(exc)) from exc
    except InvalidSparql as exc:
        raise ApiError(400, "invalid_sparql", str(exc)) from exc
