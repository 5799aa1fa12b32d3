"""RDF documents (kb-compat §3.7): the default ontology, load/load_data, save (asserted triples as
RDF/XML to ``path/basename-<model>.rdf``), exports, and clear errors for bad documents.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from rdflib import Graph, Literal, URIRef

from kb import KB, KbError
from kb.errors import NotSerialisable
from kb.rdfio import FORMATS, default_ontology, parse_data, parse_location, serialize

ORO = "http://kb.openrobots.org#"
TURTLE = """
@prefix : <http://kb.openrobots.org#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
:loaded_cup a <https://dbpedia.org/resource/Cup> ; rdfs:label "loaded cup"@en .
<#relative_thing> :isOn :table_1 .
"""


@pytest.fixture
def kb() -> Iterator[KB]:
    with KB() as k:
        yield k


def test_default_ontology_is_parsed_once() -> None:
    triples = default_ontology()
    assert default_ontology() is triples
    assert len(triples) > 1000
    assert (URIRef(ORO + "Human"), URIRef("http://www.w3.org/2000/01/rdf-schema#subClassOf"),
            URIRef(ORO + "EmbodiedAgent")) in triples


def test_parse_data_resolves_relative_iris_against_oro() -> None:
    triples = set(parse_data(TURTLE, "turtle"))
    assert (URIRef(ORO + "relative_thing"), URIRef(ORO + "isOn"), URIRef(ORO + "table_1")) in triples
    assert (URIRef(ORO + "loaded_cup"), URIRef("http://www.w3.org/2000/01/rdf-schema#label"),
            Literal("loaded cup", lang="en")) in triples


@pytest.mark.parametrize(
    ("data", "fmt"),
    [
        ("this is not turtle", "turtle"),
        ("@prefix : <http://x#> . :a :b", "turtle"),
        ("<rdf:RDF", "xml"),
        ("{not json", "json-ld"),
        ("<a> <b> .", "nt"),
        ("ex:a ex:b ex:c .", "turtle"),  # unknown prefix
    ],
)
def test_bad_documents_are_kb_errors(data: str, fmt: str) -> None:
    with pytest.raises(KbError, match=fmt):
        parse_data(data, fmt)


def test_parse_location_refuses_the_network_and_missing_files(tmp_path: Path) -> None:
    with pytest.raises(KbError, match="local"):
        parse_location("http://example.org/onto.ttl")
    with pytest.raises(KbError, match="local"):
        parse_location("https://example.org/onto.owl")
    with pytest.raises(KbError, match="no such file"):
        parse_location(str(tmp_path / "missing.ttl"))


def test_parse_location_guesses_the_format(tmp_path: Path) -> None:
    graph = Graph().parse(data=TURTLE, format="turtle", publicID=ORO)
    suffixes = ((".ttl", "turtle"), (".rdf", "xml"), (".owl", "xml"), (".nt", "nt"), (".jsonld", "json-ld"))
    for suffix, fmt in suffixes:
        path = tmp_path / f"doc{suffix}"
        path.write_bytes(graph.serialize(format=fmt, encoding="utf-8"))
        assert set(parse_location(str(path))) == set(graph)
        assert set(parse_location(path.as_uri())) == set(graph)


@pytest.mark.parametrize("fmt", sorted(FORMATS))
def test_serialize_round_trips(fmt: str) -> None:
    triples = set(parse_data(TURTLE, "turtle"))
    data = serialize(triples, fmt)
    assert isinstance(data, bytes)
    assert set(Graph().parse(data=data, format=fmt)) == triples


def test_serialize_unknown_format() -> None:
    with pytest.raises(KbError, match="format"):
        serialize([], "pdf")


# --- through the KB --------------------------------------------------------------------------


def test_load_data_and_load(kb: KB, tmp_path: Path) -> None:
    kb.load_data(TURTLE)
    assert kb["?x rdf:type dbr:Cup"] == [{"x": "loaded_cup"}]
    assert kb["?x isAt table_1"] == [{"x": "relative_thing"}]  # reasoned like any write
    path = tmp_path / "more.ttl"
    path.write_text("@prefix : <http://kb.openrobots.org#> . :file_cup :isIn :kitchen .")
    kb.load(str(path), models=["bob"])
    assert kb.find("?x isIn kitchen", models=["bob"]) == [{"x": "file_cup"}]
    assert kb.find("?x isIn kitchen") == []


def test_load_errors_write_nothing(kb: KB, tmp_path: Path) -> None:
    before = kb.size()
    with pytest.raises(KbError):
        kb.load_data("@prefix : <http://kb.openrobots.org#> . :a :b :c . :d :e")
    with pytest.raises(KbError):
        kb.load(str(tmp_path / "nope.ttl"))
    assert kb.size() == before


def test_save_writes_asserted_rdf_xml_per_model(kb: KB, tmp_path: Path) -> None:
    kb += ["alfred rdf:type Human", "alfred sees cup_1", 'alfred rdfs:label "Alfred"@en']
    kb.add(["r2 rdf:type Robot"], models=["bob"])
    written = kb.save(tmp_path, "robot", models=["all"])
    assert sorted(Path(p).name for p in written) == ["robot-bob.rdf", "robot-default.rdf"]
    graph = Graph().parse(tmp_path / "robot-default.rdf", format="xml")
    alfred = URIRef(ORO + "alfred")
    assert (alfred, URIRef(ORO + "sees"), URIRef(ORO + "cup_1")) in graph
    # Only asserted triples are saved: alfred's inferred classes are not.
    rdf_type = URIRef("http://www.w3.org/1999/02/22-rdf-syntax-ns#type")
    assert (alfred, rdf_type, URIRef(ORO + "Agent")) not in graph


def test_save_default_basename_and_model(kb: KB, tmp_path: Path) -> None:
    kb += "alfred sees cup_1"
    kb.add("r2 sees cup_1", models=["bob"])
    assert [Path(p).name for p in kb.save(tmp_path)] == ["kb-default.rdf"]
    assert [Path(p).name for p in kb.save(tmp_path, "only", models=["bob"])] == ["only-bob.rdf"]
    graph = Graph().parse(tmp_path / "only-bob.rdf", format="xml")
    assert (URIRef(ORO + "r2"), URIRef(ORO + "sees"), URIRef(ORO + "cup_1")) in graph
    assert (URIRef(ORO + "alfred"), URIRef(ORO + "sees"), URIRef(ORO + "cup_1")) not in graph


def test_save_then_load_round_trip(kb: KB, tmp_path: Path) -> None:
    kb += [
        "alfred rdf:type Human",
        "alfred sees dbr:Table_(furniture)",
        "alfred isIn living-room",
        "alfred age 4.5",
        'alfred rdfs:label "hello, world."',
        'alfred rdfs:label "bonjour"@fr',
        "alfred likes <http://example.org/other#thing>",
    ]
    kb.save(tmp_path)
    with KB(ontology=False) as other:
        other.load(str(tmp_path / "kb-default.rdf"))
        for predicate in ["sees", "isIn", "age", "rdfs:label", "likes"]:
            pattern = f"alfred {predicate} ?x"
            assert other[pattern] == kb[pattern]
        assert other.size(inferred=False) == kb.size(inferred=False)


def test_save_to_a_missing_directory(kb: KB, tmp_path: Path) -> None:
    with pytest.raises(KbError, match="directory"):
        kb.save(tmp_path / "missing")


@pytest.mark.parametrize("fmt", sorted(FORMATS))
def test_export(fmt: str) -> None:
    with KB(ontology=False) as kb:  # a small TBox keeps the serialisers quick
        kb += ["Human rdfs:subClassOf Agent", "alfred rdf:type Human", 'alfred rdfs:label "Alfred"@en']
        kb.add("r2 rdf:type Human", models=["bob"])
        asserted = Graph().parse(data=kb.export(fmt), format=fmt)
        inferred = Graph().parse(data=kb.export(fmt, inferred=True), format=fmt)
        bob = Graph().parse(data=kb.export(fmt, model="bob"), format=fmt)
        alfred = URIRef(ORO + "alfred")
        rdf_type = URIRef("http://www.w3.org/1999/02/22-rdf-syntax-ns#type")
        assert (alfred, rdf_type, URIRef(ORO + "Human")) in asserted
        assert (alfred, rdf_type, URIRef(ORO + "Agent")) not in asserted
        assert (alfred, rdf_type, URIRef(ORO + "Agent")) in inferred
        assert len(asserted) == kb.size(inferred=False) == 3
        assert (URIRef(ORO + "r2"), rdf_type, URIRef(ORO + "Human")) in bob
        assert (alfred, rdf_type, URIRef(ORO + "Human")) not in bob


def test_export_errors(kb: KB) -> None:
    with pytest.raises(KbError, match="format"):
        kb.export("pdf")
    with pytest.raises(KbError, match="nope"):
        kb.export("turtle", model="nope")


def test_kb_with_ontology_files(tmp_path: Path) -> None:
    onto = tmp_path / "mini.ttl"
    onto.write_text(
        "@prefix : <http://kb.openrobots.org#> . @prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"
        ":Cat rdfs:subClassOf :Animal .\n"
    )
    with KB(ontology=[onto]) as k:
        k += "tom rdf:type Cat"
        assert k["?x rdf:type Animal"] == [{"x": "tom"}]
        assert k["?x rdf:type Agent"] == []  # not the default ontology
        k.clear()
        k += "tim rdf:type Cat"
        assert k["?x rdf:type Animal"] == [{"x": "tim"}]  # clear keeps these defaults
    with pytest.raises(KbError):
        KB(ontology=[tmp_path / "missing.ttl"])


@pytest.mark.parametrize("fmt", ["turtle", "xml", "nt"])
def test_documents_read_to_the_triples_an_rdflib_graph_reads(fmt: str) -> None:
    """Turtle and RDF/XML are parsed into a plain collection of triples rather than an indexed
    graph: the same triples, blank nodes and lists included (the whole default ontology here)."""
    from importlib.resources import files

    from rdflib.compare import isomorphic

    from kb.rdfio import DEFAULT_ONTOLOGY

    ontology = Graph()
    ontology.parse(data=(files("ontologies") / DEFAULT_ONTOLOGY).read_text(encoding="utf-8"), format="turtle")
    ontology.parse(data="<http://ex.org/a> <http://ex.org/p> ( 1 [ <http://ex.org/q> \"x\"@en ] ) .",
                   format="turtle")
    document = ontology.serialize(format=fmt)
    expected = Graph()
    expected.parse(data=document, format=fmt, publicID=ORO)
    found = parse_data(document, fmt)
    assert len(found) == len(set(found)) == len(expected)
    got = Graph()
    for triple in found:
        got.add(triple)
    assert isomorphic(got, expected)


@pytest.mark.parametrize("predicate", ["http://x.org/p/", "http://x.org/1", "http://x.org/#"])
def test_a_predicate_no_xml_name_ends_is_not_serialisable_as_rdf_xml_only(predicate: str) -> None:
    """rdflib's ValueError (once a 500 on every RDF/XML export, red team round 3 rerun) is said as
    what it is, and every other format writes the graph."""
    triple = (URIRef("http://x.org/a"), URIRef(predicate), Literal("c"))
    with pytest.raises(NotSerialisable, match=r"^xml cannot write this graph \(.*\); ask for another format"):
        serialize([triple], "xml")
    for fmt in ("turtle", "nt", "json-ld"):
        assert set(parse_data(serialize([triple], fmt), fmt)) == {triple}, fmt
