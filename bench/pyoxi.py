"""The pyoxigraph baseline of `situated bench kb`: the same triples in an in-memory Oxigraph store.

pyoxigraph (the test extra) is a Rust triple store without reasoning: it is given the triples the
KB holds, asserted or materialised, so its figures are what storing and querying them costs in a
fast native store. Without pyoxigraph the benchmark still runs and says, in each baseline cell and
once on stderr, that the column is missing and how to get it.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterable, Sequence
from types import ModuleType
from typing import Any

from rdflib import BNode, Literal, URIRef

from kb.terms import ORO, PREFIXES, Node, Triple

MISSING = "pyoxigraph: not installed (pip install -e '.[test]')"


def module() -> ModuleType | None:
    """pyoxigraph, or None (then the benchmark says so once on stderr)."""
    try:
        import pyoxigraph
    except ImportError:
        return None
    return pyoxigraph


def warn_if_missing() -> bool:
    """True when pyoxigraph is there; else a notice on stderr (the baseline column is empty)."""
    if module() is not None:
        return True
    print("situated bench kb: pyoxigraph is not installed, so its baseline column is empty; it is in "
          "the test extra: pip install -e '.[test]'", file=sys.stderr)
    return False


class Terms:
    """rdflib terms to pyoxigraph terms, each converted once."""

    def __init__(self, ox: ModuleType) -> None:
        self._ox = ox
        self._made: dict[Node, Any] = {}

    def term(self, node: Node) -> Any:
        made = self._made.get(node)
        if made is None:
            made = self._made[node] = self._convert(node)
        return made

    def _convert(self, node: Node) -> Any:
        ox = self._ox
        if isinstance(node, URIRef):
            return ox.NamedNode(str(node))
        if isinstance(node, BNode):
            return ox.BlankNode(str(node))
        if isinstance(node, Literal):
            if node.language:
                return ox.Literal(str(node), language=node.language)
            if node.datatype is not None:
                return ox.Literal(str(node), datatype=ox.NamedNode(str(node.datatype)))
            return ox.Literal(str(node))
        raise TypeError(f"not an RDF term: {node!r}")

    def quad(self, triple: Triple) -> Any:
        s, p, o = triple
        return self._ox.Quad(self.term(s), self.term(p), self.term(o))


def store_of(triples: Iterable[Triple]) -> tuple[Any, Terms]:
    """An in-memory store holding ``triples`` (no reasoning), and the converter it was filled with."""
    ox = module()
    if ox is None:
        raise RuntimeError(MISSING)
    terms = Terms(ox)
    store = ox.Store()
    store.extend(terms.quad(t) for t in triples)
    return store, terms


def load_seconds(document: bytes) -> tuple[float, int]:
    """Seconds to load an N-Triples document into a new store, and how many triples it holds."""
    ox = module()
    if ox is None:
        raise RuntimeError(MISSING)
    start = time.perf_counter()
    store = ox.Store()
    store.load(document, ox.RdfFormat.N_TRIPLES)
    return time.perf_counter() - start, len(store)


def select(store: Any, query: str, names: Sequence[str]) -> list[tuple[str, ...]]:
    """A SELECT's rows as tuples of the values' text (what a caller of the KB gets, as strings)."""
    prefixes = {prefix or "": ns for prefix, ns in PREFIXES.items() if prefix != "oro"}
    return [tuple(solution[name].value for name in names)
            for solution in store.query(query, base_iri=ORO, prefixes=prefixes)]


def apply(store: Any, terms: Terms, add: Sequence[Triple], remove: Sequence[Triple]) -> None:
    """A perception tick without reasoning: the quads out, then the new ones in."""
    for triple in remove:
        store.remove(terms.quad(triple))
    for triple in add:
        store.add(terms.quad(triple))
