"""Reading and writing RDF documents: the default ontology, load(), save() and exports."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from functools import lru_cache
from importlib.resources import files
from io import BytesIO, StringIO
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlparse
from xml.sax import InputSource, SAXParseException
from xml.sax.handler import ContentHandler

from defusedxml import DefusedXmlException
from defusedxml.sax import parse as defused_sax_parse
from rdflib import Dataset, Graph, URIRef
from rdflib.exceptions import ParserError
from rdflib.store import Store

from kb import ntriples
from kb.errors import KbError, NotSerialisable
from kb.formats import EXPORTS, Syntax, export_format, format_of_path, rdf_format
from kb.terms import ORO, PREFIXES, Triple
from kb.unicode import check_terms

DEFAULT_ONTOLOGY = "oro.ttl"
# Export formats by name, with their media types.
FORMATS = {fmt.name: fmt.media_type for fmt in EXPORTS}
# What rdflib's parsers raise on malformed input (the Turtle parser even raises IndexError).
_PARSE_ERRORS: tuple[type[BaseException], ...] = (
    SyntaxError, ValueError, SAXParseException, KeyError, IndexError, ParserError,
)


@lru_cache(maxsize=1)
def default_ontology() -> tuple[Triple, ...]:
    """The triples of situated's ORO-compatible ontology, parsed once per process."""
    data = (files("ontologies") / DEFAULT_ONTOLOGY).read_text(encoding="utf-8")
    return parse_data(data, "turtle", source=DEFAULT_ONTOLOGY)


def parse_data(data: str | bytes, fmt: str, source: str = "data") -> tuple[Triple, ...]:
    """Parse a document; relative IRIs resolve against the ORO namespace, as upstream. ``fmt`` is
    any name of a format (kb.formats); what its syntax could make rdflib fetch or expand is
    refused first, and a document of named graphs is merged into one set of triples."""
    rdf = rdf_format(fmt)
    fmt = rdf.name
    _REFUSALS[rdf.syntax](data, source)
    if fmt == "nt" and (fast := ntriples.parse(data, source)) is not None:
        return fast
    if rdf.quads:
        graph: Graph = Dataset(default_union=True)
    else:
        graph = Graph(store=_Collected()) if fmt in _PLAIN_PARSERS else Graph()
    try:
        graph.parse(data=data, format=fmt, publicID=ORO)
    except _PARSE_ERRORS as exc:
        raise KbError(f"cannot parse {source} as {fmt}: {exc}") from exc
    except RecursionError:  # rdflib's parsers recurse on nested lists and blank nodes
        raise KbError(f"cannot parse {source} as {fmt}: it is nested too deeply") from None
    except Exception as exc:
        # rdflib's parsers raise bare Exception (e.g. "Unknown namespace prefix"); anything
        # more specific than that is a bug and propagates.
        if type(exc) is not Exception:
            raise
        raise KbError(f"cannot parse {source} as {fmt}: {exc}") from exc
    triples = tuple(graph.triples((None, None, None)))
    for triple in triples:
        check_terms(triple, f"a term of {source}")
    return triples  # type: ignore[return-value]  # rdflib yields (Node, Node, Node) triples


#: Formats whose rdflib parser only adds triples to a plain graph (JSON-LD's and N3's need a
#: context-aware store).
_PLAIN_PARSERS = frozenset({"turtle", "xml", "nt"})


class _Collected(Store):
    """Where an rdflib parser puts a document's triples: a set, in document order. A Graph's
    default store indexes every triple three ways for lookups nobody makes here (half of a
    Turtle document's parse). Lookups still work (a parser may read back what it wrote)."""

    def __init__(self) -> None:
        super().__init__()
        self._found: dict[Triple, None] = {}
        self._ns: dict[str, URIRef] = {}

    def add(self, triple: Any, context: Any, quoted: bool = False) -> None:
        self._found[triple] = None

    def remove(self, triple: Any, context: Any = None) -> None:
        for found in list(self._matches(triple)):
            del self._found[found]

    def triples(self, triple_pattern: Any, context: Any = None) -> Iterator[tuple[Triple, Iterator[Any]]]:
        for found in list(self._matches(triple_pattern)):
            yield found, iter(())

    def _matches(self, pattern: Any) -> Iterator[Triple]:
        s, p, o = pattern
        return (t for t in self._found
                if (s is None or t[0] == s) and (p is None or t[1] == p) and (o is None or t[2] == o))

    def __len__(self, context: Any = None) -> int:
        return len(self._found)

    def bind(self, prefix: str, namespace: URIRef, override: bool = True) -> None:
        self._ns[prefix] = namespace

    def namespace(self, prefix: str) -> URIRef | None:
        return self._ns.get(prefix)

    def prefix(self, namespace: URIRef) -> str | None:
        return next((p for p, ns in self._ns.items() if ns == namespace), None)

    def namespaces(self) -> Iterator[tuple[str, URIRef]]:
        yield from self._ns.items()


