"""Read-only SPARQL over one model's closure, through rdflib, for completeness (kb-compat §3.7).

The model's index is exposed to rdflib as a read-only Store, so no copy of the graph is made.
This path is not the hot path: pattern queries use kb.query. The knowledge_core prefixes and
base are declared to the parser as initial namespaces and base IRI, never pasted into the text.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import Any

from pyparsing import ParseBaseException
from rdflib import BNode, Graph, URIRef
from rdflib.plugins.sparql.algebra import translateQuery, translateUpdate, traverse
from rdflib.plugins.sparql.parser import expandUnicodeEscapes, parseQuery, parseUpdate
from rdflib.plugins.sparql.parserutils import CompValue
from rdflib.query import Result
from rdflib.store import Store
from rdflib.term import Node as RdfNode

from kb.deadline import Deadline, TimedIndex
from kb.errors import InvalidSparql, KbError, QueryEvaluationError, QueryTooLarge, UnsupportedUpdate
from kb.index import TripleIndex
from kb.rdfio import unwritable
from kb.sparqlbudget import bound, check_size
from kb.sparqlexpr import EVALUATION_ERRORS
from kb.sparqlparse import Parser, parse
from kb.terms import ORO, PREFIXES, Node, Triple
from kb.unicode import check_terms, check_text

_GRAPH_ID = URIRef(ORO + "sparql")
#: The longest query text parsed, in characters: a parse holds what it builds, and takes time in
#: proportion (an update is a write, bounded by its request or file).
MAX_QUERY_CHARS = 100_000
# rdflib keeps one prefix per namespace, so `:` is declared and `oro:` names are renamed to it in
# the parse tree (see _alias_oro), unless the query declares its own `oro:`.
INIT_NS = {**{prefix: ns for prefix, ns in PREFIXES.items() if prefix not in ("", "oro")}, "": ORO}


class IndexStore(Store):
    """rdflib's view of a TripleIndex: triples and length only; writes are refused."""

    context_aware = False
    formula_aware = False
    graph_aware = False
    transaction_aware = False

    def __init__(self, index: TripleIndex | TimedIndex) -> None:
        super().__init__()
        self._index = index
        self._ns: dict[str, URIRef] = {}

    def triples(
        self, triple_pattern: tuple[Any, Any, Any], context: Any = None
    ) -> Iterator[tuple[tuple[Node, Node, Node], Iterator[Any]]]:
        s, p, o = triple_pattern
        if not _plain(s) or not _plain(p) or not _plain(o):
            # rdflib may pass a Path or a Graph as a pattern term: evaluate it as a wildcard
            # and let the caller filter (it does for paths).
            s = s if _plain(s) else None
            p = p if _plain(p) else None
            o = o if _plain(o) else None
        for triple in self._index.triples(s, p, o):
            yield triple, iter(())

    def __len__(self, context: Any = None) -> int:
        return len(self._index)

    def add(self, triple: Any, context: Any, quoted: bool = False) -> None:
        raise KbError("SPARQL access to the KB is read-only: use add/update/remove")

    def remove(self, triple: Any, context: Any = None) -> None:
        raise KbError("SPARQL access to the KB is read-only: use add/update/remove")

    def bind(self, prefix: str, namespace: URIRef, override: bool = True) -> None:
        self._ns[prefix] = namespace

    def namespace(self, prefix: str) -> URIRef | None:
        return self._ns.get(prefix)

    def prefix(self, namespace: URIRef) -> str | None:
        return next((p for p, ns in self._ns.items() if ns == namespace), None)

    def namespaces(self) -> Iterator[tuple[str, URIRef]]:
        yield from self._ns.items()


def _plain(term: Any) -> bool:
    return term is None or (isinstance(term, RdfNode) and not isinstance(term, Graph))


def _alias_oro(node: Any) -> None:
    if isinstance(node, CompValue) and node.name == "pname" and node.get("prefix") == "oro":
        del node["prefix"]


