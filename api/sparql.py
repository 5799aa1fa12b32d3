"""SPARQL 1.1 Protocol semantics over the KB: result formats by query form and Accept, and the
INSERT DATA / DELETE DATA subset of SPARQL Update, applied through the KB's write path.

Everything here is blocking (rdflib parsing and evaluation): call it off the event loop.
"""

from __future__ import annotations

from typing import Any

from pyparsing import ParseBaseException
from rdflib import Graph, Literal, URIRef
from rdflib.plugins.sparql.algebra import translateUpdate, traverse
from rdflib.plugins.sparql.parser import parseQuery, parseUpdate
from rdflib.plugins.sparql.parserutils import CompValue
from rdflib.term import BNode, Node

from api.errors import ApiError
from api.negotiation import negotiate
from kb import KB
from kb.sparql import INIT_NS
from kb.terms import ORO, format_triple

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


def _alias_oro(node: Any) -> None:
    # As kb.sparql does for queries: rdflib keeps one prefix per namespace, so `oro:` names are
    # renamed to the predeclared `:` (unless the update declares its own `oro:`).
    if isinstance(node, CompValue) and node.name == "pname" and node.get("prefix") == "oro":
        del node["prefix"]


def _invalid(kind: str, exc: ParseBaseException) -> ApiError:
    return ApiError(400, "invalid_sparql", f"invalid SPARQL {kind}: {exc}")


def query_form(query: str) -> str:
    """``SelectQuery``, ``AskQuery``, ``ConstructQuery`` or ``DescribeQuery``."""
    try:
        return str(parseQuery(query)[1].name)
    except ParseBaseException as exc:
        raise _invalid("query (SPARQL Update goes in an 'update' parameter)", exc) from exc


def answer(kb: KB, query: str, accept: str | None, model: str | None) -> tuple[str, bytes]:
    """Run a read-only query; returns (media type, body) in the format the client accepts."""
    offers = _FORMS[query_form(query)]
    media = negotiate(accept, list(offers))
    if offers[media] == "tsv":  # rdflib has no TSV results serialiser
        return media, _tsv(kb.sparql(query, model))
    _, body = kb.sparql_serialize(query, offers[media], model)
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


def apply_update(kb: KB, update: str, model: str | None) -> None:
    """Apply INSERT DATA / DELETE DATA operations in order; anything else is refused before any
    change is made. Inserts add exactly the triples (no functional-property replacement)."""
    try:
        tree = parseUpdate(update)
        if not any(getattr(d, "prefix", None) == "oro" for prologue in tree["prologue"] for d in prologue):
            traverse(tree, visitPost=_alias_oro)
        parsed = translateUpdate(tree, base=ORO, initNs=INIT_NS)
    except ParseBaseException as exc:
        raise _invalid("update", exc) from exc
    except Exception as exc:
        if type(exc) is not Exception:  # rdflib raises a bare Exception for an unknown prefix
            raise
        raise ApiError(400, "invalid_sparql", f"invalid SPARQL update: {exc}") from exc
    operations = []
    for op in parsed.algebra:
        if op.name not in ("InsertData", "DeleteData"):
            raise ApiError(400, "unsupported_update",
                           f"only INSERT DATA and DELETE DATA are supported, not {op.name}")
        if op.quads and any(op.quads.values()):
            raise ApiError(400, "unsupported_update",
                           "GRAPH blocks are not supported in updates; use the 'model' parameter")
        triples = list(op.triples or [])
        if any(isinstance(t, BNode) for triple in triples for t in triple):
            raise ApiError(400, "unsupported_update", "blank nodes cannot be written to the KB")
        operations.append((op.name, triples))
    models = [model] if model else None
    for name, triples in operations:
        if not triples:
            continue
        if name == "InsertData":
            graph = Graph()
            for triple in triples:
                graph.add(triple)
            kb.load_data(graph.serialize(format="nt", encoding="utf-8"), "nt", models)
        else:
            kb.remove([format_triple(t) for t in triples], models)
