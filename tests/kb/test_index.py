"""``kb.index.TripleIndex``: the three access paths, exact counts, and clean removal.

Every pattern shape is checked against a brute-force filter of a plain Python set, and a
hypothesis state sequence of adds and removes keeps the index equal to that set.
"""

from __future__ import annotations

import itertools

import pytest
from hypothesis import given
from hypothesis import strategies as st
from rdflib import Literal, URIRef

from kb.index import TripleIndex
from kb.terms import Node

EX = "http://example.org/"


def u(name: str) -> URIRef:
    return URIRef(EX + name)


A, B, C, D = u("a"), u("b"), u("c"), u("d")
KNOWS, SEES, AGE = u("knows"), u("sees"), u("age")
TRIPLES: list[tuple[Node, Node, Node]] = [
    (A, KNOWS, B),
    (A, KNOWS, C),
    (B, KNOWS, C),
    (A, SEES, C),
    (C, SEES, A),
    (A, AGE, Literal(42)),
    (B, AGE, Literal(42)),
    (D, SEES, D),
]


@pytest.fixture
def index() -> TripleIndex:
    idx = TripleIndex()
    for t in TRIPLES:
        idx.add(*t)
    return idx


def brute(s: object, p: object, o: object) -> set[tuple[object, object, object]]:
    return {
        t
        for t in TRIPLES
        if (s is None or t[0] == s) and (p is None or t[1] == p) and (o is None or t[2] == o)
    }


TERMS_S = [None, A, B, D, u("missing")]
TERMS_P = [None, KNOWS, SEES, AGE, u("nopred")]
TERMS_O = [None, C, A, Literal(42), u("missing")]
PATTERNS = list(itertools.product(TERMS_S, TERMS_P, TERMS_O))


@pytest.mark.parametrize(("s", "p", "o"), PATTERNS)
def test_triples_and_count_match_brute_force(index: TripleIndex, s: object, p: object, o: object) -> None:
    found = list(index.triples(s, p, o))  # type: ignore[arg-type]
    assert len(found) == len(set(found))
    assert set(found) == brute(s, p, o)
    assert index.count(s, p, o) == len(found)  # type: ignore[arg-type]


def test_len_contains_iter(index: TripleIndex) -> None:
    assert len(index) == len(TRIPLES)
    assert set(index) == set(TRIPLES)
    assert (A, KNOWS, B) in index
    assert (B, KNOWS, A) not in index
    assert (u("zz"), KNOWS, B) not in index


def test_add_and_remove_report_change(index: TripleIndex) -> None:
    assert index.add(A, KNOWS, B) is False
    assert index.add(B, KNOWS, A) is True
    assert len(index) == len(TRIPLES) + 1
    assert index.remove(B, KNOWS, A) is True
    assert index.remove(B, KNOWS, A) is False
    assert index.remove(u("zz"), KNOWS, A) is False
    assert index.remove(A, u("zz"), A) is False
    assert len(index) == len(TRIPLES)


def test_point_access(index: TripleIndex) -> None:
    assert index.objects(A, KNOWS) == {B, C}
    assert index.subjects(KNOWS, C) == {A, B}
    assert index.predicates(A, C) == {KNOWS, SEES}
    assert index.objects(u("zz"), KNOWS) == set()
    assert index.subjects(u("zz"), C) == set()
    assert index.predicates(u("zz"), C) == set()
    assert index.has_subject_predicate(A, AGE)
    assert not index.has_subject_predicate(C, AGE)
    assert index.has_predicate_object(AGE, Literal(42))
    assert not index.has_predicate_object(AGE, Literal(43))
    assert index.out_edges(A) == {KNOWS: {B, C}, SEES: {C}, AGE: {Literal(42)}}
    assert index.in_edges(C) == {A: {KNOWS, SEES}, B: {KNOWS}}
    assert index.by_predicate(SEES) == {C: {A}, A: {C}, D: {D}}


def test_term_sets(index: TripleIndex) -> None:
    assert set(index.subject_terms()) == {A, B, C, D}
    assert set(index.predicate_terms()) == {KNOWS, SEES, AGE}
    assert set(index.object_terms()) == {A, B, C, D, Literal(42)}
    assert index.is_subject(D) and not index.is_subject(Literal(42))
    assert index.is_predicate(AGE) and not index.is_predicate(A)
    assert index.is_object(Literal(42)) and not index.is_object(AGE)


def test_removal_drops_empty_entries(index: TripleIndex) -> None:
    index.remove(D, SEES, D)
    assert not index.is_subject(D)
    assert not index.is_object(D)
    assert index.out_edges(D) == {}
    assert index.in_edges(D) == {}
    for s, p, o in list(TRIPLES):
        index.remove(s, p, o)
    assert len(index) == 0
    assert list(index) == []
    assert list(index.predicate_terms()) == []
    assert index.count(None, SEES, None) == 0


def test_removing_while_iterating_a_pattern_is_safe(index: TripleIndex) -> None:
    for s, p, o in index.triples(A, None, None):
        index.remove(s, p, o)
    for s, p, o in index.triples(None, SEES, None):
        index.remove(s, p, o)
    assert set(index) == {(B, KNOWS, C), (B, AGE, Literal(42))}


def test_clear(index: TripleIndex) -> None:
    index.clear()
    assert len(index) == 0
    assert index.count(None, None, None) == 0
    assert index.add(A, KNOWS, B)
    assert list(index) == [(A, KNOWS, B)]


# --- hypothesis: the index behaves as a set ---------------------------------------------------

small_terms = st.sampled_from([A, B, C, D])
small_preds = st.sampled_from([KNOWS, SEES])
ops = st.lists(st.tuples(st.booleans(), small_terms, small_preds, small_terms), max_size=60)


@given(ops)
def test_index_equals_a_set_after_any_operation_sequence(
    sequence: list[tuple[bool, URIRef, URIRef, URIRef]],
) -> None:
    index = TripleIndex()
    model: set[tuple[URIRef, URIRef, URIRef]] = set()
    for is_add, s, p, o in sequence:
        if is_add:
            assert index.add(s, p, o) == ((s, p, o) not in model)
            model.add((s, p, o))
        else:
            assert index.remove(s, p, o) == ((s, p, o) in model)
            model.discard((s, p, o))
    assert set(index) == model
    assert len(index) == len(model)
    for qs, qp, qo in itertools.product([None, A, C], [None, KNOWS], [None, B, D]):
        expected = {
            t for t in model
            if (qs is None or t[0] == qs) and (qp is None or t[1] == qp) and (qo is None or t[2] == qo)
        }
        assert set(index.triples(qs, qp, qo)) == expected
        assert index.count(qs, qp, qo) == len(expected)