def _refuse_remote(tree: Any) -> None:
    """SERVICE makes rdflib call the named endpoint, and FROM / FROM NAMED / GRAPH make it load
    or expect other graphs: a query must not make the service fetch from the network or reach
    other hosts (nor fail inside rdflib), so these are refused before evaluation."""
    if "datasetClause" in tree[1]:
        raise KbError("FROM and FROM NAMED are not supported: each KB model is one dataset; "
                      "choose it with the model parameter")
    found: list[CompValue] = []

    def visit(node: Any) -> None:
        if isinstance(node, CompValue) and node.name in ("ServiceGraphPattern", "GraphGraphPattern"):
            found.append(node)

    traverse(tree, visitPost=visit)
    for node in found:
        if node.name == "ServiceGraphPattern":
            raise KbError(f"SERVICE is not supported (a federated query would call {node['term']}); "
                          "situated answers from its own KB only")
        raise KbError("GRAPH is not supported: each KB model is one graph; choose it with the model "
                      "parameter")


def _translate(text: str, kind: str, parser: Parser, translate: Callable[..., Any],
               prologues: Callable[[Any], Iterable[Any]], deadline: Deadline | None = None,
               max_chars: int | None = MAX_QUERY_CHARS) -> tuple[Any, frozenset[str]]:
    """The translated query or update, and the prefixes it declares itself."""
    if max_chars is not None and len(text) > max_chars:  # before expanding escapes, too
        raise QueryTooLarge(f"the SPARQL {kind} has {len(text)} characters; the limit is {max_chars}")
    try:
        # SPARQL's \u escapes apply to the whole text before parsing; a lone surrogate one would
        # put text that is not Unicode into the results (or, for an update, into the KB).
        check_text(expandUnicodeEscapes(text), f"the SPARQL {kind}")
    except ValueError as exc:  # an escape beyond U+10FFFF
        raise InvalidSparql(f"invalid SPARQL {kind}: {exc}") from None
    try:
        tree = parse(text, parser, deadline)
        if kind == "query":
            _refuse_remote(tree)
        # CompValue.get takes no default (its second argument means something else): use dict's.
        declared = frozenset(dict.get(decl, "prefix", "")
                             for p in prologues(tree) for decl in p if decl.name == "PrefixDecl")
        if "oro" not in declared:
            traverse(tree, visitPost=_alias_oro)
        return translate(tree, base=ORO, initNs=INIT_NS), declared
    except ParseBaseException as exc:
        hint = " (only read-only queries are accepted here)" if kind == "query" else ""
        raise InvalidSparql(f"invalid SPARQL {kind}{hint}: {exc}") from exc
    except RecursionError:  # pyparsing and the algebra recurse on nested groups
        raise InvalidSparql(f"invalid SPARQL {kind}: it is nested too deeply") from None
    except Exception as exc:
        if type(exc) is not Exception:  # rdflib raises a bare Exception for an unknown prefix
            raise
        raise InvalidSparql(f"invalid SPARQL {kind}: {exc}") from exc


def parse_update(update: str) -> tuple[list[Triple], list[Triple]]:
    """The net (added, removed) triples of INSERT DATA / DELETE DATA operations, in order; any
    other update form is refused before anything changes."""
    if not isinstance(update, str) or not update.strip():
        raise InvalidSparql("a SPARQL update must be a non-empty string")
    # An update is a write, whose size the caller bounds (a request body, a file): no text bound.
    parsed, _ = _translate(update, "update", parseUpdate, translateUpdate, lambda tree: tree["prologue"],
                           max_chars=None)
    added: dict[Triple, None] = {}
    removed: dict[Triple, None] = {}
    for op in parsed.algebra:
        if op.name not in ("InsertData", "DeleteData"):
            raise UnsupportedUpdate(f"only INSERT DATA and DELETE DATA are supported, not {op.name}")
        if op.quads and any(op.quads.values()):
            raise UnsupportedUpdate("GRAPH blocks are not supported in updates; choose the model instead")
        triples = list(op.triples or [])
        if any(isinstance(t, BNode) for triple in triples for t in triple):
            raise UnsupportedUpdate("blank nodes cannot be written to the KB")
        into, out_of = (added, removed) if op.name == "InsertData" else (removed, added)
        for triple in triples:
            check_terms(triple, "a term of the SPARQL update")
            into[triple] = None
            out_of.pop(triple, None)
    return list(added), list(removed)


