"""``kb.arguments.render``: rows as dicts of output values, sorted by their text whatever the
values (names, numbers, booleans), with each term's output form made once per cache."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st
from rdflib import Literal, URIRef

from kb import terms
from kb.arguments import render
from kb.query import build_query
from kb.terms import ORO, Node, parse_patterns

_terms = st.one_of(
    st.sampled_from(["cup_1", "cup_10", "Cup_2", "table", "é_1", "a(b)"]).map(lambda n: URIRef(ORO + n)),
    st.sampled_from(["http://ex.org/z", "https://dbpedia.org/resource/Cup"]).map(URIRef),
    st.integers(-20, 20).map(Literal),
    st.booleans().map(Literal),
    st.text(max_size=4).map(Literal),
)


def _text(row: tuple[object, ...]) -> tuple[str, ...]:
    return tuple(str(v) for v in row)


def _typed(row: tuple[object, ...]) -> tuple[tuple[str, object], ...]:
    return tuple((type(v).__name__, v) for v in row)  # 0 and False are different values here


@given(st.lists(st.tuples(_terms, _terms), max_size=20))
def test_rows_sort_by_their_text(rows: list[tuple[Node, Node]]) -> None:
    query = build_query(parse_patterns(["?a sees ?b"]))
    got = [(r["a"], r["b"]) for r in render(query, set(rows))]
    assert got == sorted(got, key=_text)
    assert sorted(map(_typed, got), key=repr) == \
        sorted((_typed((terms.shorten(a), terms.shorten(b))) for a, b in set(rows)), key=repr)


@given(st.lists(_terms, max_size=20))
def test_one_column(values: list[Node]) -> None:
    query = build_query(parse_patterns(["myself sees ?x"]))
    got = [(r["x"],) for r in render(query, {(v,) for v in values})]
    assert got == sorted(got, key=_text)
    assert sorted(map(_typed, got), key=repr) == sorted((_typed((terms.shorten(v),)) for v in set(values)), key=repr)


def test_the_cache_is_filled_once_and_used() -> None:
    query = build_query(parse_patterns(["myself sees ?x"]))
    cup = URIRef(ORO + "cup_1")
    cache: dict[Node, object] = {}
    assert render(query, {(cup,)}, cache) == [{"x": "cup_1"}]
    assert cache == {cup: "cup_1"}
    cache[cup] = "from the cache"
    assert render(query, {(cup,)}, cache) == [{"x": "from the cache"}]
