"""``kb.records``: journal statements read back to the very triples written, by the fast path for
names and blank nodes as by the tokenizer, and corrupt ones refused."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st
from rdflib import BNode, Literal, URIRef

from kb.errors import KbError
from kb.records import nt, parse_nt
from kb.terms import Triple

_names = st.sampled_from(["http://kb.openrobots.org#cup_1", "http://ex.org/a(b)", "urn:x:é",
                          "https://dbpedia.org/resource/Table_(furniture)"]).map(URIRef)
_objects = st.one_of(_names, st.sampled_from(["b1", "n0abc"]).map(BNode),
                     st.text(st.characters(exclude_categories=("Cs",)), max_size=8).map(Literal),
                     st.integers().map(Literal))


@given(st.tuples(st.one_of(_names, st.sampled_from(["b1"]).map(BNode)), _names, _objects))
def test_a_written_statement_reads_back_the_same(triple: Triple) -> None:
    bnodes: dict[str, BNode] = {}
    assert parse_nt(nt(triple), bnodes) == triple


def test_the_fast_path_gives_what_the_tokenizer_gives() -> None:
    from kb.records import _node
    from kb.terms import tokenize

    for statement in ["<http://ex.org/a> <http://ex.org/p> <http://ex.org/b>",
                      "_:x <http://ex.org/p> _:y", "<http://ex.org/a>\t<http://ex.org/p>  <urn:x>"]:
        fast = parse_nt(statement, {})
        slow = tuple(_node(token, {}) for token in tokenize(statement))
        assert fast == slow


@pytest.mark.parametrize("statement", [
    "<http://ex.org/a> <http://ex.org/p>",
    "<http://ex.org/a> <http://ex.org/p> <http://ex.org/b> <http://ex.org/c>",
    "<http://ex.org/a>x <http://ex.org/p> <http://ex.org/b>",
    "<not an iri> <http://ex.org/p> <http://ex.org/b>",
    "<relative> <http://ex.org/p> <http://ex.org/b>",
])
def test_corrupt_statements_are_refused(statement: str) -> None:
    with pytest.raises(KbError):
        parse_nt(statement, {})
