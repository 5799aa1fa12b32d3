"""RDF formats by any of their names (kb.formats): every alias of every format parses its format,
and no name of a format lets parsing reach the network (issue 19, item 6) or expand XML entities
(item 10)."""

from __future__ import annotations

import socket
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import rdflib.parser
from rdflib import Dataset, Graph, Literal, URIRef

from kb import KB, KbError
from kb.formats import TABLE, all_names, export_format, format_of_path, rdf_format
from kb.rdfio import parse_data

ORO = "http://kb.openrobots.org#"
# The names each format must be accepted under (rdflib's plugin names, media types, extensions).
NAMES = {
    "turtle": {"turtle", "ttl", "text/turtle", "application/x-turtle", "application/turtle"},
    "xml": {"xml", "rdf", "owl", "rdfxml", "rdf/xml", "rdf+xml", "application/rdf+xml"},
    "json-ld": {"json-ld", "jsonld", "json", "application/ld+json", "application/json"},
    "nt": {"nt", "ntriples", "n-triples", "nt11", "application/n-triples"},
    "n3": {"n3", "text/n3", "text/rdf+n3"},
    "trig": {"trig", "application/trig"},
    "nquads": {"nquads", "nq", "n-quads", "application/n-quads"},
    "trix": {"trix", "application/trix"},
}
ALIASES = sorted((fmt, name) for fmt, names in NAMES.items() for name in names)
TRIPLES = {(URIRef(ORO + "cup_1"), URIRef(ORO + "isOn"), URIRef(ORO + "table_1")),
           (URIRef(ORO + "cup_1"), URIRef("http://www.w3.org/2000/01/rdf-schema#label"), Literal("cup", lang="en"))}
QUADS = {"trig", "nquads", "trix"}


def document(fmt: str) -> bytes:
    """TRIPLES in ``fmt``; quad formats hold one in a named graph and one in the default graph."""
    if fmt in QUADS:
        dataset = Dataset()
        first, second = sorted(TRIPLES)
        dataset.graph(URIRef("http://example.org/g")).add(first)
        dataset.add(second)
        return dataset.serialize(format=fmt, encoding="utf-8")
    graph = Graph()
    for triple in TRIPLES:
        graph.add(triple)
    return graph.serialize(format=fmt, encoding="utf-8")


def test_the_table_names_exactly_the_tested_aliases() -> None:
    assert {fmt.name: set(all_names(fmt)) for fmt in TABLE} == NAMES


@pytest.mark.parametrize(("fmt", "name"), ALIASES)
def test_every_alias_of_every_format_parses_that_format(fmt: str, name: str) -> None:
    data = document(fmt)
    assert set(parse_data(data, name)) == TRIPLES
    for variant in (name.upper(), f" {name} ", f"{name}; charset=utf-8"):
        assert rdf_format(variant).name == fmt
    with KB(ontology=False) as kb:
        kb.load_data(data, name, models=["m"])
        assert kb["cup_1 isOn ?t"] == [] and kb.find("cup_1 isOn ?t", models=["m"]) == [{"t": "table_1"}]


def test_unknown_formats_are_refused_with_the_list() -> None:
    for name in ("pdf", "hext", "html", "", "text/plain"):
        with pytest.raises(KbError, match=r"unknown RDF format.*turtle, xml, json-ld"):
            parse_data("<a> <b> <c> .", name)


def test_files_are_read_in_the_format_of_their_extension(tmp_path: Path) -> None:
    for fmt, names in NAMES.items():
        for name in names:
            if "/" in name:
                continue
            assert format_of_path(tmp_path / f"doc.{name}").name == fmt
    assert format_of_path("scene.txt").name == "turtle" and format_of_path("facts").name == "turtle"


def test_exports_accept_any_name_of_their_format() -> None:
    assert export_format("application/ld+json").name == "json-ld"
    with KB(ontology=False) as kb:
        kb += ["cup_1 isOn table_1"]
        assert kb.export("application/rdf+xml") == kb.export("xml")
        with pytest.raises(KbError, match="cannot export as 'trig'"):
            kb.export("trig")


# --- nothing is fetched, whatever the format is called -----------------------------------------


