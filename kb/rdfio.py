"""Reading and writing RDF documents: the default ontology, load(), save() and exports."""

from __future__ import annotations

from collections.abc import Iterable
from functools import lru_cache
from importlib.resources import files
from pathlib import Path
from urllib.parse import unquote, urlparse
from xml.sax import SAXParseException

from rdflib import Graph, URIRef, plugin
from rdflib.exceptions import ParserError
from rdflib.parser import Parser
from rdflib.plugin import PluginException
from rdflib.util import guess_format

from kb.errors import KbError
from kb.terms import ORO, PREFIXES, Triple

DEFAULT_ONTOLOGY = "oro.ttl"
# Export formats by name, with their media types.
FORMATS = {
    "turtle": "text/turtle",
    "nt": "application/n-triples",
    "json-ld": "application/ld+json",
    "xml": "application/rdf+xml",
}
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
    """Parse a document; relative IRIs resolve against the ORO namespace, as upstream."""
    graph = Graph()
    try:
        plugin.get(fmt, Parser)
    except PluginException:
        raise KbError(f"unknown RDF format {fmt!r}; use turtle, xml, json-ld, nt, n3 or trig") from None
    try:
        graph.parse(data=data, format=fmt, publicID=ORO)
    except _PARSE_ERRORS as exc:
        raise KbError(f"cannot parse {source} as {fmt}: {exc}") from exc
    except Exception as exc:
        # rdflib's parsers raise bare Exception (e.g. "Unknown namespace prefix"); anything
        # more specific than that is a bug and propagates.
        if type(exc) is not Exception:
            raise
        raise KbError(f"cannot parse {source} as {fmt}: {exc}") from exc
    return tuple(graph)  # type: ignore[arg-type]  # rdflib yields (Node, Node, Node) triples


def parse_location(uri: str) -> tuple[Triple, ...]:
    """Parse a local file given as a path or a file:// URI. Nothing is fetched from a network."""
    parsed = urlparse(uri)
    if parsed.scheme in ("http", "https", "ftp"):
        raise KbError(f"cannot load {uri!r}: situated loads local files only (offline by default)")
    path = Path(unquote(parsed.path) if parsed.scheme == "file" else uri)
    if not path.is_file():
        raise KbError(f"cannot load {uri!r}: no such file")
    fmt = guess_format(str(path)) or "turtle"
    return parse_data(path.read_bytes(), fmt, source=str(path))


def to_graph(triples: Iterable[Triple]) -> Graph:
    graph = Graph(identifier=URIRef(ORO + "export"))
    for prefix, ns in PREFIXES.items():
        graph.bind(prefix or "oro", ns, override=True)
    for triple in triples:
        graph.add(triple)
    return graph


def serialize(triples: Iterable[Triple], fmt: str) -> bytes:
    if fmt not in FORMATS:
        raise KbError(f"unknown export format {fmt!r}; use one of {sorted(FORMATS)}")
    return to_graph(triples).serialize(format=fmt, encoding="utf-8")
