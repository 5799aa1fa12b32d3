"""Pattern queries of a read replica translated to SPARQL: one request per model and call.

A model's closure is the merge of its asserted and inferred graphs (kb.sparqlstore.layout), so a ``find`` is
one ``SELECT DISTINCT`` over ``FROM <asserted> FROM <inferred>`` with the compiled patterns as
its basic graph pattern, and ``exist`` (or a ground ``find``) is one ``ASK``. Rows holding a
blank node are dropped by the store (a FILTER on the projected variables), as kb.query drops them,
so that ``LIMIT max_rows + 1`` counts the same rows as the in-process KB. Every term is written
by kb.sparqlstore.text from rdflib terms.
"""

from __future__ import annotations

from dataclasses import dataclass

from rdflib import Literal, URIRef, Variable

from kb.deadline import Deadline
from kb.errors import KbError
from kb.models import DEFAULT_MODEL
from kb.query import Query, Row
from kb.sparqlstore import text
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.layout import GENID, MODEL, REVISION, Layout
from kb.terms import Node, Triple

_S, _P, _O = Variable("s"), Variable("p"), Variable("o")
_GENID = Literal(GENID)


@dataclass(frozen=True)
class Graphs:
    """The two graphs of one model: their merge is the model's closure."""

    model: str
    asserted: URIRef
    inferred: URIRef

    @classmethod
    def of(cls, layout: Layout, model: str) -> Graphs:
        return cls(model, *layout.graphs(model))

    def closure(self, inferred: bool = True) -> tuple[URIRef, ...]:
        """The graphs to merge: both, or only the asserted one."""
        return (self.asserted, self.inferred) if inferred else (self.asserted,)


@dataclass(frozen=True)
class Meta:
    """What the meta graph says: the writer's revision (None for an empty dataset) and models."""

    revision: int | None
    models: tuple[str, ...]


def not_skolem(var: Variable) -> str:
    """A FILTER that drops solutions binding ``var`` to a (skolemised) blank node."""
    return f"FILTER (!(isIRI({text.term(var)}) && STRSTARTS(STR({text.term(var)}), {text.term(_GENID)})))"


def select_text(query: Query, graphs: Graphs, limit: int | None = None) -> str:
    projection = " ".join(text.term(v) for v in query.projection)
    filters = "\n".join(not_skolem(v) for v in query.projection)
    bound = f"\nLIMIT {int(limit)}" if limit is not None else ""
    return (f"SELECT DISTINCT {projection}\n{text.from_clauses(graphs.closure())}\n"
            f"WHERE {{\n{text.block(query.patterns)}\n{filters}\n}}{bound}")


def ask_text(query: Query, graphs: Graphs) -> str:
    return f"ASK\n{text.from_clauses(graphs.closure())}\nWHERE {{\n{text.block(query.patterns)}\n}}"


def meta_text(layout: Layout) -> str:
    root = layout.root
    return (f"SELECT ?r ?m WHERE {{ GRAPH {text.term(layout.meta)} {{\n"
            f"OPTIONAL {{ {text.triple(root, REVISION, Variable('r'))} }}\n"
            f"OPTIONAL {{ {text.triple(root, MODEL, Variable('m'))} }}\n}} }}")


def count_text(graphs: Graphs, inferred: bool) -> str:
    return (f"SELECT (COUNT(*) AS ?n)\n{text.from_clauses(graphs.closure(inferred))}\n"
            f"WHERE {{ {text.triple(_S, _P, _O)} }}")


def triples_text(graphs: Graphs, inferred: bool) -> str:
    return (f"SELECT ?s ?p ?o\n{text.from_clauses(graphs.closure(inferred))}\n"
            f"WHERE {{ {text.triple(_S, _P, _O)} }}")


def asserted_text(triple: Triple, graphs: Graphs) -> str:
    return f"ASK {{ GRAPH {text.term(graphs.asserted)} {{ {text.triple(*triple)} }} }}"


def model_order(names: set[str]) -> tuple[str, ...]:
    """The robot's own model first, then the others by name (the store keeps no creation order)."""
    return tuple(sorted(names, key=lambda n: (n != DEFAULT_MODEL, n)))


class StoreQueries:
    """Runs the pattern queries of one dataset; each method is one request."""

    def __init__(self, endpoint: SparqlEndpoint) -> None:
        self.endpoint = endpoint
        self.layout = endpoint.layout

    def graphs(self, model: str) -> Graphs:
        return Graphs.of(self.layout, model)

    def meta(self) -> Meta:
        revision: int | None = None
        models: set[str] = set()
        for row in self.endpoint.select(meta_text(self.layout)):
            if "r" in row:
                revision = _integer(row["r"])
            if "m" in row:
                models.add(str(row["m"]))
        return Meta(revision, model_order(models))

    def rows(self, query: Query, graphs: Graphs, limit: int | None = None,
             deadline: Deadline | None = None) -> set[Row]:
        if not query.projection:  # a ground query has one empty row when it holds (kb.query.rows)
            return {()} if self.holds(query, graphs, deadline) else set()
        found = self.endpoint.select(select_text(query, graphs, limit), deadline)
        names = [str(v) for v in query.projection]
        return {tuple(row[name] for name in names) for row in found}

    def holds(self, query: Query, graphs: Graphs, deadline: Deadline | None = None) -> bool:
        return self.endpoint.ask(ask_text(query, graphs), deadline)

    def size(self, graphs: Graphs, inferred: bool) -> int:
        rows = self.endpoint.select(count_text(graphs, inferred))
        return _integer(rows[0]["n"]) if rows else 0

    def triples(self, graphs: Graphs, inferred: bool, timeout: float | None = None) -> list[Triple]:
        rows = self.endpoint.select(triples_text(graphs, inferred), timeout=timeout)
        return [(row["s"], row["p"], row["o"]) for row in rows]

    def is_asserted(self, triple: Triple, graphs: Graphs) -> bool:
        return self.endpoint.ask(asserted_text(triple, graphs))


def _integer(node: Node) -> int:
    value = node.toPython() if isinstance(node, Literal) else None
    if isinstance(value, bool) or not isinstance(value, int):
        raise KbError(f"the store holds {node!r} where an integer belongs")
    return value