@pytest.fixture
def no_network(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[Any]]:
    """Every way rdflib could open a URL, and every socket connection, recorded and refused."""
    attempts: list[Any] = []

    def refuse(*args: Any, **kwargs: Any) -> Any:
        attempts.append(args)
        raise OSError("network access attempted while parsing")

    monkeypatch.setattr(rdflib.parser, "_urlopen", refuse)
    monkeypatch.setattr(urllib.request, "urlopen", refuse)
    monkeypatch.setattr(socket.socket, "connect", refuse)
    monkeypatch.setattr(socket, "create_connection", refuse)
    yield attempts


REMOTE_CONTEXTS = [
    '{"@context": "http://203.0.113.7/context.jsonld", "@id": "http://example.org/a", "name": "x"}',
    '{"@context": [{"@vocab": "http://example.org/"}, "http://203.0.113.7/c2"], "@id": "http://example.org/b"}',
    '{"@graph": [{"@context": {"@import": "http://203.0.113.7/c3"}, "@id": "http://example.org/c"}]}',
    '{"@context": {"p": {"@id": "http://example.org/p", "@context": "http://203.0.113.7/c4"}}, "p": {"q": 1}}',
]


@pytest.mark.parametrize("name", sorted(NAMES["json-ld"]))
@pytest.mark.parametrize("doc", REMOTE_CONTEXTS)
def test_a_remote_json_ld_context_is_refused_under_every_name(
        name: str, doc: str, no_network: list[Any]) -> None:
    with KB(ontology=False) as kb:
        with pytest.raises(KbError, match="remote JSON-LD @context"):
            kb.load_data(doc, name)
        assert kb.revision == 0
    assert no_network == []


EXTERNAL = ('<?xml version="1.0"?><!DOCTYPE r [<!ENTITY e SYSTEM "http://203.0.113.7/x">]>'
            '<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:o="http://kb.openrobots.org#">'
            '<rdf:Description rdf:about="http://kb.openrobots.org#a"><o:p>&e;</o:p></rdf:Description></rdf:RDF>')


@pytest.mark.parametrize("name", sorted(NAMES["xml"] | NAMES["trix"]))
def test_an_external_xml_entity_is_refused_under_every_name(name: str, no_network: list[Any]) -> None:
    with pytest.raises(KbError, match="DTD"):
        parse_data(EXTERNAL, name)
    assert no_network == []


# --- entity expansion (item 10) ------------------------------------------------------------------

RDF_BODY = ('<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:o="http://kb.openrobots.org#">'
            '<rdf:Description rdf:about="http://kb.openrobots.org#a"><o:p>&lol{n};</o:p></rdf:Description>'
            '</rdf:RDF>')
TRIX_BODY = ('<TriX xmlns="http://www.w3.org/2004/03/trix/trix-1/"><graph><triple>'
             '<uri>http://kb.openrobots.org#a</uri><uri>http://kb.openrobots.org#p</uri>'
             '<plainLiteral>&lol{n};</plainLiteral></triple></graph></TriX>')


def entity_bomb(root: str, body: str, levels: int) -> str:
    """A document whose one entity expands to 10**levels 'lol's (levels=9: billion laughs, < 1 kB)."""
    entities = ['<!ENTITY lol0 "lol">'] + [
        f'<!ENTITY lol{i} "{("&lol" + str(i - 1) + ";") * 10}">' for i in range(1, levels + 1)]
    return f'<?xml version="1.0"?><!DOCTYPE {root} [{"".join(entities)}]>' + body.format(n=levels)


@pytest.mark.parametrize("levels", [3, 9], ids=["small-bomb", "billion-laughs"])
@pytest.mark.parametrize(("fmt", "root", "body"), [("xml", "rdf:RDF", RDF_BODY), ("trix", "TriX", TRIX_BODY)])
def test_xml_entity_declarations_are_refused_before_parsing(fmt: str, root: str, body: str, levels: int) -> None:
    bomb = entity_bomb(root, body, levels)
    assert len(bomb) < 1100
    with KB(ontology=False) as kb:
        with pytest.raises(KbError, match="DTD or entity declarations are refused"):
            kb.load_data(bomb, fmt)
        with pytest.raises(KbError, match="DTD or entity declarations are refused"):
            kb.load_data(bomb.encode(), fmt)
        assert kb.revision == 0