@dataclass(frozen=True)
class CheckedQuery:
    """A read-only query that passed the checks of ``execute``, not yet run."""

    prepared: Any  # rdflib's translated query
    form: str  # SELECT, ASK, CONSTRUCT or DESCRIBE
    declared: frozenset[str]  # the prefixes the query declares itself ("" for ':')


_FORMS = {"SelectQuery": "SELECT", "AskQuery": "ASK", "ConstructQuery": "CONSTRUCT",
          "DescribeQuery": "DESCRIBE"}


def check_query(query: str, deadline: Deadline | None = None) -> CheckedQuery:
    """Parse a read-only query and refuse what ``execute`` refuses (updates, SERVICE, FROM,
    GRAPH, syntax errors, a text over ``MAX_QUERY_CHARS``), with the same errors; the query is not
    run. Parsing waits for its turn and stops at the ``deadline`` (``QueryTimeout``)."""
    if not isinstance(query, str) or not query.strip():
        raise InvalidSparql("a SPARQL query must be a non-empty string")
    prepared, declared = _translate(query, "query", parseQuery, translateQuery, lambda tree: [tree[0]],
                                    deadline)
    return CheckedQuery(prepared, _FORMS[prepared.algebra.name], declared)


def execute(index: TripleIndex, query: str | CheckedQuery, deadline: Deadline | None = None,
            max_rows: int | None = None) -> Result:
    """Run a read-only query (text, or checked by ``check_query`` under the same deadline); a
    SPARQL Update or a syntax error is a KbError. Past the ``deadline`` it stops with
    ``kb.deadline.QueryTimeout``; a SELECT with more than ``max_rows`` rows (a graph with more
    triples) is ``kb.query.TooManyRows``; a string built past kb.sparqlspend's bounds is
    ``QueryTooLarge``."""
    checked = query if isinstance(query, CheckedQuery) else check_query(query, deadline)
    prepared = checked.prepared
    bound(prepared, deadline, max_rows)
    store = IndexStore(index if deadline is None else TimedIndex(index, deadline))
    try:
        result = Graph(store=store, identifier=_GRAPH_ID).query(prepared)
        if result.type == "SELECT":
            result.bindings  # noqa: B018 - materialise while the caller holds the KB lock
    except EVALUATION_ERRORS as exc:
        # An expression's errors are error values (kb.sparqlexpr); what reaches here is an
        # aggregate's (SUM of a duration and a number, of decimals past the largest one).
        raise QueryEvaluationError(f"the query could not be evaluated: {_reason(exc)}") from None
    check_size(result, max_rows)
    return result


def _reason(exc: BaseException) -> str:
    text = str(exc) or type(exc).__name__
    return text if len(text) <= 200 else text[:200] + "..."


def serialize(result: Result, fmt: str) -> bytes:
    """A result in a results format (``json``, ``xml``, ``csv``, ``tsv``) or, for a graph, an RDF
    format rdflib writes."""
    if fmt == "tsv":  # rdflib has no TSV results serialiser
        return _tsv(result)
    with unwritable(fmt):  # a CONSTRUCT's graph in RDF/XML: a predicate no XML name ends
        return result.serialize(format=fmt, encoding="utf-8") or b""


def _tsv(result: Result) -> bytes:
    """W3C SPARQL 1.1 TSV results of a SELECT: a header of ?vars, then terms in Turtle syntax."""
    names = list(result.vars or [])
    lines = ["\t".join(f"?{n}" for n in names)]
    for row in result.bindings:
        lines.append("\t".join(row[n].n3() if row.get(n) is not None else "" for n in names))
    return ("\n".join(lines) + "\n").encode("utf-8")


def to_json(result: Result, query: str) -> dict[str, Any]:
    """W3C SPARQL 1.1 JSON results with the query added, as knowledge_core returns them."""
    if result.type in ("SELECT", "ASK"):
        data: dict[str, Any] = json.loads(result.serialize(format="json") or b"{}")
    else:
        graph = result.graph
        if graph is None:
            raise KbError("the SPARQL query produced no graph")
        data = {"head": {}, "graph": json.loads(graph.serialize(format="json-ld"))}
    data["query"] = query
    return data
