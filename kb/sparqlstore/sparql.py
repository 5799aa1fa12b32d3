"""Read-only SPARQL of a read replica: checked here as in-process, answered by the store.

The query is checked by kb.sparql (read-only; no SERVICE, FROM or GRAPH: one model per call) and
sent unchanged after a prologue declaring the base and the knowledge_core prefixes it does not
declare itself (so ``oro:`` and ``:`` work undeclared, as in-process). The model's two graphs are
the query's default graph (SPARQL Protocol ``default-graph-uri``). The answer is read back into
an rdflib ``Result`` with blank nodes restored, so kb.sparql.to_json and rdflib's serialisers
give the in-process shapes.
"""

from __future__ import annotations

import io
from typing import Any

from rdflib import Graph, URIRef
from rdflib.query import Result

from kb.deadline import Deadline
from kb.sparql import check_query, to_json
from kb.sparqlbudget import check_size
from kb.sparqlstore import text
from kb.sparqlstore.endpoint import RESULTS_JSON, SparqlEndpoint
from kb.sparqlstore.layout import unskolem
from kb.sparqlstore.query import Graphs
from kb.terms import ORO, PREFIXES

N_TRIPLES = "application/n-triples"


def full_text(query: str, declared: frozenset[str]) -> str:
    """The query after the declarations it relies on without writing them."""
    missing = [(prefix, URIRef(ns)) for prefix, ns in PREFIXES.items() if prefix not in declared]
    return f"{text.prologue(URIRef(ORO), missing)}\n{query}"


def run(endpoint: SparqlEndpoint, query: str, graphs: Graphs, deadline: Deadline | None = None,
        max_rows: int | None = None) -> Result:
    """One request: the query's result, as rdflib would have given it in-process. The deadline
    bounds the request and the reading of the answer; the row cap is checked on the answer."""
    checked = check_query(query, deadline)
    default_graphs = [str(g) for g in graphs.closure()]
    body = full_text(query, checked.declared)
    if checked.form in ("SELECT", "ASK"):
        _, answer = endpoint.raw(body, RESULTS_JSON, default_graphs, deadline)
        result = _restore_bindings(Result.parse(io.BytesIO(answer), format="json"))
    else:
        _, answer = endpoint.raw(body, N_TRIPLES, default_graphs, deadline)
        parsed = Graph().parse(data=answer, format="nt")
        graph = Graph()
        for s, p, o in parsed:
            graph.add((_restore(s), p, _restore(o)))
        result = Result(checked.form)
        result.graph = graph
    check_size(result, max_rows)
    return result


def answer(endpoint: SparqlEndpoint, query: str, graphs: Graphs, deadline: Deadline | None = None,
           max_rows: int | None = None) -> dict[str, Any]:
    return to_json(run(endpoint, query, graphs, deadline, max_rows), query)


def _restore(node: Any) -> Any:
    return unskolem(str(node)) if isinstance(node, URIRef) else node


def _restore_bindings(parsed: Result) -> Result:
    if parsed.type != "SELECT":
        return parsed
    result = Result("SELECT")
    result.vars = parsed.vars
    result.bindings = [{var: _restore(value) for var, value in row.items()} for row in parsed.bindings]
    return result

