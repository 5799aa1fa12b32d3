"""The RDF document formats situated reads and writes, and every name a client may give them.

A format enters by many doors (``KB.load_data(fmt=)``, a file's extension, ``POST /kb/load``'s
``?format=`` or ``Content-Type``, a reader forwarding a load to its writer) and under many names
(rdflib's plugin names, media types, extensions). Each is normalised here, once, to one canonical
format, so a safety check keyed on the format (remote JSON-LD contexts, XML DTDs) cannot be walked
around by naming the same parser differently: rdflib registers ``application/ld+json`` as a parser
of its own, and a check that only compared with ``json-ld`` let it fetch remote contexts.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from pathlib import PurePath

from kb.errors import KbError


class Syntax(Enum):
    """What a format's document is written in; the hazards to refuse before parsing follow it."""

    TEXT = "text"  # Turtle and its relatives: nothing is fetched or expanded
    XML = "xml"  # DTDs and entity declarations are refused (entity expansion, external files)
    JSON_LD = "json-ld"  # remote @context and @import are refused (rdflib would download them)


@dataclass(frozen=True)
class RdfFormat:
    """One RDF format: its canonical name (rdflib's plugin name for it), media type and aliases."""

    name: str
    media_type: str
    aliases: tuple[str, ...]
    syntax: Syntax = Syntax.TEXT
    quads: bool = False  # named graphs: parsed as a dataset, merged into the model
    export: bool = False  # offered by KB.export and GET /kb/export


TABLE: tuple[RdfFormat, ...] = (
    RdfFormat("turtle", "text/turtle", ("ttl", "application/x-turtle", "application/turtle"), export=True),
    RdfFormat("xml", "application/rdf+xml", ("rdf", "owl", "rdfxml", "rdf/xml", "rdf+xml"),
              Syntax.XML, export=True),
    RdfFormat("json-ld", "application/ld+json", ("jsonld", "json", "application/json"),
              Syntax.JSON_LD, export=True),
    RdfFormat("nt", "application/n-triples", ("ntriples", "n-triples", "nt11"), export=True),
    RdfFormat("n3", "text/n3", ("text/rdf+n3",)),
    RdfFormat("trig", "application/trig", (), quads=True),
    RdfFormat("nquads", "application/n-quads", ("nq", "n-quads"), quads=True),
    RdfFormat("trix", "application/trix", (), Syntax.XML, quads=True),
)
_BY_NAME: dict[str, RdfFormat] = {
    alias: fmt for fmt in TABLE for alias in (fmt.name, fmt.media_type, *fmt.aliases)
}
EXPORTS: tuple[RdfFormat, ...] = tuple(fmt for fmt in TABLE if fmt.export)


def all_names(fmt: RdfFormat) -> tuple[str, ...]:
    """Every name that means ``fmt``: canonical, media type and aliases."""
    return tuple(name for name, known in _BY_NAME.items() if known is fmt)


def find_format(name: str) -> RdfFormat | None:
    """The format a name means, else None: case and media-type parameters (``; charset=utf-8``)
    are ignored."""
    return _BY_NAME.get(name.split(";", 1)[0].strip().lower())


def rdf_format(name: str) -> RdfFormat:
    """The format a name means; an unknown name is a KbError listing the formats."""
    if not isinstance(name, str):
        raise KbError(f"an RDF format is a name such as 'turtle', got {name!r}")
    found = find_format(name)
    if found is None:
        raise KbError(f"unknown RDF format {name!r}; use one of {', '.join(f.name for f in TABLE)} "
                      "(or their media types)")
    return found


def export_format(name: str) -> RdfFormat:
    """A format ``export`` writes; the others are refused with the list of those it does."""
    found = rdf_format(name)
    if not found.export:
        raise KbError(f"cannot export as {name!r}; use one of {', '.join(f.name for f in EXPORTS)}")
    return found


def format_of_path(path: str | PurePath) -> RdfFormat:
    """A file's format by its extension; Turtle when the extension names none."""
    suffix = PurePath(path).suffix.lstrip(".").lower()
    return _BY_NAME.get(suffix, TABLE[0]) if suffix else TABLE[0]
