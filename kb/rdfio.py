"""Reading and writing RDF documents: the default ontology, load(), save() and exports."""

from __future__ import annotations

import json
from collections.abc import Iterable
from functools import lru_cache
from importlib.resources import files
from pathlib import Path
from typing import Any
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
    if fmt == "json-ld":
        _check_json_ld(data, source)
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
    return tuple(graph)  # type: ignore[arg-type]  # rdflib yields (Node, Node, Node) triples


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
    return path.read_bytes(), guess_format(str(path)) or "turtle", str(path)


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