def _check_xml(data: str | bytes, source: str) -> None:
    """Refuse a DTD before rdflib's expat parser sees it: its entity declarations expand (a
    billion-laughs document of 1 kB costs minutes of CPU) and may name local files. Without a DTD
    no entity can be declared, so none can be expanded or fetched."""
    document = InputSource(source)
    if isinstance(data, str):
        document.setCharacterStream(StringIO(data))
    else:
        document.setByteStream(BytesIO(data))
    try:
        defused_sax_parse(document, ContentHandler(), forbid_dtd=True, forbid_entities=True,
                          forbid_external=True)
    except DefusedXmlException as exc:
        raise KbError(f"cannot load {source}: XML documents with a DTD or entity declarations are "
                      f"refused ({type(exc).__name__})") from None
    except SAXParseException as exc:
        raise KbError(f"cannot parse {source} as xml: {exc}") from None


def _check_json_ld(data: str | bytes, source: str) -> None:
    """Refuse what rdflib's JSON-LD parser would crash on or fetch: a document that is not an
    object or array, and remote contexts (rdflib would download them: nothing is fetched from a
    network here, and an uploaded document must not make the service call other hosts)."""
    try:
        document = json.loads(data)
    except (ValueError, RecursionError) as exc:
        raise KbError(f"cannot parse {source} as json-ld: {exc}") from None
    if not isinstance(document, dict | list):
        raise KbError(f"cannot parse {source} as json-ld: the document must be a JSON object or array")
    stack: list[Any] = [document]
    while stack:
        node = stack.pop()
        if isinstance(node, dict):
            context = node.get("@context")
            contexts = context if isinstance(context, list) else [context]
            if any(isinstance(c, str) or (isinstance(c, dict) and "@import" in c) for c in contexts):
                raise KbError(f"cannot load {source}: it names a remote JSON-LD @context, which would be "
                              "fetched from the network; inline the context instead")
            stack.extend(node.values())
        elif isinstance(node, list):
            stack.extend(node)


def parse_location(uri: str) -> tuple[Triple, ...]:
    """Parse a local file given as a path or a file:// URI. Nothing is fetched from a network."""
    data, fmt, source = read_location(uri)
    return parse_data(data, fmt, source=source)


def read_location(uri: str) -> tuple[bytes, str, str]:
    """The bytes of a local file given as a path or a file:// URI, its RDF format (guessed from
    the name, Turtle by default) and its name for messages."""
    parsed = urlparse(uri)
    if parsed.scheme in ("http", "https", "ftp"):
        raise KbError(f"cannot load {uri!r}: situated loads local files only (offline by default)")
    path = Path(unquote(parsed.path) if parsed.scheme == "file" else uri)
    if not path.is_file():
        raise KbError(f"cannot load {uri!r}: no such file")
    return path.read_bytes(), format_of_path(path).name, str(path)


def to_graph(triples: Iterable[Triple]) -> Graph:
    graph = Graph(identifier=URIRef(ORO + "export"))
    for prefix, ns in PREFIXES.items():
        graph.bind(prefix or "oro", ns, override=True)
    for triple in triples:
        graph.add(triple)
    return graph


def serialize(triples: Iterable[Triple], fmt: str) -> bytes:
    name = export_format(fmt).name
    with unwritable(name):
        return to_graph(triples).serialize(format=name, encoding="utf-8")


@contextmanager
def unwritable(fmt: str) -> Iterator[None]:
    """rdflib's serialisers raise ValueError for a graph the format cannot write (RDF/XML: a
    predicate no XML name ends); said as ``NotSerialisable``, naming the format."""
    try:
        yield
    except ValueError as exc:
        raise NotSerialisable(f"{fmt} cannot write this graph ({exc}); ask for another format, e.g. "
                              "text/turtle, application/n-triples or application/ld+json") from None


def _nothing_to_refuse(data: str | bytes, source: str) -> None:
    return None


# What each syntax must be checked for before rdflib parses it.
_REFUSALS: dict[Syntax, Callable[[str | bytes, str], None]] = {
    Syntax.TEXT: _nothing_to_refuse,
    Syntax.XML: _check_xml,
    Syntax.JSON_LD: _check_json_ld,
}
