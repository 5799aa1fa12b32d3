"""SPARQL 1.1 Protocol semantics over the KB: result formats by query form and Accept, and the
INSERT DATA / DELETE DATA subset of SPARQL Update, applied through the KB's write path.

Everything here is blocking (rdflib parsing and evaluation): call it off the event loop.
"""

from __future__ import annotations

from typing import Any

from pyparsing import ParseBaseException
from rdflib import Literal, URIRef
from rdflib.plugins.sparql.parser import parseQuery
from rdflib.term import BNode, Node

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
_FORMS = {"SelectQuery": RESULTS, "AskQuery": BOOLEAN_RESULTS, "ConstructQuery": GRAPHS,
          "DescribeQuery": GRAPHS}


def _invalid(kind: str, exc: ParseBaseException) -> ApiError:
    return ApiError(400, "invalid_sparql", f"invalid SPARQL {kind}: {exc}")


def query_form(query: str) -> str:
    """``SelectQuery``, ``AskQuery``, ``ConstructQuery`` or ``DescribeQuery``."""
    try:
        return str(parseQuery(query)[1].name)
    except ParseBaseException as exc:
        raise _invalid("query (SPARQL Update goes in an 'update' parameter)", exc) from exc
    except RecursionError:  # pyparsing recurses on nested groups
        raise ApiError(400, "invalid_sparql", "invalid SPARQL query: it is nested too deeply") from None


def answer(kb: KnowledgeBase, query: str, accept: str | None, model: str | None,
           limits: Limits) -> tuple[str, bytes]:
    """Run a read-only query within the service's time budget and row cap; returns (media type,
    body) in the format the client accepts."""
    offers = _FORMS[query_form(query)]
    media = negotiate(accept, list(offers))
    timeout, max_rows = limits.query_timeout, limits.max_rows
    if offers[media] == "tsv":  # rdflib has no TSV results serialiser
        return media, _tsv(kb.sparql(query, model, timeout=timeout, max_rows=max_rows))
    _, body = kb.sparql_serialize(query, offers[media], model, timeout=timeout, max_rows=max_rows)
    return media, body


def _term(binding: dict[str, str]) -> Node:
    kind, value = binding["type"], binding["value"]
    if kind == "uri":
        return URIRef(value)
    if kind == "bnode":
        return BNode(value)
    datatype = binding.get("datatype")
    return Literal(value, lang=binding.get("xml:lang"), datatype=URIRef(datatype) if datatype else None)


def _tsv(results: dict[str, Any]) -> bytes:
    """W3C SPARQL 1.1 TSV results: a header of ?vars, then terms in Turtle syntax."""
    names = results["head"]["vars"]
    lines = ["\t".join(f"?{n}" for n in names)]
    for row in results["results"]["bindings"]:
        lines.append("\t".join(_term(row[n]).n3() if n in row else "" for n in names))
    return ("\n".join(lines) + "\n").encode("utf-8")


def apply_update(kb: KnowledgeBase, update: str, model: str | None) -> None:
    """Apply INSERT DATA / DELETE DATA as one KB batch; anything else is refused unchanged."""
    try:
        kb.sparql_update(update, [model] if model else None)
    except UnsupportedUpdate as exc:
        raise ApiError(400, "unsupported_update", str(exc)) from exc
    except InvalidSparql as exc:
        raise ApiError(400, "invalid_sparql", str(exc)) from exc
