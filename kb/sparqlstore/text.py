"""SPARQL text from rdflib terms, for the requests sent to a SPARQL store.

Every piece of a request is written from a typed term (``URIRef``, ``Literal``, ``BNode``,
``Variable``), never from a caller's string: IRIs are checked against the IRIREF grammar,
literals are escaped here, variable names are checked, so no term can end the IRI or the
literal it is written in and inject anything. Blank nodes become skolem IRIs (kb.sparqlstore.layout).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence

from rdflib import BNode, Literal, URIRef, Variable

from kb.errors import KbError
from kb.sparqlstore.layout import skolem
from kb.terms import Node, Term

# SPARQL 1.1 IRIREF: no control characters, space, <>"{}|^`\.
_BAD_IRI = re.compile(r'[\x00-\x20<>"{}|^`\\]')
_VARNAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_PREFIX = re.compile(r"(?:[A-Za-z][A-Za-z0-9_\-]*)?")
_LANGUAGE = re.compile(r"[A-Za-z]+(?:-[A-Za-z0-9]+)*")
_ESCAPES = str.maketrans({"\\": "\\\\", '"': '\\"', "\n": "\\n", "\r": "\\r", "\t": "\\t",
                          "\b": "\\b", "\f": "\\f"})


def term(node: Term) -> str:
    """One term as SPARQL text."""
    if isinstance(node, BNode):
        node = skolem(node)
    if isinstance(node, URIRef):
        if _BAD_IRI.search(node):
            raise KbError(f"{str(node)!r} is not a valid IRI: it holds a space, a control character "
                          "or one of <>\"{}|^`\\")
        return f"<{node}>"
    if isinstance(node, Literal):
        return _literal(node)
    if isinstance(node, Variable):
        if not _VARNAME.fullmatch(str(node)):
            raise KbError(f"{str(node)!r} is not a valid variable name")
        return f"?{node}"
    raise KbError(f"cannot write {node!r} in SPARQL")


def _literal(node: Literal) -> str:
    """Every character that could end or bend the string is escaped (tabs too: some parsers
    expand them)."""
    text = '"' + str(node).translate(_ESCAPES) + '"'
    if node.language:
        if not _LANGUAGE.fullmatch(node.language):
            raise KbError(f"{node.language!r} is not a valid language tag")
        return f"{text}@{node.language}"
    if node.datatype is not None:
        return f"{text}^^{term(URIRef(node.datatype))}"
    return text


def triple(s: Term, p: Term, o: Term) -> str:
    return f"{term(s)} {term(p)} {term(o)} ."


def block(triples: Iterable[Sequence[Term]]) -> str:
    """Triples (or patterns) as the lines of a group graph pattern."""
    return "\n".join(triple(*t) for t in triples)


def graph_data(graph: URIRef, triples: Iterable[Sequence[Node]]) -> str:
    """``GRAPH <g> { ... }`` for INSERT DATA / DELETE DATA; empty text when there is nothing."""
    body = block(triples)
    return f"GRAPH {term(graph)} {{\n{body}\n}}" if body else ""


def values(var: Variable, nodes: Iterable[Node]) -> str:
    """``VALUES ?v { ... }``: binds a variable to given terms (one query for many terms)."""
    return f"VALUES {term(var)} {{ {' '.join(term(n) for n in nodes)} }}"


def from_clauses(graphs: Iterable[URIRef]) -> str:
    """``FROM <g>`` lines: the query's default graph is the merge of these graphs."""
    return "\n".join(f"FROM {term(g)}" for g in graphs)


def prologue(base: URIRef, prefixes: Iterable[tuple[str, URIRef]]) -> str:
    """``BASE`` and ``PREFIX`` declarations (a query's own later declarations override them)."""
    lines = [f"BASE {term(base)}"]
    for prefix, namespace in prefixes:
        if not _PREFIX.fullmatch(prefix):
            raise KbError(f"{prefix!r} is not a valid prefix name")
        lines.append(f"PREFIX {prefix}: {term(namespace)}")
    return "\n".join(lines)
