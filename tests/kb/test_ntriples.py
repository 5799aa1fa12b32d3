"""``kb.ntriples``: N-Triples read fast, to exactly the triples rdflib's parser reads, and every
document it does not read is left to rdflib (so an error reads as before)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rdflib import BNode, Graph, Literal, URIRef
from rdflib.compare import isomorphic

from kb import KB, KbError, ntriples
from kb.rdfio import parse_data
from kb.terms import Triple
from kb.unicode import carried

DOCUMENT = "\n".join([
    "# a comment line",
    "<http://ex.org/a> <http://ex.org/p> <http://ex.org/b> .",
    "<http://ex.org/a>\t<http://ex.org/p>  \"plain\" . # a trailing comment",
    '<http://ex.org/a> <http://ex.org/p> "tab\\there \\"quoted\\" \\u00e9 \\U0001F600"@en-GB .',
    '<http://ex.org/a> <http://ex.org/p> "42"^^<http://www.w3.org/2001/XMLSchema#integer>.',
    '<http://ex.org/a> <http://ex.org/p> "042"^^<http://www.w3.org/2001/XMLSchema#integer> .',
    "_:x <http://ex.org/p> _:y .",
    "_:y <http://ex.org/p> _:x .",
    "<http://ex.org/a> <http://ex.org/p> <http://ex.org/b> .",  # twice: one triple
    "   ",
    "<http://ex.org/\\u00e9> <http://ex.org/p> <urn:x:y> .",
    "<http://ex.org/a> <http://ex.org/p> \"\" .",
]) + "\r\n<http://ex.org/c> <http://ex.org/p> <http://ex.org/d> .\r<http://ex.org/e> <http://ex.org/p> <http://ex.org/f> ."


def rdflib_reads(data: str | bytes) -> Graph:
    graph = Graph()
    graph.parse(data=data, format="nt")
    return graph


def graph_of(triples: tuple[Triple, ...]) -> Graph:
    graph = Graph()
    for triple in triples:
        graph.add(triple)
    return graph


def test_a_document_reads_as_rdflib_reads_it() -> None:
    found = ntriples.parse(DOCUMENT, "doc")
    assert found is not None
    assert len(found) == len(set(found)) == len(rdflib_reads(DOCUMENT))
    assert isomorphic(graph_of(found), rdflib_reads(DOCUMENT))
    assert (URIRef("http://ex.org/a"), URIRef("http://ex.org/p"), Literal("tab\there \"quoted\" é 😀", lang="en-GB")) in found
    x, y = [t[0] for t in found if isinstance(t[0], BNode)]
    assert x != y and (x, URIRef("http://ex.org/p"), y) in found


def test_bytes_and_repeated_names_are_one_object() -> None:
    found = ntriples.parse(DOCUMENT.encode(), "doc")
    assert found is not None
    subjects = [s for s, _p, _o in found if s == URIRef("http://ex.org/a")]
    assert len(subjects) > 1 and all(s is subjects[0] for s in subjects)


def test_blank_nodes_are_fresh_per_document() -> None:
    first, second = ntriples.parse("_:x <http://ex.org/p> <http://ex.org/o> .", "a"), \
        ntriples.parse("_:x <http://ex.org/p> <http://ex.org/o> .", "b")
    assert first is not None and second is not None
    assert first[0][0] != second[0][0]


@pytest.mark.parametrize("line", [
    "<http://ex.org/a> <http://ex.org/p> <http://ex.org/b>",  # no dot
    "<http://ex.org/a> <http://ex.org/p> <http://ex.org/b> . trailing",
    '<http://ex.org/a> <http://ex.org/p> "unterminated .',
    "<http://ex.org/a> _:p <http://ex.org/b> .",  # a blank predicate
    "<relative> <http://ex.org/p> <http://ex.org/b> .",
    '"literal" <http://ex.org/p> <http://ex.org/b> .',
    "<http://ex.org/a> <http://ex.org/p> <http://ex.org/b> .\f",
    "\ufeff<http://ex.org/a> <http://ex.org/p> <http://ex.org/b> .",
    "<http://ex.org/a> <http://ex.org/p> 'single' .",
])
def test_what_it_does_not_read_is_left_to_rdflib(line: str) -> None:
    assert ntriples.parse(line, "doc") is None
    try:
        expected = ("read", set(rdflib_reads(line)))
    except Exception as exc:  # noqa: BLE001 - whatever rdflib raises, the KB must say the same
        expected = ("error", type(exc).__name__)
    try:
        got = ("read", set(parse_data(line, "nt")))
    except KbError as exc:
        got = ("error", type(exc.__cause__).__name__ if exc.__cause__ else type(exc).__name__)
    if expected[0] == "read":
        assert got[0] == "read" and isomorphic(graph_of(tuple(got[1])), graph_of(tuple(expected[1])))
    else:
        assert got[0] == "error"


def test_invalid_utf8_and_lone_surrogates_keep_rdflibs_refusal() -> None:
    assert ntriples.parse(b"<http://ex.org/a> <http://ex.org/p> \"\xff\" .", "doc") is None
    with pytest.raises(KbError, match="cannot parse"):
        parse_data(b"<http://ex.org/a> <http://ex.org/p> \"\xff\" .", "nt")
    assert ntriples.parse('<http://ex.org/a> <http://ex.org/p> "\ud800" .', "doc") is None
    with pytest.raises(KbError):
        parse_data('<http://ex.org/a> <http://ex.org/p> "\\ud800" .', "nt")


def test_a_load_is_the_same_kb_either_way() -> None:
    document = DOCUMENT.replace("_:x", "<http://ex.org/x>").replace("_:y", "<http://ex.org/y>")
    with KB() as fast, KB() as slow:
        fast.load_data(document, "nt")
        slow.load_data(rdflib_reads(document).serialize(format="turtle"), "turtle")
        # Compared by lines: an export's order follows the store's history, not only its triples.
        assert sorted(fast.export("nt", inferred=True).splitlines()) == sorted(
            slow.export("nt", inferred=True).splitlines()
        )


_iris = st.sampled_from(["http://ex.org/a", "http://ex.org/b", "urn:x:é", "http://ex.org/p#q",
                         "http://ex.org/a(b)", "mailto:x@y"])
# Any text the KB takes: no lone surrogate, nothing RDF/XML cannot carry (kb.unicode).
_texts = st.text(st.characters(exclude_categories=("Cs",)), max_size=12).map(carried)
_literals = st.one_of(
    st.builds(Literal, _texts),
    st.builds(lambda t, lang: Literal(t, lang=lang), _texts, st.sampled_from(["en", "fr-BE", "zh-Hant-TW"])),
    st.builds(lambda n: Literal(n), st.integers()),
    st.builds(lambda x: Literal(x), st.floats(allow_nan=False)),
    st.builds(lambda b: Literal(b), st.booleans()),
)
_objects = st.one_of(_iris.map(URIRef), _literals, st.sampled_from(["b1", "b2"]).map(BNode))
_triples = st.lists(st.tuples(st.one_of(_iris.map(URIRef), st.sampled_from(["b1", "b2"]).map(BNode)),
                              _iris.map(URIRef), _objects), max_size=12)


@settings(max_examples=150, deadline=None)
@given(_triples, st.sampled_from(["\n", "\r\n", "\r"]), st.sampled_from([" ", "\t", "  \t"]))
def test_any_document_rdflib_writes_reads_the_same(triples: list[Triple], newline: str, space: str) -> None:
    graph = graph_of(tuple(triples))
    text = graph.serialize(format="nt")
    text = newline.join(line.replace("> <", f">{space}<", 1) for line in text.split("\n"))
    found = ntriples.parse(text, "doc")
    assert found is not None
    assert isomorphic(graph_of(found), rdflib_reads(text))
