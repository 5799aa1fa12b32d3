"""N-Triples read fast: the bulk format of ``load_data``, ``KB.load`` and ``POST /kb/load``.

rdflib's N-Triples parser eats each line term by term in Python and adds every triple to an
rdflib graph (whose own indexes cost more than the KB's): two thirds of a 100k load. Here a line
is one match of one expression built from rdflib's own term expressions, each term made once per
document (so repeated names are one object) with rdflib's own unescaping: the same triples, with
the same blank-node handling (a fresh node per label and document). The expression's parts are
atomic, so a line matches exactly when rdflib's term-by-term reading accepts it. A document with
any line it does not match (a syntax error, or something rarer) is left to rdflib, so errors read
as before.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import TypeVar

from rdflib import BNode, Literal, URIRef
from rdflib.plugins.parsers.ntriples import literal as _LITERAL
from rdflib.plugins.parsers.ntriples import unquote, uriquote
from rdflib.plugins.parsers.ntriples import uriref as _IRI

from kb.terms import Node, Triple
from kb.unicode import check_terms, surrogate_at

K = TypeVar("K")
T = TypeVar("T", URIRef, Literal)

_NODEID = r"_:([A-Za-z0-9_:](?:[-A-Za-z0-9_:\.]*[-A-Za-z0-9_:])?)"
_LITINFO = r"(?:@([a-zA-Z]+(?:-[a-zA-Z0-9]+)*)|\^\^" + _IRI + r")?"
# A line of rdflib's reading (W3CNTriplesParser.parseline): subject, predicate and object eaten
# in turn (atomic groups: no backtracking into an eaten term), then the tail and nothing else.
_LINE = re.compile(
    rf"[ \t]*(?>{_IRI}|{_NODEID})(?>[ \t]+)(?>{_IRI})(?>[ \t]+)"
    rf"(?>{_IRI}|{_NODEID}|(?>{_LITERAL}){_LITINFO})[ \t]*\.[ \t]*(?:#.*)?"
)
_SKIP = re.compile(r"[ \t]*(?:#.*)?")  # a blank or comment line
_LINES = re.compile(r"\r\n|\r|\n")


def parse(data: str | bytes, source: str) -> tuple[Triple, ...] | None:
    """The triples of an N-Triples document, each once; None when a line is not one this reads
    (rdflib then reads the document, and says what is wrong with it)."""
    if isinstance(data, bytes):
        try:
            data = data.decode("utf-8")
        except UnicodeDecodeError:
            return None
    elif surrogate_at(data) is not None:  # rdflib cannot encode it: its message, not ours
        return None
    reader = _Reader(f"a term of {source}")
    found: dict[Triple, None] = {}
    match, skip = _LINE.fullmatch, _SKIP.fullmatch
    for line in _LINES.split(data):
        m = match(line)
        if m is None:
            if skip(line) is None:
                return None
            continue
        found[reader.triple(m.groups())] = None
    return tuple(found)


class _Reader:
    """Terms of one document, each made (and checked for invalid Unicode) once."""

    def __init__(self, what: str) -> None:
        self._what = what
        self._iris: dict[str, URIRef] = {}
        self._literals: dict[tuple[str, str | None, str | None], Literal] = {}
        self._bnodes: dict[str, BNode] = {}

    def triple(self, groups: tuple[str | None, ...]) -> Triple:
        s_iri, s_node, p_iri, o_iri, o_node, lexical, lang, datatype = groups
        assert p_iri is not None  # the expression requires it
        subject = self._iri(s_iri) if s_iri is not None else self._bnode(s_node)
        obj: Node
        if o_iri is not None:
            obj = self._iri(o_iri)
        elif o_node is not None:
            obj = self._bnode(o_node)
        else:
            obj = self._literal(lexical or "", lang, datatype)
        return (subject, self._iri(p_iri), obj)

    def _iri(self, text: str) -> URIRef:
        return self._made(self._iris, text, lambda: URIRef(uriquote(unquote(text))))

    def _bnode(self, label: str | None) -> BNode:
        assert label is not None
        node = self._bnodes.get(label)
        if node is None:
            node = self._bnodes[label] = BNode()
        return node

    def _literal(self, lexical: str, lang: str | None, datatype: str | None) -> Literal:
        return self._made(self._literals, (lexical, lang, datatype), lambda: Literal(
            unquote(lexical), lang or None, self._iri(datatype) if datatype else None))

    def _made(self, cache: dict[K, T], key: K, make: Callable[[], T]) -> T:
        term = cache.get(key)
        if term is None:
            term = cache[key] = make()
            check_terms((term,), self._what)
        return term
